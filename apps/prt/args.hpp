#pragma once
// Argument parsing shared by the verbs (header-only, internal to the command line), so that
// --rotate, --size, --mode and number lists mean the same and fail the same way everywhere.

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/vec.hpp"
#include "prt/image/image.hpp"
#include "prt/render/reference.hpp"
#include "prt/sh/convolve.hpp"

namespace prt::cli {

/// "1,2,5" -> {1, 2, 5}; throws naming `option` on anything else.
inline std::vector<double> parseNumberList(const std::string& s, const char* option) {
  std::vector<double> out;
  std::istringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::istringstream is(item);
    double v;
    if (!(is >> v) || !(is >> std::ws).eof() || !std::isfinite(v))
      throw Error(std::string(option) + " '" + s + "' is not a comma-separated list of numbers");
    out.push_back(v);
  }
  if (out.empty()) throw Error(std::string(option) + " is empty");
  return out;
}

/// "X,Y,Z" Euler degrees (about X, then Y, then Z) -> the three angles; "" -> zeros.
inline std::array<double, 3> parseEulerDegrees(const std::string& s) {
  if (s.empty()) return {0, 0, 0};
  const std::vector<double> a = parseNumberList(s, "--rotate");
  if (a.size() != 3) throw Error("--rotate '" + s + "' is not three angles X,Y,Z in degrees");
  return {a[0], a[1], a[2]};
}

/// "X,Y,Z" Euler degrees -> R = Rz Ry Rx; "" -> identity.
inline Mat3d parseRotation(const std::string& s) {
  const std::array<double, 3> a = parseEulerDegrees(s);
  return rotationEulerXYZ(a[0], a[1], a[2]);
}

/// "WxH" -> (w, h), both in 1..image::kMaxImageSide; `option` names the flag in messages.
inline void parseSize(const std::string& s, int& w, int& h, const char* option = "--size") {
  char x = 0;
  std::istringstream in(s);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !(in >> std::ws).eof())
    throw Error(std::string(option) + " '" + s + "' is not WIDTHxHEIGHT");
  if (w <= 0 || h <= 0 || w > image::kMaxImageSide || h > image::kMaxImageSide)
    throw Error(std::string(option) + " " + s + ": width and height must be 1.." +
                std::to_string(image::kMaxImageSide));
}

inline render::MisHeuristic parseMis(const std::string& s) {
  if (s == "power") return render::MisHeuristic::Power;
  if (s == "balance") return render::MisHeuristic::Balance;
  throw Error("--mis '" + s + "': expected power or balance");
}

/// --window: none | hanning | lanczos | dering (prt light, prt validate): sh::parseWindow.
inline sh::Window parseWindow(const std::string& s) {
  try {
    return sh::parseWindow(s);
  } catch (const Error& e) {
    throw Error(std::string("--") + e.what());
  }
}

}  // namespace prt::cli
