#include "prt/render/metrics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "prt/core/error.hpp"

namespace prt::render {

namespace {

void checkSizes(const image::Image& a, const image::Image& b) {
  if (a.empty() || b.empty()) throw Error("image comparison: an image is empty");
  if (a.width != b.width || a.height != b.height)
    throw Error("image comparison: sizes differ (" + std::to_string(a.width) + "x" +
                std::to_string(a.height) + " against " + std::to_string(b.width) + "x" +
                std::to_string(b.height) + ")");
}

}  // namespace

ErrorStats compareImages(const image::Image& test, const image::Image& reference, double epsilon) {
  checkSizes(test, reference);
  // Double accumulators in pixel order: deterministic.
  double sq = 0, rel = 0, absSum = 0, maxAbs = 0;
  for (std::size_t p = 0; p < test.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double a = test.pixels[p][c], b = reference.pixels[p][c], d = a - b;
      sq += d * d;
      rel += d * d / (b * b + epsilon);
      absSum += std::abs(d);
      maxAbs = std::max(maxAbs, std::abs(d));
    }
  const double n = 3.0 * double(test.size());
  return {std::sqrt(sq / n), std::sqrt(rel / n), maxAbs, absSum / n};
}

double rmse(const image::Image& test, const image::Image& reference) {
  return compareImages(test, reference).rmse;
}

double relativeRmse(const image::Image& test, const image::Image& reference, double epsilon) {
  return compareImages(test, reference, epsilon).relativeRmse;
}

Rgb falseColour(float t) {
  // Control points of the ramp (linear RGB), evenly spaced in t; luminance increases along it.
  static constexpr std::array<std::array<float, 3>, 6> kRamp = {{{0.0f, 0.0f, 0.0f},
                                                                 {0.02f, 0.02f, 0.35f},
                                                                 {0.45f, 0.03f, 0.45f},
                                                                 {0.95f, 0.25f, 0.05f},
                                                                 {1.0f, 0.85f, 0.05f},
                                                                 {1.0f, 1.0f, 1.0f}}};
  if (!(t > 0.0f)) t = 0.0f;  // also maps NaN to 0
  t = std::min(t, 1.0f) * float(kRamp.size() - 1);
  const int i = std::min(int(t), int(kRamp.size()) - 2);
  const float f = t - float(i);
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = kRamp[i][k] + f * (kRamp[i + 1][k] - kRamp[i][k]);
  return c;
}

image::Image errorImage(const image::Image& test, const image::Image& reference, double scale) {
  checkSizes(test, reference);
  std::vector<float> e(test.size());
  for (std::size_t p = 0; p < test.size(); ++p) {
    const Rgb d = test.pixels[p] - reference.pixels[p];
    e[p] = (std::abs(d.x) + std::abs(d.y) + std::abs(d.z)) / 3.0f;
  }
  if (!(scale > 0)) {
    std::vector<float> sorted = e;
    const std::size_t k = std::min(sorted.size() - 1, sorted.size() * 99 / 100);
    std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
    scale = sorted[k] > 0 ? sorted[k] : 1.0;
  }
  image::Image out(test.width, test.height);
  for (std::size_t p = 0; p < e.size(); ++p) out.pixels[p] = falseColour(float(e[p] / scale));
  return out;
}

}  // namespace prt::render
