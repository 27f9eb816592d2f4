#pragma once
// The shader-ready form of CPCA-compressed transfer: what a GPU viewer uploads to relight in the
// compressed space, as Sloan, Hall, Hart & Snyder do ("Clustered Principal Components for
// Precomputed Radiance Transfer", SIGGRAPH 2003, §5: per-cluster light projections on the CPU,
// per-vertex weighted sums on the GPU). Shared by prt view (texture buffers) and, in JS, by the
// web page (2D float textures of the same texel order; web/src/compressed.js).
//
// Two RGBA32F arrays:
//
//  * per vertex, static (uploaded once): T = ⌈(N + 1) / 4⌉ texels per vertex, vertex v at texels
//    v·T .. v·T + T − 1, slots s = 0 .. 4T − 1 in texel order:
//        slot 0     the cluster id k(v), as a float (exact: ids are below 2²⁴, checked)
//        slot 1 + j the weight w_vj, j < N
//        the rest   0
//    so a vertex uploads 16·T bytes (N = 8: 48 bytes) against 16·⌈B²/4⌉ (scalar) or 16·B² (RGB)
//    for a dense vector row and 4·B⁴·C for a matrix.
//
//  * per frame, the projections of relight::projectClusters (compressed.hpp) as texels
//    (r, g, b, 0): texel (k·(N + 1) + j)·Q + i holds value i (Q = 1 for vectors, B² for matrices)
//    of the cluster's mean (j = 0) or of basis vector j − 1 projected on the rotated light:
//        vectors   c_k = M_k·L, d_kj = B_kj·L                         K(N + 1) texels
//        matrices  L'_k0 = M_k L, L'_kj = B_kj L (B² RGB values each)  K(N + 1)·B² texels
//
// A shader then forms, with k = k(v) and w_j read from the vertex's texels,
//    vectors:   e(v) = albedo(v) ⊙ (c_k + Σ_j w_vj d_kj)
//    matrices:  L'_v,i = L'_k0,i + Σ_j w_vj L'_kj,i, then the glossy response of glossy.hpp
// (shaders/prt_compressed.glsl). evalPackedVertex below is that sum on the CPU, the reference
// the packing is tested against (tests/relight).

#include <cstddef>
#include <vector>

#include "prt/compress/cpca.hpp"
#include "prt/core/vec.hpp"
#include "prt/relight/compressed.hpp"

namespace prt::relight {

/// The per-vertex texels: cluster id and weights, RGBA32F.
struct CompressedVertexTexels {
  int texelsPerVertex = 0;  ///< T = ⌈(N + 1) / 4⌉
  int basisCount = 0;       ///< N
  std::vector<float> rgba;  ///< 4·T floats per vertex
  /// Bytes one vertex uploads (16·T).
  std::size_t bytesPerVertex() const { return 16 * static_cast<std::size_t>(texelsPerVertex); }
};

/// T = ⌈(N + 1) / 4⌉: texels per vertex for N weights.
constexpr int compressedTexelsPerVertex(int basisCount) {
  return (basisCount + 1 + 3) / 4;
}

/// Packs the cluster ids and weights (throws prt::Error when K ≥ 2²⁴: ids would not be exact
/// floats, or when the arrays do not match the transfer's shape).
CompressedVertexTexels packCompressedVertices(const CompressedTransfer& transfer);

/// Lays the per-frame projections out as (r, g, b, 0) texels (see above) into `rgba`, resized to
/// 4·K(N + 1)·Q floats; no allocation once it has that size.
void packClusterTable(const ClusterLight& projected, std::vector<float>& rgba);

/// The shader's sum at vertex v from the two packings: for vectors out[0] = c_k + Σ_j w_vj d_kj
/// (albedo not applied); for matrices out[i] = L'_v,i for i < Q. `coeffs` = Q.
void evalPackedVertex(const CompressedVertexTexels& vertices, const std::vector<float>& table,
                      int coeffs, std::size_t v, Rgb* out);

}  // namespace prt::relight
