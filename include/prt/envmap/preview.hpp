#pragma once
// Previews: an environment and its SH reconstruction rendered into lat-long images (same
// convention as layout.hpp), so the band-limited light can be compared with its source.

#include "prt/envmap/environment.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image.hpp"
#include "prt/sh/sh.hpp"

namespace prt::envmap {

/// The environment resampled into a width × width/2 lat-long, seen after `rotation`: pixel with
/// direction d shows env.lookup(Rᵀ d) (a light rotated by R).
image::Image renderEnvironment(const Environment& env, int width,
                               const Mat3d& rotation = Mat3d::identity());
/// Σ_i L_i Y_i(d) at each lat-long pixel centre.
image::Image renderSh(const sh::RgbSh& sh, int width);
/// Irradiance over π, E(n)/π = Σ Λ_l/π L_lm Y_lm(n): the exit radiance of a white Lambertian
/// surface facing n (Ramamoorthi & Hanrahan 2001).
image::Image renderIrradiance(const sh::RgbSh& sh, int width);
/// Three panels stacked top to bottom: source, SH radiance, SH irradiance/π.
image::Image previewPanels(const Environment& env, const sh::RgbSh& sh, int width,
                           const Mat3d& rotation = Mat3d::identity());
/// The exposure for a previewPanels() image shown through `op`: image::autoExposure (the one
/// rule prt render, view, web and the demo pick a model's exposure by) of its irradiance panel —
/// the bottom third: smooth, and what a white object under the light looks like. The source
/// panel would not do: under a sun its median sits far below the SH panels' mean (Λ₀/π = 1),
/// so they would be shown blown out.
float previewExposure(const image::Image& panels, image::ToneMap op);

}  // namespace prt::envmap
