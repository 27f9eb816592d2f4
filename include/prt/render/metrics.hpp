#pragma once
// Image error metrics for comparing a render against a reference (golden images, PRT against
// Monte Carlo). All work on linear RGB images of equal size, over all three channels:
//   RMSE          = sqrt( (1/3N) Σ_p Σ_c (a_pc − b_pc)² )
//   relative RMSE = sqrt( (1/3N) Σ_p Σ_c (a_pc − b_pc)² / (b_pc² + ε) )   (b is the reference;
//                   ε keeps dark pixels from dominating, as in Rousselle et al. 2011's relMSE)
//   max abs error = max_pc |a_pc − b_pc|
// The false-colour image maps each pixel's error e_p = |a_p − b_p| averaged over channels,
// divided by `scale` (default: the 99th percentile of e, so a few outliers do not wash out the
// map) and clamped to [0, 1], through a perceptually ordered ramp black → blue → magenta →
// orange → yellow → white (an "inferno"-like map, hand-fitted: not a copy of matplotlib's table).

#include "prt/image/image.hpp"

namespace prt::render {

struct ErrorStats {
  double rmse = 0;
  double relativeRmse = 0;
  double maxAbs = 0;
  double meanAbs = 0;
};

/// Throws prt::Error if sizes differ or an image is empty.
ErrorStats compareImages(const image::Image& test, const image::Image& reference,
                         double epsilon = 1e-2);
double rmse(const image::Image& test, const image::Image& reference);
double relativeRmse(const image::Image& test, const image::Image& reference, double epsilon = 1e-2);

/// The colour ramp at t ∈ [0, 1] (linear RGB, monotonically increasing luminance).
Rgb falseColour(float t);
/// Per-pixel error as a false-colour image (linear RGB; write it as PNG with the clamp tone
/// map). `scale` ≤ 0 picks the 99th percentile of the per-pixel error.
image::Image errorImage(const image::Image& test, const image::Image& reference, double scale = 0);

}  // namespace prt::render
