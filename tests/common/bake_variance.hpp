#pragma once
// The bake's own variance in validation's rel RMSE metric (render/validate.hpp), from one row
// set relit from two bakes of different seeds: ½ mean (R₁ − R₂)² / (R_ref² + ε), ε = 10⁻² m²,
// m the reference's mean (per row and channel; E[(R₁ − R₂)²] = 2 Var R). What rel RMSE² may
// hold beyond floor² + noise².

#include <vector>

#include "prt/core/vec.hpp"

namespace prt::testing {

inline double bakeVarianceOf(const std::vector<Rgb>& r1, const std::vector<Rgb>& r2,
                             const std::vector<Rgb>& ref) {
  double m = 0;
  for (const Rgb& c : ref) m += (double(c.x) + c.y + c.z) / 3.0;
  m /= double(ref.size());
  const double eps = 1e-2 * m * m;
  double sum = 0;
  for (std::size_t i = 0; i < ref.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = double(r1[i][c]) - r2[i][c];
      sum += 0.5 * d * d / (double(ref[i][c]) * ref[i][c] + eps);
    }
  return sum / (3.0 * double(ref.size()));
}

}  // namespace prt::testing
