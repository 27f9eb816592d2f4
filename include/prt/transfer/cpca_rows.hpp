#pragma once
// The data of CPCA-compressed transfer (Sloan, Hall, Hart & Snyder, "Clustered Principal
// Components for Precomputed Radiance Transfer", SIGGRAPH 2003): one of prt::Transfer's two
// representations. Each row x_r (stride() floats of its shape) is approximated inside its
// cluster k = k(r) by
//
//   x_r ≈ M_k + Σ_{j<N} w_rj B_kj,
//
// M_k the cluster mean, B_k0..B_k,N−1 its principal directions. The fitting is compress/cpca.hpp;
// this type is only the numbers, so that anything that reads or relights a compressed bake links
// no eigensolver.

#include <cstdint>
#include <vector>

#include "prt/core/float_array.hpp"

namespace prt {

struct CpcaRows {
  int clusters = 0;                    ///< K ≥ 1
  int basisCount = 0;                  ///< N ≥ 0 (0 = vector quantisation)
  std::vector<std::uint32_t> cluster;  ///< one cluster id < K per row
  FloatArray weights;                  ///< rows × N
  FloatArray means;                    ///< K × stride
  FloatArray basis;                    ///< K × N × stride: B_kj at (k·N + j)·stride
};

}  // namespace prt
