#pragma once
// CPU relighting: exit radiance per row of a transfer, whatever its layout and representation,
// through one entry point (Sloan, Kautz & Snyder 2002, §5–6; Sloan, Hall, Hart & Snyder 2003,
// §5 for compressed rows). Inside, one kernel per layout × representation:
//
//   dense vectors    R_c(p) = kd_c(p) · Σ_i T_i,c(p) L_i,c          (scalar: T_i,c = T_i)
//   dense matrices   e_c(p, v) = kd_c(p) d(p)·(M_p L_c) + ks_c g(p, v)·(M_p L_c)
//                    d_i = (A_l/π) Y_i(n_p), g_i = Λ_l Y_i(R_p(v))   (material.hpp)
//                    written as u = M_pᵀ d, w = M_pᵀ g, one pass over the B⁴ entries of M_p
//   CPCA vectors     R(p) = kd(p) ⊙ (M_k·L + Σ_j w_pj (B_kj·L)), the K(N+1) dots once per call
//   CPCA matrices    L'_p = M_k L + Σ_j w_pj (B_kj L) (B² × RGB per cluster vector, once per
//                    call), then the glossy shading above on L'_p
//
// kd is the material's diffuse colour when it sets one, else the surface's albedo (one per row,
// one, or none: albedo.hpp). Vectors are diffuse: a material's lobe needs a matrix (callers
// warn). Matrices are view-dependent: each row is seen from `eye`.
//
// Rotating the environment by R is done on the light's coefficients (sh::Rotation, one
// orthogonal (2l+1)² block per band), never by re-projecting: the result is exactly the
// relighting under the rotated band-limited light, L' = D(R) L, at O(B³) cost per frame.
//
// Band counts. SH bands are orthogonal, so a light with more bands than the transfer is cut to
// the transfer's bands exactly (the extra coefficients would meet zeros). A light with fewer
// bands than the transfer is an approximation (the transfer's upper bands — for matrices its
// columns — see no light): the light's bands are used and RelightInfo says so, so the caller can
// warn. To relight with fewer bands than baked, cut the transfer (Transfer::cut).
//
// Cost: memory-bound for dense rows (a dot product of B² (×3) floats, or one pass over a
// matrix, against the same few hundred bytes of light), compute-bound for compressed matrices;
// see docs/perf/relight.md and docs/perf/cpca.md. Every kernel has an AVX2+FMA form and a
// portable one (core/cpu.hpp picks; results agree to float rounding) and is independent of the
// thread count.

#include <span>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/prepared_material.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

/// How the band counts of light and transfer were reconciled.
struct RelightInfo {
  int bands = 0;                   ///< bands used: min(light, transfer)
  int lightBands = 0;              ///< bands of the light given
  int transferBands = 0;           ///< bands of the transfer given
  bool lightTruncated = false;     ///< light had more bands than the transfer (exact, no warning)
  bool transferTruncated = false;  ///< light had fewer bands: transfer's upper bands unused
  /// A one-line warning when transferTruncated, else "".
  std::string warning() const;
};

/// Lighting laid out for the kernels: rotated, cut to `bands`, in two layouts.
struct PreparedLight {
  int bands = 0;
  /// Scalar-transfer layouts: 3 planes (r, g, b) of B² floats padded to a multiple of 4 (P),
  /// then B² × 3 × 4 floats with L_i,c four times at P + 12 i + 4 c.
  std::vector<float> planar;
  std::vector<float> interleaved;  ///< B² × 3: (r, g, b) per coefficient (RGB transfer)
};

/// Reconciles bands (see above), rotates by `rotation` if given (its bands must be at least the
/// bands used) and lays the light out for the kernels. Allocates; cheap (B² values).
PreparedLight prepareLight(const sh::RgbSh& light, int transferBands,
                           const sh::Rotation* rotation = nullptr, RelightInfo* info = nullptr);
/// The same from coefficients already rotated and cut: (r, g, b) per coefficient, b² of them.
PreparedLight prepareLight(std::span<const Rgb> rotated, int bands);

/// Where the transfer's rows are: per row a position and a unit normal (matrices need them:
/// the view and the lobe), and the albedo (one per row, one, or none = white).
struct Surface {
  std::span<const Vec3f> positions;
  std::span<const Vec3f> normals;
  std::span<const Rgb> albedo;
};

/// Throws prt::Error("relight: ...") for a Haar transfer: SH light cannot relight it (its rows
/// are wavelet terms; relight_haar.hpp relights it under a Haar light). Every SH entry point
/// here and relight::Relighter check it first.
void requireShTransfer(const Transfer& transfer);

/// The one entry point: out[r] = exit radiance of row r of `transfer` under `light` rotated by
/// `rotation` (a lobe along d moves to R d), with `material`, seen from `eye` (matrices only).
/// `out.size()` must equal transfer.rowCount(). Throws prt::Error on mismatched sizes.
RelightInfo relight(const Transfer& transfer, const sh::RgbSh& light, const Material& material,
                    const Surface& surface, const Vec3f& eye, std::span<Rgb> out,
                    const Mat3d& rotation = Mat3d::identity());
/// Same, returning a new vector.
std::vector<Rgb> relight(const Transfer& transfer, const sh::RgbSh& light, const Material& material,
                         const Surface& surface, const Vec3f& eye,
                         const Mat3d& rotation = Mat3d::identity(), RelightInfo* info = nullptr);

/// The entry point for a frame loop that has already rotated and laid out the light (bands ≤
/// the transfer's) and prepared the material at the transfer's bands: allocation-free for dense
/// rows.
void relightPrepared(const Transfer& transfer, const PreparedLight& light,
                     const PreparedMaterial& material, const Surface& surface, const Vec3f& eye,
                     std::span<Rgb> out);

}  // namespace prt::relight
