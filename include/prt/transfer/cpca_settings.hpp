#pragma once
// How a transfer was CPCA-compressed (compress/cpca.hpp fits it; the bake file stores it):
// the options a fit takes and the error it reports. Types only.

#include <cstdint>

namespace prt {

/// How the clustering ran (stored with the compressed transfer; K and N are the rows' own).
struct CpcaFit {
  std::uint64_t seed = 0;  ///< of the k-means++ seeding
  int maxIterations = 30;  ///< of the reassignment loop
  /// Converged when a pass lowers the total squared error by less than this fraction (0: run
  /// until no row moves or maxIterations).
  double tolerance = 1e-3;
  bool operator==(const CpcaFit&) const = default;
};

/// What a fit takes.
struct CpcaOptions : CpcaFit {
  int clusters = 1;    ///< K
  int basisCount = 0;  ///< N ≤ D
};

/// How well a compressed transfer approximates its source.
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

/// The record a compressed transfer carries: how it was fitted and its error.
struct CpcaRecord {
  CpcaFit fit;
  CpcaStats stats;
};

}  // namespace prt
