#pragma once
// Relighting straight from CPCA-compressed transfer (Sloan, Hall, Hart & Snyder 2003, §5).
// Relighting is linear in the transfer row, so with x_p ≈ M_k + Σ_j w_pj B_kj (compress/cpca.hpp):
//
//   vectors:  R(p) = albedo(p) ⊙ ( M_k·L + Σ_j w_pj (B_kj·L) )
//             the K(N+1) RGB dots c_k = M_k·L, d_kj = B_kj·L are done once per frame, then each
//             vertex costs N RGB multiply-adds and reads 4N + 4 bytes instead of 4·B²·C.
//   matrices: L'_p = M_p L ≈ (M_k L) + Σ_j w_pj (B_kj L)   (B² × RGB per cluster and vector, once
//             per frame), then the glossy shading of glossy.hpp on L'_p:
//             e = kd Σ_i d_i L'_p,i + ks Σ_i g_i L'_p,i.
// Light bands follow relight.hpp: a light with fewer bands uses the leading coefficients
// (matrix: leading columns).

#include <span>
#include <vector>

#include "prt/compress/cpca.hpp"
#include "prt/relight/glossy.hpp"
#include "prt/relight/relight.hpp"

namespace prt::relight {

/// The per-frame cluster projections: for vectors K × (N+1) RGB values (c_k, d_k0 .. d_k,N−1);
/// for matrices K × (N+1) × B² RGB values (M_k L, B_k0 L, ...).
struct ClusterLight {
  int clusters = 0, basisCount = 0, coeffs = 0;  ///< coeffs = 1 (vectors) or B² (matrices)
  std::vector<float> rgb;                        ///< (k·(N+1) + j)·coeffs·3 + i·3 + c
};
/// Projects every cluster's mean and basis onto the light (the once-per-frame step).
ClusterLight projectClusters(const CompressedTransfer& transfer, const PreparedLight& light);

/// Diffuse (vector) kernel: out[v] = albedo(v) ⊙ (c_k + Σ_j w_vj d_kj). Throws prt::Error on a
/// matrix transfer or mismatched sizes. Independent of the thread count.
void relightCompressed(const CompressedTransfer& transfer, const PreparedLight& light,
                       std::span<const Rgb> albedo, std::span<Rgb> out);
/// Same with the projections already made (projectClusters) — what a frame loop calls.
void relightCompressed(const CompressedTransfer& transfer, const ClusterLight& projected,
                       std::span<const Rgb> albedo, std::span<Rgb> out);

/// Which implementation of a compressed-relighting kernel runs: the fastest this CPU supports
/// (AVX2+FMA where present, picked at run time), or the portable one — for tests that compare
/// the two and for measuring. Both equal relighting the reconstruction up to float rounding.
enum class CompressedKernel { Auto, Portable };
/// The diffuse kernel with an explicit implementation choice (layout:
/// src/relight/compressed_diffuse.cpp).
void relightCompressed(const CompressedTransfer& transfer, const ClusterLight& projected,
                       std::span<const Rgb> albedo, std::span<Rgb> out, CompressedKernel kernel);
/// Whether CompressedKernel::Auto picks a SIMD kernel on this CPU.
bool compressedSimdAvailable();

/// Glossy (matrix) kernel, as relightGlossy (glossy.hpp) on the reconstructed matrices.
void relightCompressedGlossy(const CompressedTransfer& transfer, const PreparedLight& light,
                             const PreparedMaterial& material, const GlossyView& view,
                             std::span<const Rgb> albedo, std::span<Rgb> out);
/// The same with an explicit implementation choice (layout: src/relight/compressed_glossy.cpp).
void relightCompressedGlossy(const CompressedTransfer& transfer, const PreparedLight& light,
                             const PreparedMaterial& material, const GlossyView& view,
                             std::span<const Rgb> albedo, std::span<Rgb> out,
                             CompressedKernel kernel);

/// Convenience, as relight() and relightGlossy(): rotates the light by `rotation`, prepares it
/// (and the material) and runs the kernel for the transfer's layout. For vectors the material's
/// kd, if set, replaces the albedo; matrices shade with the whole material and `view`.
RelightInfo relightCompressed(const CompressedTransfer& transfer, const sh::RgbSh& light,
                              const Material& material, const GlossyView& view,
                              std::span<const Rgb> albedo, std::span<Rgb> out,
                              const Mat3d& rotation = Mat3d::identity());

}  // namespace prt::relight
