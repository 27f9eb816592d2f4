#pragma once
// Glossy (matrix) transfer seen from one eye, collapsed to a vector transfer (Sloan, Kautz &
// Snyder 2002, §6): per row and colour channel c,
//
//   t_c(p) = kd_c(p) M_pᵀ d(p) + ks_c M_pᵀ g(p, v)      (d, g: relight.hpp)
//
// so that relighting t with a white albedo equals relighting the matrices with the material for
// every light L (any band count up to the transfer's). One pass over the matrices — a frame's
// work — when the eye, the material or the transfer changes; after that a light that turns
// costs one vector relighting (3·B² floats per row instead of B⁴·C). relight::Relighter uses it
// for frames in which only the light changed.

#include "prt/core/vec.hpp"
#include "prt/relight/relight.hpp"
#include "prt/transfer/prepared_material.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

/// The collapsed transfer (dense vectors, RGB, same rows) of dense matrices; the surface's
/// albedo (kd unless the material sets one) is folded in. Throws prt::Error on another layout or
/// representation, or mismatched sizes.
Transfer viewTransfer(const Transfer& transfer, const PreparedMaterial& material,
                      const Surface& surface, const Vec3f& eye);

/// The diffuse part of glossy transfer: per row t = M_pᵀ d(n_p), d_i = (A_l/π) Y_i(n_p) — the
/// vector transfer a diffuse surface at p relights with (R = albedo ⊙ t·L), what a vector bake
/// of the same mode estimates. Dense vectors with the matrices' channels; compressed matrices
/// are reconstructed row by row. Throws prt::Error on vectors or a normal count that is not
/// one per row.
Transfer diffuseTransfer(const Transfer& matrices, std::span<const Vec3f> normals);

}  // namespace prt::relight
