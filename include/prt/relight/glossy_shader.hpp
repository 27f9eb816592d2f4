#pragma once
// The glossy kernels as the vertex shaders take them (prt view --glossy-on gpu, and the web page
// for CPCA-compressed matrices). shaders/prt_sh_basis.glsl evaluates the real SH basis without
// its normalisation N_lm (the associated-Legendre recurrence times (x + iy)^m), so the per-band
// kernels of PreparedMaterial (glossy.hpp) are handed over multiplied by it:
//   N_lm = sqrt((2l+1)/4π · (l−|m|)!/(l+|m|)!), times √2 for m ≠ 0 (real SH),
//   diffuse_i = (A_l/π)·N_lm,   glossy_i = Λ_l·N_lm,   i = l(l+1)+m.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <span>

#include "prt/core/vec.hpp"

namespace prt::relight {

/// Bands the shaders' glossy path evaluates: their SH arrays hold 64 coefficients.
inline constexpr int kMaxShaderGlossyBands = 8;

/// Per-coefficient kernel × N_lm for the first 64 coefficients (zero past the kernel's size).
inline std::array<float, 64> shaderKernel(std::span<const float> perCoefficient) {
  std::array<float, 64> out{};
  for (int l = 0; l < kMaxShaderGlossyBands; ++l)
    for (int m = -l; m <= l; ++m) {
      const int i = l * (l + 1) + m, am = std::abs(m);
      double ratio = 1.0;  // (l−|m|)! / (l+|m|)!
      for (int k = l - am + 1; k <= l + am; ++k) ratio /= k;
      double norm = std::sqrt((2 * l + 1) / (4 * kPi) * ratio);
      if (m != 0) norm *= std::sqrt(2.0);
      if (std::size_t(i) < perCoefficient.size()) out[i] = float(perCoefficient[i] * norm);
    }
  return out;
}

}  // namespace prt::relight
