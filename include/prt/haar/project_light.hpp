#pragma once
// An environment into the Haar basis (cube_haar.hpp): the mean radiance of every cube texel,
// then the wavelet transform and the non-linear approximation by the K largest terms.
//
// Texel means. For a tabulated environment whose texels are small against the cube's (at least
// 16 of them per cube texel on average), every environment texel's power L·Ω is added to the
// cube texel its direction falls in and the sum divided by the cube texel's exact solid angle —
// energy is kept exactly. Otherwise each cube texel is supersampled 8 × 8 through the
// environment's bilinear lookup, each point weighted by its exact solid angle. An analytic
// environment (a sky and its sun) takes its smooth part the second way and each disc (Cap) by
// 256 × 256 stratified points over the disc, each carrying 1/65536 of its exact power — a sun
// far smaller than a texel still lands with its whole power in the right texels.
//
// Rotation. Rotating the light by R gives L'(ω) = L(R⁻¹ω): the environment is resampled (a
// texel's direction, a disc's centre turned by R), never rotated in the basis (Haar wavelets are
// not closed under rotation; Ng et al. §7).
//
// Selection. Of the 6 N² coefficients c_k (RGB), the K kept maximise |c_k| · A_k, |c| the RGB
// norm and A_k the area of the coefficient's support in texels (supportSide²): Ng et al.'s
// "area-weighted" selection, which they found best because a transfer's coefficients grow with
// their support. Selection::Magnitude keeps the largest |c_k| (the L2-optimal approximation of
// the light alone). Ties break toward the lower index, so the choice is deterministic.

#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/haar/resolution.hpp"

namespace prt::haar {

enum class Selection { AreaWeighted, Magnitude };
const char* toString(Selection selection);
/// Parses "area" | "magnitude"; throws prt::Error otherwise.
Selection parseSelection(const std::string& s);

/// The mean radiance of each of the 6 N² texels of the cube (cube_haar.hpp's order) of the
/// environment turned by `rotation`.
std::vector<Rgb> cubeMeans(const envmap::Environment& env, int resolution,
                           const Mat3d& rotation = Mat3d::identity());

/// The K = `terms` largest coefficients (by `selection`) of the wavelet transform of `means`
/// (6 N² texel means); terms ≥ 6 N² keeps them all. The SH part is left empty (the caller sets
/// it: unshadowedPart). Throws prt::Error on a bad resolution, a
/// size mismatch or terms < 1.
HaarLight approximate(const std::vector<Rgb>& means, int resolution, std::size_t terms,
                      Selection selection = Selection::AreaWeighted);

/// The unshadowed part of the light (haar_light.hpp): the kBrightTexels texels of `means` (the
/// cube of `env` turned by `rotation`) with the largest luminance power L·Ω, and the SH at
/// kUnshadowedBands of the rest: the environment projected once and rotated in SH (exact), less
/// each bright texel's constant patch (its SH integrated 16 × 16 per texel).
struct UnshadowedPart {
  sh::RgbSh sh;
  std::vector<BrightTexel> bright;
};
UnshadowedPart unshadowedPart(const envmap::Environment& env, const std::vector<Rgb>& means,
                              int resolution, const Mat3d& rotation = Mat3d::identity());
/// The same from the environment's SH at kUnshadowedBands, unturned (`environmentSh`: what
/// envmap::projectEnvironment gives), for a viewer that holds the environment's cube and SH
/// rather than the environment (haar/turned_cube.hpp).
UnshadowedPart unshadowedPart(const sh::RgbSh& environmentSh, const std::vector<Rgb>& means,
                              int resolution, const Mat3d& rotation = Mat3d::identity());

/// The SH (kUnshadowedBands bands) of texel `texel` of the cube as a constant patch of unit
/// radiance: Σ over its 16 × 16 midpoints of Y(d̂) dA/|d|³ — what unshadowedPart takes away
/// for each bright texel.
std::vector<double> texelPatchSh(std::uint32_t texel, int resolution);
/// The whole light's SH at kUnshadowedBands: the rest's and each bright texel's patch, which is
/// the environment's SH turned as the light was. An inter-reflected Haar row's bounce is relit
/// against it (relight/relight_haar.hpp).
sh::RgbSh fullSh(const HaarLight& light);

/// cubeMeans, approximate and unshadowedPart: the light a Haar bake is relit with.
HaarLight projectLight(const envmap::Environment& env, int resolution, std::size_t terms,
                       const Mat3d& rotation = Mat3d::identity(),
                       Selection selection = Selection::AreaWeighted);

}  // namespace prt::haar
