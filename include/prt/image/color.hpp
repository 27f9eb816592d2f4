#pragma once
// Colour helpers: the sRGB transfer function (IEC 61966-2-1), Rec. 709 luminance, and the tone
// mappers used to turn linear HDR radiance into display-referred PNGs.
//
// Tone mappers (applied after multiplying by 2^exposure):
//  * Clamp:    v ↦ min(v, 1)
//  * Reinhard: v ↦ v / (1 + v) per channel (Reinhard et al., "Photographic Tone Reproduction
//              for Digital Images", SIGGRAPH 2002, eq. 3 without the white point).
//  * Aces:     Narkowicz's fit of the ACES RRT+ODT, v ↦ v(2.51v + 0.03) / (v(2.43v + 0.59) + 0.14)
//              ("ACES Filmic Tone Mapping Curve", 2016), clamped to [0, 1].

#include <cstdint>
#include <string>

#include "prt/core/vec.hpp"

namespace prt::image {

/// sRGB-encoded value in [0, 1] → linear.
float srgbToLinear(float v);
/// Linear → sRGB-encoded value (input clamped to [0, 1]).
float linearToSrgb(float v);
/// 8-bit sRGB code → linear, via a 256-entry table.
float srgb8ToLinear(std::uint8_t v);
/// The course's (stb's default) LDR → HDR decode: (v/255)^2.2, evaluated exactly as stb does
/// (float(pow(float(v/255.0f), 2.2f))).
float gamma22ToLinear(std::uint8_t v);
/// Rec. 709 / sRGB relative luminance: 0.2126 R + 0.7152 G + 0.0722 B.
inline float luminance(const Rgb& c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

enum class ToneMap { Clamp, Reinhard, Aces };
/// "clamp" | "linear", "reinhard", "aces"; throws prt::Error otherwise.
ToneMap parseToneMap(const std::string& name);
/// Display-referred [0, 1] colour (still linear, before the sRGB encode).
Rgb toneMap(const Rgb& linear, ToneMap op, float exposureStops = 0.0f);

}  // namespace prt::image
