#pragma once
// The once-per-frame step of relighting CPCA-compressed transfer (Sloan, Hall, Hart & Snyder
// 2003, §5): relighting is linear in the row, so with x_r ≈ M_k + Σ_j w_rj B_kj every cluster's
// mean and basis vectors are projected onto the light once, and each row then costs N
// multiply-adds:
//
//   vectors:  c_k = M_k·L, d_kj = B_kj·L                          K(N+1) RGB values
//   matrices: L'_k0 = M_k L, L'_kj = B_kj L (B² × RGB each)       K(N+1)·B² RGB values
//
// The CPU kernels (relight.hpp) and the GPU viewers' cluster table (shader_transfer.hpp) both
// start here. A light with fewer bands than the transfer uses the leading coefficients
// (matrices: the leading columns).

#include <vector>

#include "prt/relight/relight.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

/// The per-frame cluster projections: for vectors K × (N+1) RGB values (c_k, d_k0 .. d_k,N−1);
/// for matrices K × (N+1) × B² RGB values (M_k L, B_k0 L, ...).
struct ClusterLight {
  int clusters = 0, basisCount = 0, coeffs = 0;  ///< coeffs = 1 (vectors) or B² (matrices)
  std::vector<float> rgb;                        ///< (k·(N+1) + j)·coeffs·3 + i·3 + c
};
/// Projects every cluster's mean and basis of a compressed transfer onto the light.
ClusterLight projectClusters(const Transfer& transfer, const PreparedLight& light);

}  // namespace prt::relight
