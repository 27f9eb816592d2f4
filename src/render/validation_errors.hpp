#pragma once
// The error metrics of a validation over its vertices, the one definition for every basis:
// SH (validate.cpp, per band count) and Haar (validate_haar.cpp, per light budget) measure the
// relit radiance against the reference with the same columns (validate.hpp: rel RMSE,
// energy-weighted, mean and max of e(p), the negative share). Private to src/render.

#include <cstddef>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt::render {

inline double sumSq(const Rgb& c) {
  return double(c.x) * c.x + double(c.y) * c.y + double(c.z) * c.z;
}

/// The relative-RMSE metric over the validated vertices: per vertex and channel the weight
/// 1 / (R_ref² + ε), ε = 10⁻² mean(R_ref)², and the reference's own noise in it.
struct Metric {
  const std::vector<Rgb>& ref;
  const std::vector<Rgb>& stdError;
  double meanRef = 0;
  double eps = 0;

  Metric(const std::vector<Rgb>& reference, const std::vector<Rgb>& se)
      : ref(reference), stdError(se) {
    for (const Rgb& c : ref) meanRef += (double(c.x) + c.y + c.z) / 3.0;
    meanRef /= double(std::max<std::size_t>(ref.size(), 1));
    eps = 1e-2 * meanRef * meanRef + 1e-30;
  }
  double weight(std::size_t i, int c) const { return 1.0 / (double(ref[i][c]) * ref[i][c] + eps); }
  /// What an exact transfer's squared rel RMSE would be at vertex entry i: the reference noise.
  double noiseSq(std::size_t i) const {
    double s = 0;
    for (int c = 0; c < 3; ++c) s += double(stdError[i][c]) * stdError[i][c] * weight(i, c);
    return s / 3.0;
  }
  /// Σ_c (R − R_ref)² weight / 3 at vertex entry i.
  double errorSq(std::size_t i, const Rgb& prt) const {
    double a = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = double(prt[c]) - ref[i][c];
      a += d * d * weight(i, c) / 3.0;
    }
    return a;
  }
};


/// The columns validate.hpp's tables show, over every validated vertex.
struct ErrorColumns {
  double relRmse = 0, energyRel = 0, meanRel = 0, maxRel = 0, negativeShare = 0;
};

/// The columns of relit radiance `prt` (one per validated vertex) against metric.ref; a vertex
/// counts as negative where `counted` and some channel is below `negativeBelow`, as a share of
/// `negativeVertices`. `err` (optional) receives e(p) per vertex.
ErrorColumns errorColumns(const Metric& metric, const std::vector<Rgb>& prt,
                          const std::vector<char>& counted, double negativeBelow,
                          std::size_t negativeVertices, std::vector<float>* err = nullptr);

}  // namespace prt::render
