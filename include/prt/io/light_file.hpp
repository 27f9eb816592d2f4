#pragma once
// Light files: SH lighting coefficients on disk.
//
// JSON (ours):
//   {"bands": B, "coefficients": [[r, g, b], … B² rows, index l(l+1)+m],
//    "source": "studio.exr", "layout": "latlong", "window": "none",
//    "rotation": [x, y, z] (Euler degrees, R = Rz Ry Rx), "prtkit_version": "0.1.0"}
// GAMES202 light.txt (the course's homework 2): B² lines "r g b", nothing else; B = sqrt(lines).
// Readers validate everything and throw prt::Error("FILE: line N: what is wrong") on one line.

#include <array>
#include <string>
#include <string_view>

#include "prt/sh/sh.hpp"

namespace prt::io {

struct LightFile {
  sh::RgbSh coefficients;
  std::string source;
  std::string layout;
  std::string window = "none";
  std::array<double, 3> rotationDeg = {0, 0, 0};
  std::string prtkitVersion;
};

void writeLightJson(const std::string& path, const LightFile& light);
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
