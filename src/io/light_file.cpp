#include "prt/io/light_file.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/json.hpp"
#include "prt/core/limits.hpp"

namespace prt::io {

namespace {

std::string formatFloat(float v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", static_cast<double>(v));
  return buf;
}

int bandsFromCount(const std::string& path, std::size_t count) {
  const int b = static_cast<int>(std::lround(std::sqrt(static_cast<double>(count))));
  if (count == 0 || static_cast<std::size_t>(b) * b != count)
    throw Error(path, std::to_string(count) + " coefficients is not a square number B² of bands");
  if (b > bands::kMaxLibrary)
    throw Error(path, bands::bandLimitMessage("the light", b, "prtkit", bands::kMaxLibrary));
  return b;
}

/// [x, y, z] of finite numbers, or a one-line error naming `what`.
Vec3d finiteTriple(const nlohmann::json& v, const std::string& path, const std::string& what) {
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    throw Error(path, what + " is not [x, y, z]");
  const Vec3d out(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  if (!std::isfinite(out.x) || !std::isfinite(out.y) || !std::isfinite(out.z))
    throw Error(path, what + " is not finite");
  return out;
}

/// The "irradiance" member (light_file.hpp), every field checked.
EncodedIrradianceRecord parseIrradiance(const nlohmann::json& ir, const std::string& path) {
  if (!ir.is_object()) throw Error(path, "\"irradiance\" must be an object");
  if (!ir.contains("encoding") || !ir["encoding"].is_string())
    throw Error(path, "\"irradiance\" has no \"encoding\" name");
  EncodedIrradianceRecord r;
  sh::EncodedIrradiance& e = r.encoded;
  try {
    e.encoding = sh::parseIrradianceEncoding(ir["encoding"].get<std::string>());
  } catch (const Error& x) {
    throw Error(path, std::string("\"irradiance\": ") + x.what());
  }
  const std::size_t rows = sh::shRows(e.encoding);
  if (!ir.contains("coefficients") || !ir["coefficients"].is_array() ||
      ir["coefficients"].size() != rows)
    throw Error(path, std::string("\"irradiance\": ") + sh::toString(e.encoding) + " holds " +
                          std::to_string(rows) + " coefficient rows [r, g, b]");
  for (std::size_t i = 0; i < rows; ++i)
    e.sh.push_back(
        finiteTriple(ir["coefficients"][i], path, "irradiance coefficient " + std::to_string(i)));
  if (sh::isZonal(e.encoding)) {
    if (!ir.contains("axis") || !ir.contains("zonal"))
      throw Error(path, "\"irradiance\": zh3 needs \"axis\" and \"zonal\"");
    e.axis = finiteTriple(ir["axis"], path, "irradiance axis");
    if (std::fabs(length(e.axis) - 1) > 1e-4)
      throw Error(path, "irradiance axis is not a unit vector");
    e.zonal = finiteTriple(ir["zonal"], path, "irradiance zonal coefficients");
  }
  if (ir.contains("error") && ir["error"].is_object()) {
    const auto& er = ir["error"];
    if (er.contains("referenceBands") && er["referenceBands"].is_number_integer())
      r.referenceBands = er["referenceBands"].get<int>();
    if (er.contains("relativeRms") && er["relativeRms"].is_number())
      r.relativeRms = er["relativeRms"].get<double>();
    if (er.contains("negativeShare") && er["negativeShare"].is_number())
      r.negativeShare = er["negativeShare"].get<double>();
  }
  return r;
}

}  // namespace

Json irradianceJson(const EncodedIrradianceRecord& r) {
  const sh::EncodedIrradiance& e = r.encoded;
  Json ir = {{"encoding", sh::toString(e.encoding)}, {"numbers", sh::storedNumbers(e.encoding)}};
  Json rows = Json::array();
  for (const Rgbd& x : e.sh) rows.push_back({x.x, x.y, x.z});
  ir["coefficients"] = std::move(rows);
  if (sh::isZonal(e.encoding)) {
    ir["axis"] = {e.axis.x, e.axis.y, e.axis.z};
    ir["zonal"] = {e.zonal.x, e.zonal.y, e.zonal.z};
  }
  ir["error"] = {{"referenceBands", r.referenceBands},
                 {"relativeRms", r.relativeRms},
                 {"negativeShare", r.negativeShare}};
  return ir;
}

void writeLightJson(const std::string& path, const LightFile& light) {
  const sh::RgbSh& c = light.coefficients;
  PRT_CHECK(c.c.size() == static_cast<std::size_t>(c.bands) * c.bands, "coefficient count");
  Json j;
  j["bands"] = c.bands;
  Json rows = Json::array();
  for (const Rgb& x : c.c) rows.push_back(jsonFloats(&x.x, 3));
  j["coefficients"] = std::move(rows);
  j["source"] = light.source;
  j["layout"] = light.layout;
  j["window"] = light.window;
  j["rotation"] = Json::array({light.rotationDeg[0], light.rotationDeg[1], light.rotationDeg[2]});
  j["prtkit_version"] = light.prtkitVersion;
  if (light.irradiance) j["irradiance"] = irradianceJson(*light.irradiance);
  writeFileAtomically(path, formatJson(j));
}

LightFile readLightJson(const std::string& path) {
  const std::vector<unsigned char> bytes = readFileBytes(path);
  return parseLightJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                        path);
}

LightFile parseLightJson(std::string_view text, const std::string& path) {
  nlohmann::json j = parseJsonText(text, path);  // not const: operator[] on a missing key is null
  if (!j.is_object()) throw Error(path, "expected a JSON object");
  if (j.contains("basis") && j["basis"] != "sh")
    throw Error(path, "is a " + j["basis"].dump() +
                          " light (prt light --basis haar): it relights Haar bakes, with prt "
                          "render; SH bakes need an SH light");
  if (!j.contains("coefficients") || !j["coefficients"].is_array())
    throw Error(path, "missing \"coefficients\" array");
  const auto& rows = j["coefficients"];
  const int bands = bandsFromCount(path, rows.size());
  if (j.contains("bands") && (!j["bands"].is_number_integer() || j["bands"].get<int>() != bands))
    throw Error(path, "\"bands\" says " + j["bands"].dump() + " but there are " +
                          std::to_string(rows.size()) + " coefficients");
  LightFile out;
  out.coefficients = sh::RgbSh(bands);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    if (!r.is_array() || r.size() != 3 || !r[0].is_number() || !r[1].is_number() ||
        !r[2].is_number())
      throw Error(path, "coefficient " + std::to_string(i) + " is not [r, g, b]");
    const Rgb v(r[0].get<float>(), r[1].get<float>(), r[2].get<float>());
    if (!isFinite(v)) throw Error(path, "coefficient " + std::to_string(i) + " is not finite");
    out.coefficients.c[i] = v;
  }
  auto str = [&](const char* key, std::string& dst) {
    if (!j.contains(key)) return;
    if (!j[key].is_string()) throw Error(path, std::string("\"") + key + "\" must be a string");
    dst = j[key].get<std::string>();
  };
  str("source", out.source);
  str("layout", out.layout);
  str("window", out.window);
  str("prtkit_version", out.prtkitVersion);
  if (j.contains("rotation")) {
    const auto& r = j["rotation"];
    if (!r.is_array() || r.size() != 3 || !r[0].is_number() || !r[1].is_number() ||
        !r[2].is_number())
      throw Error(path, "\"rotation\" must be [x, y, z] in degrees");
    for (int k = 0; k < 3; ++k) out.rotationDeg[k] = r[k].get<double>();
  }
  if (j.contains("irradiance")) out.irradiance = parseIrradiance(j["irradiance"], path);
  return out;
}

void writeLightGames202(const std::string& path, const sh::RgbSh& c) {
  std::string text;
  for (const Rgb& v : c.c)
    text += formatFloat(v.x) + " " + formatFloat(v.y) + " " + formatFloat(v.z) + "\n";
  writeFileAtomically(path, text);
}

sh::RgbSh readLightGames202(const std::string& path) {
  const std::vector<unsigned char> bytes = readFileBytes(path);
  return parseLightGames202(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

sh::RgbSh parseLightGames202(std::string_view text, const std::string& path) {
  std::istringstream is{std::string(text)};
  std::vector<Rgb> rows;
  std::string line;
  int lineNo = 0;
  while (std::getline(is, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::istringstream ls(line);
    float r, g, b;
    std::string extra;
    if (!(ls >> r >> g >> b) || (ls >> extra))
      throw Error(path, "line " + std::to_string(lineNo) + ": expected three numbers \"r g b\"");
    const Rgb v(r, g, b);
    if (!isFinite(v)) throw Error(path, "line " + std::to_string(lineNo) + ": value is not finite");
    rows.push_back(v);
  }
  // Both writers (ours, the course's) end every line with a newline; a file cut inside a line can
  // still leave a square number of complete-looking lines (16 cut to 9 reads as 3 bands).
  std::size_t end = text.size();
  while (end > 0 && (text[end - 1] == ' ' || text[end - 1] == '\t' || text[end - 1] == '\r')) --end;
  if (!rows.empty() && (end == 0 || text[end - 1] != '\n'))
    throw Error(path, "line " + std::to_string(lineNo) +
                          " has no newline: the file is truncated (every light.txt line ends "
                          "with one)");
  const int bands = bandsFromCount(path, rows.size());
  sh::RgbSh out(bands);
  out.c = std::move(rows);
  return out;
}

bool isLightFile(const std::string& path) {
  const std::string ext = fileExtension(path);
  return ext == "json" || ext == "txt";
}

LightFile readLight(const std::string& path) {
  if (fileExtension(path) == "json") return readLightJson(path);
  LightFile out;
  out.coefficients = readLightGames202(path);
  out.source = path;
  return out;
}

}  // namespace prt::io
