#pragma once
// Least squares conformal maps: B. Lévy, S. Petitjean, N. Ray, J. Maillot, "Least Squares
// Conformal Maps for Automatic Texture Atlas Generation", SIGGRAPH 2002.
//
// A map (u, v) of a triangulated surface to the plane is conformal on a triangle when its
// gradients are orthogonal and of equal length, ∇v = n × ∇u (Cauchy–Riemann). Writing
// U = u + i v and, in an orthonormal frame of the triangle's plane, the complex vertex
// positions z_k = x_k + i y_k, the condition becomes (Lévy et al., eq. 6)
//
//     Σ_k W_k U_k = 0,   W_k = z_{k+2} − z_{k+1}   (corners k = 0, 1, 2, indices mod 3),
//
// and the map minimising the conformal energy
//
//     C(U) = Σ_T |Σ_k W_{T,k} U_k|² / d_T,   d_T = twice the area of T,
//
// is unique up to a similarity; pinning two vertices fixes it. Split into real and imaginary
// parts this is a sparse linear least-squares problem A x = b in the free (u, v) (two rows per
// triangle: Σ a_k u_k − b_k v_k and Σ b_k u_k + a_k v_k, with W_k = a_k + i b_k, over √d_T),
// solved here through its normal equations AᵀA x = Aᵀb with a sparse Cholesky factorisation
// (Eigen's SimplicialLDLT; AᵀA is symmetric positive definite once two vertices are pinned
// and the chart is edge-connected). The identity z ↦ z makes every term vanish while the
// reflection z ↦ z̄ does not, so the map keeps the triangles' orientation: counter-clockwise
// triangles in 3D (seen from their normal) stay counter-clockwise in the plane, unless the
// chart folds (see the driver's check).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt {

using Uv2 = std::array<double, 2>;

/// The LSCM parameterisation of one chart: `positions` of its vertices and its `triangles`
/// (local indices, counter-clockwise). The two vertices farthest apart along the chart's
/// longest bounding-box axis are pinned to (0, 0) and (their distance, 0), so lengths are of the
/// order of the chart's. Triangles without area (relative to the chart's) count with a small
/// weight as if equilateral, which keeps the system regular without pulling on the rest.
/// Returns one (u, v) per vertex, or an empty vector when the system cannot be solved (fewer
/// than three vertices, a chart not connected through edges).
std::vector<Uv2> lscm(std::span<const Vec3d> positions,
                      std::span<const std::array<std::uint32_t, 3>> triangles);

}  // namespace prt
