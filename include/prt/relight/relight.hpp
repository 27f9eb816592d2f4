#pragma once
// CPU relighting: per-vertex exit radiance from transfer and lighting,
//   R_c(p) = albedo_c(p) · Σ_i T_i(p) L_i,c        scalar transfer (channels = 1)
//   R_c(p) = albedo_c(p) · Σ_i T_i,c(p) L_i,c      RGB transfer    (channels = 3)
// (Sloan, Kautz & Snyder, "Precomputed Radiance Transfer for Real-Time Rendering in Dynamic,
// Low-Frequency Lighting Environments", SIGGRAPH 2002, §5.)
//
// Rotating the environment by R is done on the light's coefficients (sh::Rotation, one
// orthogonal (2l+1)² block per band), never by re-projecting: the result is exactly the
// relighting under the rotated band-limited light, L' = D(R) L, at O(B³) cost per frame.
//
// Band counts. SH bands are orthogonal, so a light with more bands than the transfer is cut to
// the transfer's bands exactly (the extra coefficients would meet zeros). A light with fewer
// bands than the transfer is an approximation (the transfer's upper bands see no light): we use
// the light's bands and report it in RelightInfo so the caller can warn.
//
// Cost: a dot product of B² (×3) floats per vertex against the same few hundred bytes of light —
// memory-bound, so the kernels are written to stream the transfer once with the light held in
// registers/L1; see docs/perf/relight.md.

#include <span>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/field.hpp"

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

/// Lighting laid out for the relighting kernels: rotated, cut to `bands`, in two layouts.
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

/// The kernel: out[v] = albedo(v) ⊙ T(v)·L for every vertex, in parallel. `albedo` holds one
/// value per vertex, or one value for all (uniform), or nothing (white). `out.size()` must equal
/// transfer.vertexCount. Allocation-free; results do not depend on the thread count.
void relight(const TransferField& transfer, const PreparedLight& light, std::span<const Rgb> albedo,
             std::span<Rgb> out);

/// Convenience: prepareLight with the environment rotated by `rotation` (a lobe along d moves to
/// R d), then the kernel.
RelightInfo relight(const TransferField& transfer, const sh::RgbSh& light,
                    std::span<const Rgb> albedo, std::span<Rgb> out,
                    const Mat3d& rotation = Mat3d::identity());

/// Same, returning a new vector.
std::vector<Rgb> relight(const TransferField& transfer, const sh::RgbSh& light,
                         std::span<const Rgb> albedo, const Mat3d& rotation = Mat3d::identity(),
                         RelightInfo* info = nullptr);

}  // namespace prt::relight
