#pragma once
// Clustered principal component analysis of a transfer (Sloan, Hall, Hart & Snyder,
// "Clustered Principal Components for Precomputed Radiance Transfer", SIGGRAPH 2003, §3-4).
//
// Each row x_p of a dense transfer (its stride() floats: B² or B⁴ values × channels, treated as one
// signal vector of dimension D) is approximated inside its cluster k = k(p) by
//
//   x_p ≈ M_k + Σ_{j<N} w_pj B_kj,      w_pj = B_kj · (x_p − M_k),
//
// with M_k the cluster mean and B_k0..B_k,N−1 the orthonormal top-N principal directions of the
// cluster's covariance. Relighting is linear in the row, so exit radiance becomes
// (M_k·L) + Σ_j w_pj (B_kj·L): K(N+1) dot products per frame, then N multiply-adds per vertex
// (relight/relight.hpp, relight/cluster_projection.hpp).
//
// The iteration (the paper's "iterative CPCA", a Lloyd iteration with PCA in place of the mean):
//   0. seed K clusters by k-means++ (Arthur & Vassilvitskii 2007) from a Pcg32 stream of `seed`;
//   1. per cluster, mean and top-N eigenvectors of the covariance (D×D, SelfAdjointEigenSolver)
//      or, when the cluster has fewer rows m than D, of the m×m Gram matrix (the "snapshot"
//      trick: B = Xcᵀu / |Xcᵀu|); above order 128 only the top N, by Lanczos (Spectra), with
//      the matrix applied as products with the centred rows, never formed;
//   2. reassign every row to the cluster whose mean + basis reconstructs it with least squared
//      error |x − M_k|² − Σ_j (B_kj·(x − M_k))², keeping its cluster on ties;
//   3. repeat until no row moves, a pass lowers the total error by less than `tolerance`
//      (relative), or maxIterations; then refit the bases to the last assignment.
// Both steps are optimal for the other's output, so the total squared error never increases
// across iterations (up to float rounding). An empty cluster is re-seeded with the row of largest
// error (lowest index on ties). N = 0 is vector quantisation (k-means); K = 1 is plain PCA.
//
// Determinism: rows are visited per index in parallel, clusters are gathered in row order and
// every sum runs in a fixed order (prt::parallelReduce with fixed chunks), so the result is
// bit-identical for any thread count.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/transfer/cpca_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

/// Compresses a dense transfer into a CPCA-compressed one of the same shape (throws prt::Error
/// on a compressed source or bad options: K < 1, K > rows, N < 0, N > D). When `start` is given
/// (a compressed transfer of the same shape and K, any N) its cluster assignment replaces the
/// seeding, so a sweep over N can warm-start each run from the previous one. `progress` gets
/// one tick per iteration and may cancel.
Transfer compressCpca(const Transfer& source, const CpcaOptions& options,
                      CpcaStats* stats = nullptr, const Transfer* start = nullptr,
                      const ProgressFn& progress = {});

/// The error statistics of `compressed` against the dense `source` (seconds and iterations
/// left 0).
CpcaStats measureCpca(const Transfer& source, const Transfer& compressed);

/// One (K, N) of a sweep.
struct CpcaSweepPoint {
  int clusters = 0, basisCount = 0;
  std::size_t bytes = 0;  ///< Transfer::bytes() of the compressed transfer
  CpcaStats stats;
};

/// Compresses with every K of `clusters` (each ≤ rows) and N = 0..maxBasis (≤ D), each N
/// warm-started from the clustering of N − 1 so the error never grows with N. With
/// stopAtError > 0 a K's sweep stops at the first N whose relative RMS error is ≤ stopAtError
/// (larger N only cost more). Points in order of K then N.
std::vector<CpcaSweepPoint> sweepCpca(const Transfer& source, const std::vector<int>& clusters,
                                      int maxBasis, const CpcaFit& fit, double stopAtError = 0,
                                      const ProgressFn& progress = {});

/// compressCpca through the warm-started chain N = 0..options.basisCount that sweepCpca runs,
/// so that a (K, N) picked from a sweep is reproduced exactly; stats.seconds sums the chain.
Transfer compressCpcaChain(const Transfer& source, const CpcaOptions& options, CpcaStats& stats,
                           const ProgressFn& progress = {});

}  // namespace prt
