#include "prt/image/color.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "prt/core/error.hpp"

namespace prt::image {

float srgbToLinear(float v) {
  // IEC 61966-2-1: linear segment below the 0.04045 knee, then a 2.4 power with offset.
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgb8ToLinear(std::uint8_t v) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table[v];
}

float gamma22ToLinear(std::uint8_t v) {
  // stb_image's stbi__ldr_to_hdr: (float)(pow(data / 255.0f, l2h_gamma) * l2h_scale) with
  // l2h_gamma = 2.2f and l2h_scale = 1.0f; pow is the double overload.
  const double base = static_cast<double>(static_cast<float>(v) / 255.0f);
  return static_cast<float>(std::pow(base, static_cast<double>(2.2f)) * 1.0);
}

ToneMap parseToneMap(const std::string& name) {
  if (name == "clamp" || name == "linear") return ToneMap::Clamp;
  if (name == "reinhard") return ToneMap::Reinhard;
  if (name == "aces") return ToneMap::Aces;
  throw Error("unknown tone mapper '" + name + "' (expected clamp, reinhard or aces)");
}

float clampExposure(float stops) {
  if (std::isnan(stops)) return 0.0f;
  return std::clamp(stops, -kMaxExposureStops, kMaxExposureStops);
}

void checkExposure(float stops, const std::string& what) {
  if (!std::isfinite(stops) || std::fabs(stops) > kMaxExposureStops) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s %g: must be a finite number of stops in [%g, %g]",
                  what.c_str(), double(stops), double(-kMaxExposureStops),
                  double(kMaxExposureStops));
    throw Error(buf);
  }
}

Rgb toneMap(const Rgb& linear, ToneMap op, float exposureStops) {
  const float scale = std::exp2(clampExposure(exposureStops));
  auto one = [&](float v) {
    // Exposed, then clamped: NaN and negatives to 0, inf and anything absurd to a finite value
    // every tone map sends to white (header comment).
    v *= scale;
    v = v > 0.0f ? std::min(v, kToneMapInputMax) : 0.0f;
    switch (op) {
      case ToneMap::Clamp:
        return std::min(v, 1.0f);
      case ToneMap::Reinhard:
        return v / (1.0f + v);
      case ToneMap::Aces:
        v = std::min(v, 16.0f);  // the fit is ≥ 1 from 7.25 on: clamped to white there
        return std::clamp(v * (2.51f * v + 0.03f) / (v * (2.43f * v + 0.59f) + 0.14f), 0.0f, 1.0f);
    }
    return v;
  };
  return {one(linear.x), one(linear.y), one(linear.z)};
}

}  // namespace prt::image
