#pragma once
// Haar light files: `prt light ENV --basis haar` (haar/haar_light.hpp) on disk, JSON:
//   {"basis": "haar", "resolution": N, "selection": "area", "energyKept": 0.9999,
//    "terms": [[index, r, g, b], … K rows, ascending index < 6 N²],
//    "unshadowed": {"bands": 5, "coefficients": [[r, g, b], … 25 rows],
//                   "bright": [[texel, r, g, b], … at most 16]},
//    "source": "studio.exr", "layout": "latlong", "rotation": [x, y, z] (Euler degrees),
//    "prtkit_version": "0.1.0"}
// The reader validates everything and throws prt::Error("FILE: what is wrong") on one line;
// an SH light file's reader (light_file.hpp) refuses these by name, and this one SH files.

#include <array>
#include <string>
#include <string_view>

#include "prt/haar/haar_light.hpp"

namespace prt::io {

struct HaarLightFile {
  haar::HaarLight light;
  std::string selection = "area";
  std::string source;
  std::string layout;
  std::array<double, 3> rotationDeg = {0, 0, 0};
  std::string prtkitVersion;
};

void writeHaarLightJson(const std::string& path, const HaarLightFile& file);
HaarLightFile readHaarLightJson(const std::string& path);
/// The same from text in memory; `name` is used in messages.
HaarLightFile parseHaarLightJson(std::string_view text, const std::string& name);
/// True when the JSON light file at `path` says "basis": "haar" (false for anything else,
/// unreadable files included: its reader then says why).
bool isHaarLightFile(const std::string& path);

}  // namespace prt::io
