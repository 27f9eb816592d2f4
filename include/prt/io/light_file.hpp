#pragma once
// Light files: SH lighting coefficients on disk.
//
// JSON (ours):
//   {"bands": B, "coefficients": [[r, g, b], … B² rows, index l(l+1)+m],
//    "source": "studio.exr", "layout": "latlong", "window": "none",
//    "rotation": [x, y, z] (Euler degrees, R = Rz Ry Rx), "prtkit_version": "0.1.0",
//    "irradiance": {...}}  (optional: `prt light --encoding`, below)
// "irradiance" holds the light's irradiance in an engine's form (sh/irradiance_encoding.hpp):
//   {"encoding": "zh3", "numbers": 15, "coefficients": [[r, g, b], … 4 or 9 irradiance SH rows],
//    "axis": [x, y, z], "zonal": [r, g, b] (the zh3 forms),
//    "error": {"referenceBands": 12, "relativeRms": 0.05, "negativeShare": 0}}
// GAMES202 light.txt (the course's homework 2): B² lines "r g b", nothing else; B = sqrt(lines).
// Readers validate everything and throw prt::Error("FILE: line N: what is wrong") on one line.

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "prt/core/json.hpp"
#include "prt/sh/irradiance_encoding.hpp"
#include "prt/sh/sh.hpp"

namespace prt::io {

/// The light's irradiance as an engine stores it, and what that loses against the irradiance of
/// a `referenceBands`-band projection of the same environment.
struct EncodedIrradianceRecord {
  sh::EncodedIrradiance encoded;
  int referenceBands = 0;
  double relativeRms = 0;
  double negativeShare = 0;
};

struct LightFile {
  sh::RgbSh coefficients;
  std::string source;
  std::string layout;
  std::string window = "none";
  std::array<double, 3> rotationDeg = {0, 0, 0};
  std::string prtkitVersion;
  std::optional<EncodedIrradianceRecord> irradiance;
};

void writeLightJson(const std::string& path, const LightFile& light);
/// The "irradiance" member as a light file holds it (and prt light and prt info report it).
Json irradianceJson(const EncodedIrradianceRecord& record);
LightFile readLightJson(const std::string& path);
/// The same from text in memory; `name` is used in messages.
LightFile parseLightJson(std::string_view text, const std::string& name);
/// Coefficients printed with 9 significant digits (exact float round trip).
void writeLightGames202(const std::string& path, const sh::RgbSh& coefficients);
sh::RgbSh readLightGames202(const std::string& path);
/// The same from text in memory; `name` is used in messages.
sh::RgbSh parseLightGames202(std::string_view text, const std::string& name);
/// By extension: .json → JSON, anything else (.txt) → the course format.
LightFile readLight(const std::string& path);

/// True when `path` names an SH light file (.json, or the course's light.txt) rather than an
/// environment (image, face folder, builtin:NAME): the one rule every verb and viewer uses.
bool isLightFile(const std::string& path);

}  // namespace prt::io
