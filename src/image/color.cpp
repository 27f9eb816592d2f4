#include "prt/image/color.hpp"

#include <algorithm>
#include <array>
#include <cmath>

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

Rgb toneMap(const Rgb& linear, ToneMap op, float exposureStops) {
  const float scale = std::exp2(exposureStops);
  auto one = [&](float v) {
    v = std::max(v * scale, 0.0f);
    switch (op) {
      case ToneMap::Clamp:
        return std::min(v, 1.0f);
      case ToneMap::Reinhard:
        return v / (1.0f + v);
      case ToneMap::Aces:
        return std::clamp(v * (2.51f * v + 0.03f) / (v * (2.43f * v + 0.59f) + 0.14f), 0.0f, 1.0f);
    }
    return v;
  };
  return {one(linear.x), one(linear.y), one(linear.z)};
}

}  // namespace prt::image
