#pragma once
// How good a lightmap UV set is: how much of the square it uses, how evenly it spends texels
// over the surface, and how much it stretches them.
//
// L2 stretch is Sander, Snyder, Gortler & Hoppe, "Texture Mapping Progressive Meshes",
// SIGGRAPH 2001, §3: for the affine map of a triangle from the plane (s, t) onto the surface,
// with Jacobian columns S_s = ∂q/∂s and S_t = ∂q/∂t, a = S_s·S_s, b = S_s·S_t, c = S_t·S_t,
//
//     L2(T) = √((a + c) / 2),   L∞(T) = √(((a + c) + √((a − c)² + 4b²)) / 2),
//     L2(M) = √(Σ L2(T)² A(T) / Σ A(T))   (A: area on the surface),
//
// reported normalised, × √(Σ A'(T) / Σ A(T)) with A' the area in the plane, so that 1 is the
// least any layout can have (an isometry up to one global scale) and figures compare across
// meshes and resolutions. Texel density is ρ(T) = √(A'(T) / A(T)), reported relative to the
// atlas-wide √(Σ A' / Σ A).

#include <cstddef>
#include <span>

#include "prt/geometry/mesh.hpp"

namespace prt {

struct AtlasStats {
  std::size_t charts = 0;    ///< UV islands: triangles connected through shared vertex indices
  double chartArea = 0;      ///< Σ A' over the unit square
  double wastedArea = 0;     ///< 1 − chartArea
  double texelsCovered = 0;  ///< share of the W × W texels a triangle overlaps (conservatively)
  double wastedTexels = 0;   ///< 1 − texelsCovered
  double densityP05 = 0, densityP95 = 0;  ///< area-weighted 5th, 95th percentile of ρ / mean
  double densityMin = 0, densityMax = 0;  ///< extremes of ρ / mean over triangles with area
  double stretchL2 = 0;                   ///< Sander's L2(M), normalised (≥ 1)
  double stretchL2Max = 0;                ///< the largest normalised per-triangle L2(T)
  double stretchLinfMax = 0;              ///< the largest normalised per-triangle L∞(T)
  double seconds = 0;                     ///< the time taken to make the atlas (filled by unwrap)
};

/// Measures `uvs` (one per vertex of `mesh`) as a `resolution`² lightmap atlas. Triangles
/// without area in 3D or in the plane are left out of the density and stretch figures.
AtlasStats measureAtlas(const Mesh& mesh, std::span<const Vec2f> uvs, int resolution);

}  // namespace prt
