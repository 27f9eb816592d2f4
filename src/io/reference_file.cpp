#include "prt/io/reference_file.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

#include <nlohmann/json.hpp>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/hash.hpp"
#include "prt/core/json.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/texel_sampling.hpp"

namespace prt::io {

namespace {

constexpr const char* kFormat = "prtkit-reference";

Json triples(const std::vector<Rgb>& v) {
  Json out = Json::array();
  for (const Rgb& c : v) out.push_back(jsonFloats(&c.x, 3));
  return out;
}

}  // namespace

std::string lightmapUvFingerprint(const Mesh& mesh) {
  Fnv1a f;
  const std::uint64_t n = mesh.lightmapUvs.size();
  f.add(&n, sizeof n);
  if (n) f.add(mesh.lightmapUvs.data(), n * sizeof(Vec2f));
  return f.hex();
}

std::string environmentFingerprint(const envmap::Environment& env) {
  Fnv1a f;
  const auto kind = static_cast<int>(env.kind());
  f.add(&kind, sizeof kind);
  const std::uint64_t n = env.texelCount();
  f.add(&n, sizeof n);
  for (std::size_t k = 0; k < n; ++k) {
    const envmap::Texel t = env.texel(k);
    f.add(&t.radiance, sizeof t.radiance);
  }
  // Along fixed directions as well: an analytic sky's sun and smooth part are not texels.
  for (int i = 0; i < 64; ++i) {
    const double z = 1 - (2 * i + 1) / 64.0, r = std::sqrt(1 - z * z), phi = 2.399963 * i;
    const Rgb v = env.lookup(Vec3f(Vec3d(r * std::cos(phi), z, r * std::sin(phi))));
    f.add(&v, sizeof v);
  }
  return f.hex();
}

void writeReferenceJson(const std::string& path, const ReferenceFile& r) {
  Json j;
  j["format"] = kFormat;
  j["formatVersion"] = kReferenceFormatVersion;
  j["prtkitVersion"] = r.prtkitVersion;
  j["bake"] = {{"file", r.bakeFile}, {"vertices", r.meshVertices}, {"fingerprint", r.meshFingerprint}};
  if (r.texels())
    j["bake"]["lightmap"] = {{"width", r.lightmapWidth},
                             {"height", r.lightmapHeight},
                             {"uvFingerprint", r.lightmapUvFingerprint}};
  j["light"] = {{"source", r.lightSource},
                {"fingerprint", r.environmentFingerprint},
                {"rotation", r.rotation}};
  j["mode"] = r.mode;
  j["bounces"] = r.bounces;
  j["material"] = r.material;
  if (r.eye) j["eye"] = jsonFloats(&r.eye->x, 3);
  j["samples"] = r.samples;
  j["seed"] = r.seed;
  j["mis"] = r.mis;
  j["rays"] = r.rays;  // no timings: the same run writes the same file
  j[r.texels() ? "texels" : "vertices"] = r.vertices;
  j["radiance"] = triples(r.radiance);
  j["stdError"] = triples(r.stdError);
  writeFileAtomically(path, formatJson(j));
}

void writeReferenceBinary(const std::string& path, const ReferenceFile& r) {
  std::string out("PRTREF1", 8);
  const auto put32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
  };
  const auto putF = [&](float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    put32(u);
  };
  put32(static_cast<std::uint32_t>(r.vertices.size()));
  for (std::size_t i = 0; i < r.vertices.size(); ++i) {
    put32(r.vertices[i]);
    for (float f : {r.radiance[i].x, r.radiance[i].y, r.radiance[i].z, r.stdError[i].x,
                    r.stdError[i].y, r.stdError[i].z})
      putF(f);
  }
  writeFileAtomically(path, out);
}

ReferenceFile readReferenceJson(const std::string& path) {
  const std::vector<unsigned char> bytes = readFileBytes(path);
  return parseReferenceJson(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

ReferenceFile parseReferenceJson(std::string_view text, const std::string& path) {
  nlohmann::json j = parseJsonText(text, path);  // not const: operator[] on a missing key is null
  if (!j.is_object()) throw Error(path, "expected a JSON object");
  if (!j.contains("format")) {
    if (j.contains("radiance"))
      throw Error(path, "a reference file from before formatVersion 1: it does not say which "
                        "bake and environment it is for; run prt reference again");
    throw Error(path, "not a prtkit reference file (no \"format\")");
  }
  if (j["format"] != kFormat) throw Error(path, "not a prtkit reference file (\"format\")");
  if (!j.contains("formatVersion") || !j["formatVersion"].is_number_integer() ||
      j["formatVersion"].get<long long>() != kReferenceFormatVersion)
    throw Error(path, "reference format version " +
                          (j.contains("formatVersion") ? j["formatVersion"].dump() : "missing") +
                          " (this prt reads " + std::to_string(kReferenceFormatVersion) + ")");
  const auto member = [&](const nlohmann::json& o, const char* key,
                          const char* where) -> const nlohmann::json& {
    if (!o.is_object() || !o.contains(key))
      throw Error(path, std::string("missing \"") + key + "\"" + where);
    return o[key];
  };
  const auto str = [&](const nlohmann::json& o, const char* key, const char* where = "") {
    const nlohmann::json& v = member(o, key, where);
    if (!v.is_string()) throw Error(path, std::string("\"") + key + "\" must be a string");
    return v.get<std::string>();
  };
  const auto uint = [&](const nlohmann::json& o, const char* key, std::uint64_t max) {
    const nlohmann::json& v = member(o, key, "");
    if (!v.is_number_unsigned() || v.get<std::uint64_t>() > max)
      throw Error(path, std::string("\"") + key + "\" must be an integer 0.." + std::to_string(max));
    return v.get<std::uint64_t>();
  };
  ReferenceFile r;
  if (j.contains("prtkitVersion") && j["prtkitVersion"].is_string())
    r.prtkitVersion = j["prtkitVersion"].get<std::string>();
  const nlohmann::json& bake = member(j, "bake", "");
  r.bakeFile = str(bake, "file", " in \"bake\"");
  r.meshFingerprint = str(bake, "fingerprint", " in \"bake\"");
  r.meshVertices = uint(bake, "vertices", limits().maxVertices);
  if (bake.contains("lightmap")) {
    const nlohmann::json& lm = bake["lightmap"];
    r.lightmapWidth = int(uint(lm, "width", kMaxLightmapSide));
    r.lightmapHeight = int(uint(lm, "height", kMaxLightmapSide));
    if (r.lightmapWidth < 1 || r.lightmapHeight < 1)
      throw Error(path, "\"lightmap\" must be at least 1 x 1 texels");
    r.lightmapUvFingerprint = str(lm, "uvFingerprint", " in \"lightmap\"");
  }
  const nlohmann::json& light = member(j, "light", "");
  r.lightSource = str(light, "source", " in \"light\"");
  r.environmentFingerprint = str(light, "fingerprint", " in \"light\"");
  const nlohmann::json& rot = member(light, "rotation", " in \"light\"");
  if (!rot.is_array() || rot.size() != 9)
    throw Error(path, "\"rotation\" must be 9 numbers (a row-major 3x3 matrix)");
  for (std::size_t k = 0; k < 9; ++k) {
    if (!rot[k].is_number()) throw Error(path, "\"rotation\" must be 9 numbers");
    r.rotation[k] = rot[k].get<double>();
  }
  r.mode = str(j, "mode");
  r.material = str(j, "material");
  r.mis = str(j, "mis");
  r.bounces = static_cast<int>(uint(j, "bounces", 1000));
  r.samples = static_cast<int>(uint(j, "samples", 1u << 30));
  r.seed = uint(j, "seed", ~std::uint64_t{0});
  r.rays = uint(j, "rays", ~std::uint64_t{0});
  if (j.contains("seconds") && j["seconds"].is_number()) r.seconds = j["seconds"].get<double>();
  if (j.contains("eye")) {
    const nlohmann::json& e = j["eye"];
    if (!e.is_array() || e.size() != 3 || !e[0].is_number() || !e[1].is_number() ||
        !e[2].is_number())
      throw Error(path, "\"eye\" must be [x, y, z]");
    r.eye = Vec3f(e[0].get<float>(), e[1].get<float>(), e[2].get<float>());
    if (!isFinite(*r.eye)) throw Error(path, "\"eye\" is not finite");
  }
  const char* rows = r.texels() ? "texels" : "vertices";
  const char* row = r.texels() ? "texel" : "vertex";
  const nlohmann::json& vs = member(j, rows, "");
  const nlohmann::json& rad = member(j, "radiance", "");
  const nlohmann::json& err = member(j, "stdError", "");
  if (!vs.is_array() || !rad.is_array() || !err.is_array() || rad.size() != vs.size() ||
      err.size() != vs.size())
    throw Error(path, std::string("\"") + rows +
                          "\", \"radiance\" and \"stdError\" must be arrays of one length");
  const std::size_t bound = r.rowCount();
  if (vs.size() > bound)
    throw Error(path, std::to_string(vs.size()) + " " + rows + " for " +
                          (r.texels() ? "a lightmap of " : "a mesh of ") + std::to_string(bound));
  r.vertices.reserve(vs.size());
  r.radiance.reserve(vs.size());
  r.stdError.reserve(vs.size());
  const auto rgb = [&](const nlohmann::json& v, const char* what, std::size_t i) {
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
        !v[2].is_number())
      throw Error(path, std::string(what) + " " + std::to_string(i) + " is not [r, g, b]");
    const Rgb c(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
    if (!isFinite(c)) throw Error(path, std::string(what) + " " + std::to_string(i) + " is not finite");
    return c;
  };
  for (std::size_t i = 0; i < vs.size(); ++i) {
    if (!vs[i].is_number_unsigned() || vs[i].get<std::uint64_t>() >= bound)
      throw Error(path, std::string(row) + " entry " + std::to_string(i) + " is not a " + row +
                            " index below " + std::to_string(bound));
    const auto v = static_cast<std::uint32_t>(vs[i].get<std::uint64_t>());
    if (i > 0 && v <= r.vertices.back())
      throw Error(path, std::string("the ") + rows + " must be ascending (entry " +
                            std::to_string(i) + ")");
    r.vertices.push_back(v);
    r.radiance.push_back(rgb(rad[i], "radiance", i));
    r.stdError.push_back(rgb(err[i], "stdError", i));
  }
  return r;
}

void ReferenceFile::setRows(const Mesh& mesh, const TransferShape& shape) {
  const bool perTexel = shape.domain == TransferDomain::Texels;
  lightmapWidth = perTexel ? shape.lightmap.width : 0;
  lightmapHeight = perTexel ? shape.lightmap.height : 0;
  lightmapUvFingerprint = perTexel ? io::lightmapUvFingerprint(mesh) : std::string();
}

}  // namespace prt::io
