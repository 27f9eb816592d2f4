#pragma once
// The seam metric of per-texel transfer (issue 18): where a smooth surface is cut into two
// charts, the edge has two places in the lightmap, and a bilinear fetch on either side should
// give the same light. Over every seam edge (geometry/uv_seams.hpp: shared in space, smooth,
// cut in UV; creases are not seams) at 16 points along it, the exit radiance under a light
// (R = Σᵢ Lᵢ Tᵢ, the mean over the channels) is fetched bilinearly on each side (texel centres,
// clamped, as render::texelRadianceShader and a GPU sample), and the mismatch |R_a − R_b| is
// averaged over the points weighted by the edge's length, relative to the mean of R over the
// same points. What the seam fix (transport/lightmap_seam_fix.hpp, Sylvan 2015's least
// squares) drives towards zero.
//
// Under a white sky (R = √(4π) T₀) only the transfer's mean shows; the shadow edges a sun draws
// are where seams show most, and there the mismatch is larger (builtin:sphere-plane, shadowed,
// 256²: 1.14 % white sky, 2.40 % sun), so prt info reports both (seamLights).

#include <cstddef>
#include <vector>

#include "prt/geometry/mesh.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::render {

struct SeamStats {
  std::size_t edges = 0;   ///< seam edges found
  double length = 0;       ///< their total length (world units)
  double mismatch = 0;     ///< length-weighted mean |R_a − R_b| / mean R (0 without seams)
  double maxMismatch = 0;  ///< the largest |R_a − R_b| / mean R at any point
};

/// The seams of a complete per-texel transfer over `mesh`'s lightmap UVs (prt::Error otherwise)
/// under `light` (its first bands as many as the transfer's; fewer bands count as zeros).
SeamStats measureSeams(const Mesh& mesh, const Transfer& transfer, const sh::RgbSh& light);

/// Under the white sky (seamLights(B)[0]).
SeamStats measureSeams(const Mesh& mesh, const Transfer& transfer);

/// The lights the seams are reported under: a white sky (radiance 1), and a directional light
/// along the builtin sky's sun (builtin:sky's default, 30° above the horizon), of `bands`.
struct SeamLight {
  const char* name;  ///< "white sky", "sun"
  sh::RgbSh light;
};
std::vector<SeamLight> seamLights(int bands);

}  // namespace prt::render
