#pragma once
// The seam metric of per-texel transfer (issue 18): where a smooth surface is cut into two
// charts, the edge has two places in the lightmap, and a bilinear fetch on either side should
// give the same light. Over every seam edge (geometry/uv_seams.hpp: shared in space, smooth,
// cut in UV; creases are not seams) at 16 points along it, the exit radiance under a white sky
// (R = √(4π) T₀, the mean of the channels) is fetched bilinearly on each side (texel centres,
// clamped, as render::texelRadianceShader and a GPU sample), and the mismatch |R_a − R_b| is
// averaged over the points weighted by the edge's length, relative to the mean of R over the
// same points. What the seam fix (transport/lightmap_seam_fix.hpp, Sylvan 2015's least
// squares) drives towards zero.

#include <cstddef>

#include "prt/geometry/mesh.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::render {

struct SeamStats {
  std::size_t edges = 0;   ///< seam edges found
  double length = 0;       ///< their total length (world units)
  double mismatch = 0;     ///< length-weighted mean |R_a − R_b| / mean R (0 without seams)
  double maxMismatch = 0;  ///< the largest |R_a − R_b| / mean R at any point
};

/// The seams of a complete per-texel transfer over `mesh`'s lightmap UVs (prt::Error otherwise).
SeamStats measureSeams(const Mesh& mesh, const Transfer& transfer);

}  // namespace prt::render
