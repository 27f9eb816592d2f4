#include "prt/image/exposure.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace prt::image {

float clipDisplayValue() {
  static const float v = srgbToLinear(254.5f / 255.0f);
  return v;
}

float clipInput(ToneMap op) {
  const double y = clipDisplayValue();
  switch (op) {
    case ToneMap::Clamp:
      return float(y);
    case ToneMap::Reinhard:
      return float(y / (1.0 - y));  // v / (1 + v) = y
    case ToneMap::Aces: {
      // v(2.51v + 0.03) = y (v(2.43v + 0.59) + 0.14): a v² + b v + c = 0, the positive root.
      const double a = 2.51 - 2.43 * y, b = 0.03 - 0.59 * y, c = -0.14 * y;
      return float((-b + std::sqrt(b * b - 4 * a * c)) / (2 * a));
    }
  }
  return float(y);
}

bool clipped(const Rgb& linear, ToneMap op, float stops) {
  const Rgb t = toneMap(linear, op, stops);
  return std::max({t.x, t.y, t.z}) >= clipDisplayValue();
}

float clippedFraction(std::span<const Rgb> pixels, ToneMap op, float stops) {
  if (pixels.empty()) return 0.0f;
  std::size_t n = 0;
  for (const Rgb& p : pixels) n += clipped(p, op, stops) ? 1 : 0;
  return float(double(n) / double(pixels.size()));
}

float autoExposure(std::span<const Rgb> pixels, ToneMap op) {
  if (pixels.empty()) return 0.0f;
  std::vector<float> lum, peak;
  lum.reserve(pixels.size());
  peak.reserve(pixels.size());
  for (const Rgb& p : pixels) {
    lum.push_back(luminance(p));
    peak.push_back(std::max({p.x, p.y, p.z}));
  }
  const std::size_t n = pixels.size();
  const auto mid = lum.begin() + std::ptrdiff_t(n / 2);
  std::nth_element(lum.begin(), mid, lum.end());
  // Rank k = ceil((1 − f) n) − 1: at most floor(f n) pixels lie strictly above peak[k], and
  // those equal to it stay below the clipping input by the headroom.
  const auto k = std::size_t(std::max(
      0.0, std::ceil((1.0 - double(kAutoExposureClipFraction)) * double(n)) - 1.0));
  const auto q = peak.begin() + std::ptrdiff_t(std::min(k, n - 1));
  std::nth_element(peak.begin(), q, peak.end());
  double stops = 0;
  bool any = false;
  if (std::isfinite(*q) && *q > 0) {
    stops = std::log2(double(kAutoExposureHeadroom) * clipInput(op) / double(*q));
    any = true;
  }
  if (std::isfinite(*mid) && *mid > 0) {
    const double key = std::log2(double(kAutoExposureKey) / double(*mid));
    stops = any ? std::min(stops, key) : key;
    any = true;
  }
  return any ? clampExposure(float(stops)) : 0.0f;
}

}  // namespace prt::image
