#pragma once
// The GAMES202 course's cube-map projection, written plainly from its description (not from
// our implementation), for tests of `--compat games202`: the images in the course's order
// negx, posx, posy, negy, posz, negz, each paired with its (U, V, C) frame; texel (x, y), y from
// the top row, looks along normalize(u U + v V + C), u = 2(x + 0.5)/w − 1, v = 2(y + 0.5)/h − 1,
// weighted by its exact solid angle (two planar triangles, Van Oosterom & Strackee, IEEE Trans.
// Biomed. Eng. 30(2), 1983 — an independent formula from the corner form the library uses).

#include <array>
#include <cmath>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/image/image.hpp"
#include "prt/sh/sh.hpp"

namespace prt::testing {

inline double triangleSolidAngle(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double la = length(a), lb = length(b), lc = length(c);
  const double num = dot(a, cross(b, c));
  const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2 * std::atan2(std::abs(num), den);
}

/// SH coefficients (double) of six square faces in the course's order, by the course's recipe.
inline std::vector<Rgbd> games202Recipe(const std::array<image::Image, 6>& faces, int bands) {
  static constexpr double U[6][3] = {{0, 0, 1}, {0, 0, 1},  {1, 0, 0},
                                     {1, 0, 0}, {-1, 0, 0}, {1, 0, 0}};
  static constexpr double V[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, -1},
                                     {0, 0, 1},  {0, -1, 0}, {0, -1, 0}};
  static constexpr double C[6][3] = {{-1, 0, 0}, {1, 0, 0},  {0, -1, 0},
                                     {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
  std::vector<Rgbd> ref(bands * bands, Rgbd(0.0));
  std::vector<double> y(bands * bands);
  for (int f = 0; f < 6; ++f) {
    const int n = faces[f].width;
    const auto at = [&](double u, double v) {
      return Vec3d(u * U[f][0] + v * V[f][0] + C[f][0], u * U[f][1] + v * V[f][1] + C[f][1],
                   u * U[f][2] + v * V[f][2] + C[f][2]);
    };
    for (int py = 0; py < n; ++py)
      for (int px = 0; px < n; ++px) {
        const double u = 2 * (px + 0.5) / n - 1, v = 2 * (py + 0.5) / n - 1;
        const double u0 = 2.0 * px / n - 1, u1 = 2.0 * (px + 1) / n - 1, v0 = 2.0 * py / n - 1,
                     v1 = 2.0 * (py + 1) / n - 1;
        const double w = triangleSolidAngle(at(u0, v0), at(u1, v0), at(u1, v1)) +
                         triangleSolidAngle(at(u0, v0), at(u1, v1), at(u0, v1));
        sh::evalReference(bands, normalize(at(u, v)), y.data());
        for (int i = 0; i < bands * bands; ++i) ref[i] += Rgbd(faces[f].at(px, py)) * (y[i] * w);
      }
  }
  return ref;
}

}  // namespace prt::testing
