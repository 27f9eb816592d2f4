#include "bake_schema.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/sh/convolve.hpp"

namespace prt::io::schema {

void Reader::fail(const std::string& msg) const {
  throw Error(name_, msg);
}

const json& Reader::member(const json& obj, const std::string& key,
                           const std::string& where) const {
  if (!obj.is_object() || !obj.contains(key)) fail(where + " lacks '" + key + "'");
  return obj[key];
}

double Reader::number(const json& obj, const std::string& key, const std::string& where) const {
  const json& v = member(obj, key, where);
  if (!v.is_number()) fail(where + "." + key + " is not a number");
  return v.get<double>();
}

double Reader::numberOr(const json& obj, const std::string& key, double fallback,
                        const std::string& where) const {
  return has(obj, key) ? number(obj, key, where) : fallback;
}

std::uint64_t Reader::integer(const json& obj, const std::string& key, const std::string& where,
                              double lo, double hi) const {
  const json& v = member(obj, key, where);
  const std::string at = where + "." + key;
  std::uint64_t n = 0;
  if (v.is_string()) {  // large seeds
    const std::string& s = v.get_ref<const std::string&>();
    if (s.empty() || s.size() > 20 ||
        !std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); }))
      fail(at + " is not an integer");
    if (s.size() == 20 && s > "18446744073709551615")
      fail(at + " = " + s + " is larger than 2^64 - 1");
    n = std::stoull(s);
  } else if (v.is_number_unsigned()) {
    n = v.get<std::uint64_t>();
  } else if (v.is_number()) {
    const double x = v.get<double>();
    if (!(x == std::floor(x)) || x < 0 || x >= 18446744073709551616.0)
      fail(at + " = " + v.dump() + " is not a non-negative integer");
    n = static_cast<std::uint64_t>(x);
  } else {
    fail(at + " is not an integer");
  }
  if (static_cast<double>(n) < lo || static_cast<double>(n) > hi)
    fail(at + " = " + std::to_string(n) + " is out of range");
  return n;
}

std::string Reader::string(const json& obj, const std::string& key,
                           const std::string& where) const {
  const json& v = member(obj, key, where);
  if (!v.is_string()) fail(where + "." + key + " is not a string");
  return v.get<std::string>();
}

bool Reader::boolean(const json& obj, const std::string& key, const std::string& where) const {
  const json& v = member(obj, key, where);
  if (!v.is_boolean()) fail(where + "." + key + " is not true or false");
  return v.get<bool>();
}

json exactInteger(std::uint64_t n) {
  if (n < (std::uint64_t(1) << 53)) return n;
  return std::to_string(n);
}

namespace {

/// A float as the double of its shortest decimal form, so that the file says 0.4, not
/// 0.4000000059604645, and still reads back as exactly the same float.
double shortest(float x) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  double d = 0;
  std::from_chars(buf, end, d);
  return d;
}

json rgb(const Rgb& c) {
  return json::array({shortest(c.x), shortest(c.y), shortest(c.z)});
}

Rgb readRgb(const json& v, const std::string& where, const Reader& r, double lo, double hi) {
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    r.fail(where + " is not three numbers");
  Rgb c;
  for (int k = 0; k < 3; ++k) {
    const double x = v[k].get<double>();
    if (!(x >= lo && x <= hi))
      r.fail(where + "[" + std::to_string(k) + "] = " + v[k].dump() + " is outside " +
             json(lo).dump() + ".." + json(hi).dump());
    c[k] = static_cast<float>(x);
  }
  return c;
}

}  // namespace

json materialJson(const Material& m) {
  json o;
  switch (m.lobe.kind) {
    case LobeKind::None:
      o["type"] = "lambert";
      break;
    case LobeKind::Phong:
      o["type"] = "phong";
      o["exponent"] = m.lobe.exponent;
      break;
    case LobeKind::Ggx:
      o["type"] = "ggx";
      o["roughness"] = m.lobe.roughness;
      break;
  }
  if (m.lobe.kind != LobeKind::None) o["ks"] = rgb(m.specular);
  if (m.diffuse) o["kd"] = rgb(*m.diffuse);
  return o;
}

Material readMaterial(const json& v, const std::string& where, const Reader& r) {
  if (v.is_string())  // versions 2–3: the --material spec string
    return r.within(where, [&] { return parseMaterial(v.get<std::string>()); });
  if (!v.is_object()) r.fail(where + " is neither a material object nor a spec string");
  Material m;
  const std::string type = r.string(v, "type", where);
  const auto bounded = [&](const char* key, double lo, double hi) {
    const double x = r.number(v, key, where);
    if (!(x >= lo && x <= hi))
      r.fail(where + "." + key + " = " + json(x).dump() + " is outside " + json(lo).dump() + ".." +
             json(hi).dump());
    return x;
  };
  if (type == "lambert") {
    m.lobe.kind = LobeKind::None;
  } else if (type == "phong") {
    m.lobe.kind = LobeKind::Phong;
    m.lobe.exponent = bounded("exponent", 0.0, kMaxPhongExponent);
  } else if (type == "ggx") {
    m.lobe.kind = LobeKind::Ggx;
    m.lobe.roughness = bounded("roughness", kMinGgxRoughness, 1.0);
  } else {
    r.fail(where + ".type '" + type.substr(0, 40) + "' is unknown (lambert, phong or ggx)");
  }
  if (m.lobe.kind != LobeKind::None)
    m.specular = readRgb(r.member(v, "ks", where), where + ".ks", r, 0.0, 1.0);
  if (r.has(v, "kd")) m.diffuse = readRgb(v["kd"], where + ".kd", r, 0.0, 1.0);
  return m;
}

json responseJson(const Material& m, int bands) {
  const std::vector<double> a = sh::clampedCosineKernel(bands);
  const std::vector<double> g = m.glossy() ? m.lobe.zonal(bands) : std::vector<double>(a.size());
  json diffuse = json::array(), lobe = json::array();
  for (int l = 0; l < bands; ++l) {
    diffuse.push_back(a[l] / kPi);
    lobe.push_back(g[l]);
  }
  return {{"diffuse", std::move(diffuse)}, {"lobe", std::move(lobe)}};
}

json settingsJson(const TransferShape& shape, const BakeRecipe& recipe) {
  json o = {{"mode", toString(recipe.mode)},
            {"layout", toString(shape.layout)},
            {"domain", toString(shape.domain)},
            {"bands", shape.bands},
            {"channels", shape.channels},
            {"samples", recipe.samples},
            {"bounces", recipe.bounces},
            {"seed", exactInteger(recipe.seed)},
            {"sampling", toString(recipe.sampling)},
            {"material", materialJson(recipe.material)}};
  if (recipe.adaptive()) o["targetError"] = recipe.targetError;
  if (shape.isHaar()) {
    o.erase("bands");
    o["basis"] = toString(shape.basis);
    o["haar"] = {{"resolution", shape.haar.resolution}, {"terms", shape.haar.terms}};
    if (shape.haar.bounceBands > 0) o["haar"]["bounceBands"] = shape.haar.bounceBands;
  }
  return o;
}

void readSettings(const json& o, const std::string& where, int version, const Reader& r,
                  BakeRecipe& recipe, TransferShape& shape) {
  if (!o.is_object()) r.fail(where + " is not an object");
  recipe.mode = r.within(where, [&] { return parseTransferMode(r.string(o, "mode", where)); });
  recipe.sampling = r.within(where, [&] { return parseSampling(r.string(o, "sampling", where)); });
  recipe.samples = static_cast<int>(r.integer(o, "samples", where, 1, kMaxBakeSamples));
  recipe.bounces = static_cast<int>(r.integer(o, "bounces", where, 0, kMaxBounces));
  recipe.seed = r.integer(o, "seed", where);
  if (r.has(o, "targetError")) recipe.targetError = r.number(o, "targetError", where);
  shape.layout =
      r.has(o, "layout")
          ? r.within(where, [&] { return parseTransferLayout(r.string(o, "layout", where)); })
          : TransferLayout::Vector;
  if (shape.layout == TransferLayout::Matrix && version < 2)
    r.fail(where + " is a matrix transfer in a version " + std::to_string(version) +
           " file (matrices need version 2)");
  shape.domain =
      r.has(o, "domain")
          ? r.within(where, [&] { return parseTransferDomain(r.string(o, "domain", where)); })
          : TransferDomain::Vertices;
  shape.basis = r.has(o, "basis") ? r.within(where, [&] {
    return parseTransferBasis(r.string(o, "basis", where));
  })
                                  : TransferBasis::SphericalHarmonics;
  shape.channels = static_cast<int>(r.integer(o, "channels", where, 1, 3));
  if (shape.channels == 2) r.fail(where + ".channels must be 1 or 3");
  if (shape.isHaar()) {
    if (version < prt::kFirstHaarVersion)
      r.fail(where + " is Haar transfer in a version " + std::to_string(version) +
             " file (Haar needs version " + std::to_string(kFirstHaarVersion) + ")");
    const std::string hw = where + ".haar";
    const json& h = r.member(o, "haar", where);
    if (!h.is_object()) r.fail(hw + " is not an object");
    shape.bands = 0;
    shape.haar.resolution =
        static_cast<int>(r.integer(h, "resolution", hw, haar::kMinResolution, haar::kMaxResolution));
    shape.haar.terms = static_cast<int>(r.integer(
        h, "terms", hw, 1, static_cast<double>(haar::coefficientCount(shape.haar.resolution))));
    if (r.has(h, "bounceBands")) {
      if (version < prt::kFirstHaarBounceVersion)
        r.fail(hw + " holds a bounce in a version " + std::to_string(version) +
               " file (inter-reflected Haar needs version " +
               std::to_string(kFirstHaarBounceVersion) + ")");
      shape.haar.bounceBands =
          static_cast<int>(r.integer(h, "bounceBands", hw, 1, haar::kUnshadowedBands));
    }
    // A row holds a bounce exactly when its transfer bounced light.
    if ((shape.haar.bounceBands > 0) != (effectiveBounces(recipe.mode, recipe.bounces) > 0))
      r.fail(hw + (shape.haar.bounceBands > 0 ? " holds a bounce, but the transfer is " +
                                                    std::string(toString(recipe.mode)) + " with " +
                                                    std::to_string(recipe.bounces) + " bounces"
                                              : ".bounceBands is missing: the transfer is "
                                                "inter-reflected with " +
                                                    std::to_string(recipe.bounces) + " bounces"));
    r.within(where, [&] { shape.check(where); });
  } else {
    shape.bands = static_cast<int>(r.integer(o, "bands", where, 1, bands::kMaxLibrary));
  }
  if (r.has(o, "material")) recipe.material = readMaterial(o["material"], where + ".material", r);
  // Versions 1–3 kept a uniform bounce albedo apart from the material.
  if (r.has(o, "albedo"))
    recipe.material.diffuse = readRgb(o["albedo"], where + ".albedo", r, 0.0, 1.0);
  // Whatever form it came in, the material meets the ranges bake() and --material hold it to.
  r.within(where, [&] { checkRecipe(recipe); });
}

json statsJson(const BakeStats& s) {
  json o = {{"rays", s.rays},
            {"raysPerSecond", s.raysPerSecond},
            {"secondsTotal", s.secondsTotal},
            {"secondsDirect", s.secondsDirect},
            {"threads", s.threads},
            {"vertices", s.vertices},
            {"stdErrT0Mean", s.stdErrT0Mean},
            {"stdErrT0Max", s.stdErrT0Max},
            {"stdErrConstMean", s.stdErrConstMean},
            {"stdErrConstMax", s.stdErrConstMax}};
  if (!s.secondsBounce.empty()) o["secondsBounce"] = s.secondsBounce;
  if (!s.raysBounce.empty()) o["raysBounce"] = s.raysBounce;
  return o;
}

BakeStats readStats(const json& o, const std::string& where, const Reader& r) {
  BakeStats s;
  if (!o.is_object()) return s;
  const auto num = [&](const char* key) {
    return o.contains(key) && o[key].is_number() ? o[key].get<double>() : 0.0;
  };
  const auto count = [&](const json& v) -> std::uint64_t {
    if (v.is_number_unsigned()) return v.get<std::uint64_t>();
    if (v.is_number()) {
      const double x = v.get<double>();
      return x >= 0 && x < 1.8e19 ? static_cast<std::uint64_t>(x) : 0;
    }
    return 0;
  };
  s.rays = o.contains("rays") ? count(o["rays"]) : 0;
  s.raysPerSecond = num("raysPerSecond");
  s.secondsTotal = num("secondsTotal");
  s.secondsDirect = num("secondsDirect");
  if (o.contains("secondsBounce") && o["secondsBounce"].is_array())
    for (const json& x : o["secondsBounce"])
      s.secondsBounce.push_back(x.is_number() ? x.get<double>() : 0.0);
  if (o.contains("raysBounce") && o["raysBounce"].is_array())
    for (const json& x : o["raysBounce"]) s.raysBounce.push_back(count(x));
  s.threads = static_cast<int>(std::clamp(num("threads"), 0.0, 1e6));
  s.vertices = o.contains("vertices") ? count(o["vertices"]) : 0;
  s.stdErrT0Mean = num("stdErrT0Mean");
  s.stdErrT0Max = num("stdErrT0Max");
  s.stdErrConstMean = num("stdErrConstMean");
  s.stdErrConstMax = num("stdErrConstMax");
  (void)where, (void)r;
  return s;
}

void writeCpcaRecord(const CpcaRecord& c, json& z) {
  z["seed"] = exactInteger(c.fit.seed);
  z["maxIterations"] = c.fit.maxIterations;
  z["tolerance"] = c.fit.tolerance;
  json st = {{"squaredError", c.stats.squaredError},
             {"signalEnergy", c.stats.signalEnergy},
             {"relativeRms", c.stats.relativeRms},
             {"maxRowError", c.stats.maxRowError},
             {"compressionRatio", c.stats.compressionRatio},
             {"seconds", c.stats.seconds},
             {"iterations", c.stats.iterations}};
  if (std::isfinite(c.stats.snrDb)) st["snrDb"] = c.stats.snrDb;  // absent: exact (infinite)
  z["stats"] = std::move(st);
}

CpcaRecord readCpcaRecord(const json& z, const std::string& where, const Reader& r) {
  CpcaRecord c;
  c.fit.seed = r.has(z, "seed") ? r.integer(z, "seed", where) : 0;
  c.fit.maxIterations = static_cast<int>(
      std::clamp(r.numberOr(z, "maxIterations", c.fit.maxIterations, where), 0.0, 2147483647.0));
  c.fit.tolerance = r.numberOr(z, "tolerance", c.fit.tolerance, where);
  if (r.has(z, "stats") && z["stats"].is_object()) {
    const json& st = z["stats"];
    const std::string sw = where + ".stats";
    c.stats.squaredError = r.numberOr(st, "squaredError", 0, sw);
    c.stats.signalEnergy = r.numberOr(st, "signalEnergy", 0, sw);
    c.stats.relativeRms = r.numberOr(st, "relativeRms", 0, sw);
    c.stats.snrDb = r.numberOr(st, "snrDb", std::numeric_limits<double>::infinity(), sw);
    c.stats.maxRowError = r.numberOr(st, "maxRowError", 0, sw);
    c.stats.compressionRatio = r.numberOr(st, "compressionRatio", 0, sw);
    c.stats.seconds = r.numberOr(st, "seconds", 0, sw);
    c.stats.iterations =
        static_cast<int>(std::clamp(r.numberOr(st, "iterations", 0, sw), 0.0, 2147483647.0));
  }
  return c;
}

}  // namespace prt::io::schema
