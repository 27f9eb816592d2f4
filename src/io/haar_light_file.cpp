#include "prt/io/haar_light_file.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/json.hpp"
#include "prt/haar/resolution.hpp"

namespace prt::io {

namespace {

Rgb rgbOf(const nlohmann::json& v, std::size_t from, const std::string& path,
          const std::string& what) {
  for (std::size_t k = from; k < from + 3; ++k)
    if (!v[k].is_number()) throw Error(path, what + " is not a number triple");
  const Rgb c(v[from].get<float>(), v[from + 1].get<float>(), v[from + 2].get<float>());
  if (!isFinite(c)) throw Error(path, what + " is not finite");
  return c;
}

}  // namespace

void writeHaarLightJson(const std::string& path, const HaarLightFile& f) {
  const haar::HaarLight& l = f.light;
  l.check(path);
  Json j;
  j["basis"] = "haar";
  j["resolution"] = l.resolution;
  j["selection"] = f.selection;
  j["energyKept"] = l.energyKept;
  Json terms = Json::array();
  for (std::size_t t = 0; t < l.terms(); ++t) {
    Json row = Json::array({l.index[t]});
    for (float x : {l.value[t].x, l.value[t].y, l.value[t].z}) row.push_back(jsonFloats(&x, 1)[0]);
    terms.push_back(std::move(row));
  }
  j["terms"] = std::move(terms);
  Json sh = Json::array();
  for (const Rgb& x : l.unshadowed.c) sh.push_back(jsonFloats(&x.x, 3));
  Json bright = Json::array();
  for (const haar::BrightTexel& b : l.bright) {
    Json row = Json::array({b.texel});
    for (float x : {b.radiance.x, b.radiance.y, b.radiance.z}) row.push_back(jsonFloats(&x, 1)[0]);
    bright.push_back(std::move(row));
  }
  j["unshadowed"] = {{"bands", l.unshadowed.bands},
                     {"coefficients", std::move(sh)},
                     {"bright", std::move(bright)}};
  j["source"] = f.source;
  j["layout"] = f.layout;
  j["rotation"] = Json::array({f.rotationDeg[0], f.rotationDeg[1], f.rotationDeg[2]});
  j["prtkit_version"] = f.prtkitVersion;
  writeFileAtomically(path, formatJson(j));
}

HaarLightFile readHaarLightJson(const std::string& path) {
  const std::vector<unsigned char> bytes = readFileBytes(path);
  return parseHaarLightJson(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

HaarLightFile parseHaarLightJson(std::string_view text, const std::string& path) {
  nlohmann::json j = parseJsonText(text, path);
  if (!j.is_object()) throw Error(path, "expected a JSON object");
  if (!j.contains("basis") || j["basis"] != "haar")
    throw Error(path, "is not a Haar light (no \"basis\": \"haar\"; an SH light relights SH "
                      "bakes: make one with prt light --basis haar)");
  HaarLightFile f;
  haar::HaarLight& l = f.light;
  if (!j.contains("resolution") || !j["resolution"].is_number_integer())
    throw Error(path, "\"resolution\" must be an integer");
  l.resolution = j["resolution"].get<int>();
  if (!haar::validResolution(l.resolution))
    throw Error(path, "\"resolution\" " + std::to_string(l.resolution) +
                          " is not a power of two from " + std::to_string(haar::kMinResolution) +
                          " to " + std::to_string(haar::kMaxResolution));
  const std::size_t count = haar::coefficientCount(l.resolution);
  if (!j.contains("terms") || !j["terms"].is_array())
    throw Error(path, "missing \"terms\" array");
  const auto& terms = j["terms"];
  if (terms.empty() || terms.size() > count)
    throw Error(path, "holds " + std::to_string(terms.size()) + " terms; a " +
                          std::to_string(l.resolution) + "² cube has 1 to " +
                          std::to_string(count));
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const auto& r = terms[t];
    const std::string what = "term " + std::to_string(t);
    if (!r.is_array() || r.size() != 4 || !r[0].is_number_integer() || r[0].get<double>() < 0)
      throw Error(path, what + " is not [index, r, g, b]");
    l.index.push_back(static_cast<std::uint32_t>(std::min<double>(r[0].get<double>(), 4e9)));
    l.value.push_back(rgbOf(r, 1, path, what));
  }
  if (!j.contains("unshadowed") || !j["unshadowed"].is_object() ||
      !j["unshadowed"].contains("coefficients") || !j["unshadowed"]["coefficients"].is_array())
    throw Error(path, "missing \"unshadowed\" {\"bands\", \"coefficients\"}");
  const auto& sh = j["unshadowed"]["coefficients"];
  if (sh.size() != std::size_t(haar::kUnshadowedBands * haar::kUnshadowedBands))
    throw Error(path, "\"unshadowed\" holds " + std::to_string(sh.size()) +
                          " coefficients, expected " +
                          std::to_string(haar::kUnshadowedBands * haar::kUnshadowedBands));
  l.unshadowed = sh::RgbSh(haar::kUnshadowedBands);
  for (std::size_t i = 0; i < sh.size(); ++i) {
    if (!sh[i].is_array() || sh[i].size() != 3)
      throw Error(path, "unshadowed coefficient " + std::to_string(i) + " is not [r, g, b]");
    l.unshadowed.c[i] = rgbOf(sh[i], 0, path, "unshadowed coefficient " + std::to_string(i));
  }
  const auto& bright = j["unshadowed"]["bright"];
  if (!bright.is_array() || bright.size() > haar::kBrightTexels)
    throw Error(path, "\"unshadowed\".\"bright\" must be an array of at most " +
                          std::to_string(haar::kBrightTexels) + " [texel, r, g, b]");
  for (std::size_t b = 0; b < bright.size(); ++b) {
    const auto& r = bright[b];
    const std::string what = "bright texel " + std::to_string(b);
    if (!r.is_array() || r.size() != 4 || !r[0].is_number_integer() || r[0].get<double>() < 0)
      throw Error(path, what + " is not [texel, r, g, b]");
    l.bright.push_back({static_cast<std::uint32_t>(std::min<double>(r[0].get<double>(), 4e9)),
                        rgbOf(r, 1, path, what)});
  }
  if (j.contains("energyKept") && j["energyKept"].is_number())
    l.energyKept = j["energyKept"].get<double>();
  try {
    l.check(path);
  } catch (const Error& e) {
    throw Error(e.what());
  }
  const auto str = [&](const char* key, std::string& dst) {
    if (!j.contains(key)) return;
    if (!j[key].is_string()) throw Error(path, std::string("\"") + key + "\" must be a string");
    dst = j[key].get<std::string>();
  };
  str("selection", f.selection);
  str("source", f.source);
  str("layout", f.layout);
  str("prtkit_version", f.prtkitVersion);
  if (j.contains("rotation")) {
    const auto& r = j["rotation"];
    if (!r.is_array() || r.size() != 3 || !r[0].is_number() || !r[1].is_number() ||
        !r[2].is_number())
      throw Error(path, "\"rotation\" must be [x, y, z] in degrees");
    for (int k = 0; k < 3; ++k) f.rotationDeg[std::size_t(k)] = r[k].get<double>();
  }
  return f;
}

bool isHaarLightFile(const std::string& path) {
  if (fileExtension(path) != "json") return false;
  try {
    const std::vector<unsigned char> bytes = readFileBytes(path);
    const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, false);
    return j.is_object() && j.contains("basis") && j["basis"] == "haar";
  } catch (...) {
    return false;
  }
}

}  // namespace prt::io
