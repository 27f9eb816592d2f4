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
//
// Every tone map saturates to white for any bright input, however absurd: the exposed value is
// clamped to [0, kToneMapInputMax] first (NaN → 0), so v · 2^exposure overflowing to inf, or
// the ACES rational's v² overflowing above ~1e19, can never turn a bright pixel black. ACES
// reaches 1 at v ≈ 7.25 (0.08v² − 0.56v − 0.14 = 0) and its input is clamped to 16 before the
// rational; Reinhard's v / (1 + v) rounds to exactly 1 long before 1e30. The same code is in
// shaders/prt_display.glsl (the viewers and the web page).

#include <cstdint>
#include <string>

#include "prt/core/luminance.hpp"
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
  return luminanceOf(c);
}

/// The exposure range of every tool (prt render, view, web, light, demo; the viewers' panels and
/// the page), ±64 stops: 2^64 ≈ 1.8e19 is finite in float with room to spare, and the range
/// spans far more than any real scene needs (a sunlit scene and a moonlit one differ by ~20).
inline constexpr float kMaxExposureStops = 64.0f;
/// The largest exposed value the tone maps see (larger ones, and inf, are clamped to it).
inline constexpr float kToneMapInputMax = 1e30f;
/// `stops` within ±kMaxExposureStops (an automatic exposure of a black or absurd image); 0 for NaN.
float clampExposure(float stops);
/// Throws prt::Error("WHAT S: must be a finite number of stops in [-64, 64]") otherwise.
void checkExposure(float stops, const std::string& what = "exposure");

enum class ToneMap { Clamp, Reinhard, Aces };
/// "clamp" | "linear", "reinhard", "aces"; throws prt::Error otherwise.
ToneMap parseToneMap(const std::string& name);
/// Display-referred [0, 1] colour (still linear, before the sRGB encode).
Rgb toneMap(const Rgb& linear, ToneMap op, float exposureStops = 0.0f);

}  // namespace prt::image
