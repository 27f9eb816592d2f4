#pragma once
// Clustered principal component analysis of a transfer field (Sloan, Hall, Hart & Snyder,
// "Clustered Principal Components for Precomputed Radiance Transfer", SIGGRAPH 2003, §3-4).
//
// Each row x_p of a field (its stride() floats: B² or B⁴ values × channels, treated as one signal
// vector of dimension D) is approximated inside its cluster k = k(p) by
//
//   x_p ≈ M_k + Σ_{j<N} w_pj B_kj,      w_pj = B_kj · (x_p − M_k),
//
// with M_k the cluster mean and B_k0..B_k,N−1 the orthonormal top-N principal directions of the
// cluster's covariance. Relighting is linear in the row, so exit radiance becomes
// (M_k·L) + Σ_j w_pj (B_kj·L): K(N+1) dot products per frame, then N multiply-adds per vertex
// (relight/compressed.hpp).
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
#include "prt/transfer/field.hpp"

namespace prt {

/// A CPCA-compressed transfer field. Not a third TransferLayout: a field's rows are addressable
/// floats every kernel can stream, while a compressed row is (cluster, N weights) meaningless
/// without its cluster's mean and basis. It keeps the shape of the field it came from (layout,
/// bands, channels, rows) so it can be reconstructed or relit with the same conventions.
struct CompressedTransfer {
  TransferLayout layout = TransferLayout::Vector;  ///< of the source rows
  TransferDomain domain = TransferDomain::Vertices;
  int bands = 0;
  int channels = 1;
  std::size_t vertexCount = 0;
  int clusters = 0;                    ///< K ≥ 1
  int basisCount = 0;                  ///< N ≥ 0 (0 = vector quantisation)
  std::vector<std::uint32_t> cluster;  ///< vertexCount cluster ids < K
  std::vector<float> weights;          ///< vertexCount × N
  std::vector<float> means;            ///< K × stride()
  std::vector<float> basis;            ///< K × N × stride(): B_kj at (k·N + j)·stride()

  /// Floats of one source row (as TransferField::stride()).
  std::size_t stride() const {
    return transferRowSize(layout, bands) * static_cast<std::size_t>(channels);
  }
  const float* mean(std::size_t k) const { return means.data() + k * stride(); }
  const float* basisVector(std::size_t k, std::size_t j) const {
    return basis.data() + (k * static_cast<std::size_t>(basisCount) + j) * stride();
  }
  /// Writes the approximation of row v (stride() floats) to out.
  void reconstructRow(std::size_t v, float* out) const;
  /// The whole approximated field.
  TransferField reconstruct() const;
  /// Bytes as stored: a uint16 (K ≤ 65536) or uint32 cluster id and N floats per row, plus
  /// K(N+1) rows of stride() floats.
  std::size_t bytes() const;
  /// Throws prt::Error("WHAT: ...") unless sizes agree, ids are < K and every value is finite.
  void check(const std::string& what) const;
};

struct CpcaOptions {
  int clusters = 1;        ///< K
  int basisCount = 0;      ///< N ≤ D
  std::uint64_t seed = 0;  ///< of the k-means++ seeding
  int maxIterations = 30;  ///< of the reassignment loop
  /// Converged when a pass lowers the total squared error by less than this fraction (0: run
  /// until no row moves or maxIterations).
  double tolerance = 1e-3;
};

/// How well a compressed field approximates its source.
struct CpcaStats {
  double squaredError = 0;      ///< Σ_p |x_p − x̂_p|²
  double signalEnergy = 0;      ///< Σ_p |x_p|²
  double relativeRms = 0;       ///< sqrt(squaredError / signalEnergy)
  double snrDb = 0;             ///< 10 log10(signalEnergy / squaredError) (inf if exact)
  double maxRowError = 0;       ///< max_p |x_p − x̂_p| (Euclidean, over the row's floats)
  double compressionRatio = 0;  ///< source bytes (4·rows·D) / bytes()
  double seconds = 0;           ///< wall time of the compression
  int iterations = 0;           ///< reassignment passes run
};

/// Compresses `field` (throws prt::Error on bad options: K < 1, K > rows, N < 0, N > D). When
/// `start` is given (same shape, any K, N) its cluster assignment replaces the seeding, so a
/// sweep over N can warm-start each run from the previous one. `progress` gets one tick per
/// iteration and may cancel.
CompressedTransfer compressCpca(const TransferField& field, const CpcaOptions& options,
                                CpcaStats* stats = nullptr,
                                const CompressedTransfer* start = nullptr,
                                const ProgressFn& progress = {});

/// The error statistics of `c` against `field` (seconds and iterations left 0).
CpcaStats measureCpca(const TransferField& field, const CompressedTransfer& c);

/// One (K, N) of a sweep.
struct CpcaSweepPoint {
  int clusters = 0, basisCount = 0;
  std::size_t bytes = 0;  ///< CompressedTransfer::bytes()
  CpcaStats stats;
};

/// Compresses with every K of `clusters` (each ≤ rows) and N = 0..maxBasis (≤ D), each N
/// warm-started from the clustering of N − 1 so the error never grows with N. With
/// stopAtError > 0 a K's sweep stops at the first N whose relative RMS error is ≤ stopAtError
/// (larger N only cost more). Points in order of K then N.
std::vector<CpcaSweepPoint> sweepCpca(const TransferField& field, const std::vector<int>& clusters,
                                      int maxBasis, std::uint64_t seed, int maxIterations,
                                      double tolerance, double stopAtError = 0,
                                      const ProgressFn& progress = {});

}  // namespace prt
