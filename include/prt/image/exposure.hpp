#pragma once
// Automatic exposure: the one rule by which every prt tool (render, view, web, demo) picks the
// exposure of a relit model when none is given.
//
// From the model's pixels (radiance, linear), two exposures in stops:
//   key:     the median luminance lands on kAutoExposureKey (middle grey of a light object:
//            0.3 reads as light grey under ACES, leaving the shoulder for the brightest parts);
//   ceiling: the (1 − kAutoExposureClipFraction) quantile q of the largest channel lands on
//            kAutoExposureHeadroom · clipInput(op), so at most that fraction of pixels clip;
// and the auto exposure is the smaller, min(log2(key / median), log2(headroom · clip / q)).
// "Clipped" means what the PNG writer shows as code 255 in some channel: tone-mapped value ≥
// clipDisplayValue() (the linear value whose sRGB code rounds to 255).
// Both statistics scale with the radiance, so k× brighter pixels get exactly log2 k stops less.

#include <span>

#include "prt/core/vec.hpp"
#include "prt/image/color.hpp"

namespace prt::image {

/// Median luminance after the auto exposure (when the ceiling does not bind).
inline constexpr float kAutoExposureKey = 0.3f;
/// The most pixels the auto exposure lets clip.
inline constexpr float kAutoExposureClipFraction = 0.02f;
/// The ceiling puts its quantile this far below the clipping input (ACES then shows ≈ 0.985).
inline constexpr float kAutoExposureHeadroom = 0.9f;

/// The linear display value (tone-mapped, before the sRGB encode) at and above which an 8-bit
/// sRGB code is 255: srgbToLinear(254.5 / 255) ≈ 0.9911.
float clipDisplayValue();
/// The smallest exposed input value that `op` shows as clipped (≈ 6.38 for ACES, ≈ 111 for
/// Reinhard, ≈ 0.991 for Clamp).
float clipInput(ToneMap op);
/// True when some channel of `linear`, exposed by `stops`, clips after `op`.
bool clipped(const Rgb& linear, ToneMap op, float stops);
/// The fraction of `pixels` that clip (0 for none).
float clippedFraction(std::span<const Rgb> pixels, ToneMap op, float stops);
/// The auto exposure in stops (the file comment) of a model's pixels — only the pixels that show
/// the model, not the background. 0 for no pixels or all-black ones; within ±kMaxExposureStops.
float autoExposure(std::span<const Rgb> modelPixels, ToneMap op);

}  // namespace prt::image
