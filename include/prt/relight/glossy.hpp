#pragma once
// View-dependent relighting of glossy (matrix) transfer on the CPU (Sloan, Kautz & Snyder 2002,
// §6). Per vertex p, with L'_p = M_p L the SH of the light arriving at p (field.hpp) and the
// material's kernels (material.hpp):
//
//   e_c(p, v) = kd_c(p) Σ_i d_i(p) (M_p L_c)_i  +  ks_c Σ_i g_i(p, v) (M_p L_c)_i
//   d_i = (A_l/π) Y_i(n_p)        (the clamped cosine about the normal: diffuse)
//   g_i = Λ_l Y_i(R_p(v))         (the lobe about the reflected view direction)
//
// Cost. Written as u = M_pᵀ d and w = M_pᵀ g (one pass over the B⁴ entries of M_p, two FMAs
// each), then e_c = kd_c (u·L_c) + ks_c (w·L_c): a third fewer operations than forming M_p L
// for three channels, and the matrix is streamed exactly once per frame — the kernel is bound by
// memory bandwidth (4 bytes per entry against 2 FMAs). See docs/perf/relight.md.
//
// Band counts: a light with fewer bands than the transfer uses the leading columns of M_p (the
// transferred light keeps all the transfer's bands); one with more is cut (exact).

#include <optional>
#include <span>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/relight/relight.hpp"
#include "prt/transfer/field.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/prepared_material.hpp"

namespace prt::relight {

/// The material's kernels and response vectors live with the material (transfer module); the
/// matrix bake uses them too, at its bounce hits.
using prt::PreparedMaterial;
using prt::prepareMaterial;

/// Where the surface is and where it is seen from.
struct GlossyView {
  std::span<const Vec3f> positions;  ///< one per transfer row
  std::span<const Vec3f> normals;    ///< unit, one per transfer row
  Vec3f eye;                         ///< the viewer, world space
};

/// The kernel: out[v] = e(p_v, normalize(eye − p_v)) for every row, in parallel. `albedo` as in
/// relight() (per vertex, one, or none = white) is kd unless the material sets it. Throws
/// prt::Error on mismatched sizes. Allocation-free per vertex; independent of the thread count.
void relightGlossy(const TransferField& transfer, const PreparedLight& light,
                   const PreparedMaterial& material, const GlossyView& view,
                   std::span<const Rgb> albedo, std::span<Rgb> out);

/// The glossy transfer seen from one eye, collapsed to a vector transfer (3 channels): per vertex
/// and colour channel c,
///   t_c(p) = kd_c(p) M_pᵀ d(p) + ks_c M_pᵀ g(p, v)
/// so that relight(t, L, white) equals relightGlossy(transfer, L, material, view, albedo) for
/// every light L (any band count up to the transfer's). One pass over the matrices — a frame's
/// work — when the eye, the material or the transfer changes; after that a light that turns
/// costs one vector relighting (3·B² floats per vertex instead of B⁴·C). Throws prt::Error on
/// mismatched sizes.
TransferField viewTransfer(const TransferField& transfer, const PreparedMaterial& material,
                           const GlossyView& view, std::span<const Rgb> albedo);

/// Convenience: rotates the light by `rotation` (a lobe along d moves to R d), prepares light and
/// material, runs the kernel.
RelightInfo relightGlossy(const TransferField& transfer, const sh::RgbSh& light,
                          const Material& material, const GlossyView& view,
                          std::span<const Rgb> albedo, std::span<Rgb> out,
                          const Mat3d& rotation = Mat3d::identity());

}  // namespace prt::relight
