#pragma once
// The least-squares seam fix of per-texel transfer (issue 18), after
//   S. Sylvan, "Fixing texture seams with linear least-squares" (2015).
//
// A seam edge (geometry/uv_seams.hpp) is one edge of the surface in two places of the lightmap;
// a bilinear fetch on either side reads different texels, so the light jumps across it. The fix
// changes the texels those fetches read, as little as it can, so the two sides agree. With x the
// values of the texels the seam fetches touch, x₀ their baked values, and for each sample point
// s along a seam edge the row a_s of bilinear weights (side A's four taps +, side B's four −):
//
//     minimise  Σ_s (a_s · x)²  +  λ Σ_t (x_t − x₀_t)²,
//     i.e.      (Σ_s a_s a_sᵀ + λ I) x = λ x₀          (the normal equations, symmetric
//                                                         positive definite: Eigen's LDLᵀ)
//
// one system for every coefficient and channel (the same matrix, stride right-hand sides). The
// samples lie `kSeamSamplesPerTexel` per texel of the edge's length in the lightmap (the longer
// of its two sides), at the centres of equal steps; λ = `kSeamDataWeight` keeps the texels near
// their baked values (smaller: seams closer, the interior of a chart more disturbed). Texels
// that are not free (the empty gutter of a bake without padding) enter as fixed values. The
// result is deterministic: the unknowns are ordered by texel, the solve is sequential.

#include <cstddef>
#include <cstdint>
#include <span>

#include "prt/geometry/mesh.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

inline constexpr int kSeamSamplesPerTexel = 3;
inline constexpr double kSeamDataWeight = 0.1;

struct SeamFixStats {
  std::size_t edges = 0;    ///< seam edges found
  std::size_t samples = 0;  ///< seam sample points (least-squares rows)
  std::size_t texels = 0;   ///< texels changed (the unknowns)
  double seconds = 0;
};

/// Fixes the seams of a W × H lightmap over `uvs` (one per vertex of `mesh`) in place: `values`
/// holds `stride` floats per texel, W·H texels; `free` (W·H entries) marks the texels it may
/// change. Throws prt::Error when the buffers do not match the lightmap.
void fixLightmapSeams(const Mesh& mesh, std::span<const Vec2f> uvs, int width, int height,
                      std::span<float> values, std::size_t stride,
                      std::span<const std::uint8_t> free, SeamFixStats* stats = nullptr);

/// The seam fix of a complete dense per-texel transfer over `uvs` (the lightmap set it was baked
/// over, one per vertex of `mesh`; the two-argument form: mesh.lightmapUvs): the free
/// texels are all of them where the lightmap has padding (the taps of a fetch inside a chart lie
/// within one texel of it, all filled), else the covered ones. The result's lightmap says
/// seamsFixed. Throws prt::Error naming the mesh for a partial, compressed or per-vertex transfer
/// (fix the seams before compressing; a range's seams reach other ranges: merge first).
Transfer fixLightmapSeams(const Mesh& mesh, std::span<const Vec2f> uvs, const Transfer& transfer,
                          SeamFixStats* stats = nullptr);
inline Transfer fixLightmapSeams(const Mesh& mesh, const Transfer& transfer,
                                 SeamFixStats* stats = nullptr) {
  return fixLightmapSeams(mesh, mesh.lightmapUvs, transfer, stats);
}

}  // namespace prt
