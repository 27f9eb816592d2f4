#include "prt/core/sampling.hpp"

namespace prt {

OwenSobol2D::OwenSobol2D(std::uint32_t n) : rev1_(n) {
  // Gray-code order would be cheaper, but the table is built once per bake and must hold the
  // points in natural order (prefixes of length 2^m are then (0,m,2)-nets).
  for (std::uint32_t i = 0; i < n; ++i) rev1_[i] = reverseBits(sobol1(i));
}

// Compiled for AVX2 and SSE4.1 beside the SSE2 baseline, picked at load time (GCC function
// multiversioning): the hash needs 32-bit vector multiplies (pmulld, SSE4.1) to vectorise. All
// versions give identical bits: IEEE operations in the same order, no FMA contraction (ISO mode).
// GCC only: clang 14 (the fuzz build) emits no symbol for a multiversioned member function.
#if defined(__GNUC__) && !defined(__clang__)
#define PRT_TARGET_CLONES __attribute__((target_clones("avx2", "sse4.1", "default")))
#else
#define PRT_TARGET_CLONES
#endif
PRT_TARGET_CLONES void OwenSobol2D::cosineBatch(std::uint32_t first, std::uint32_t count,
                                                std::uint32_t seed0, std::uint32_t seed1, float* x,
                                                float* y, float* z) const {
  float u1[64], u2[64];
  if (count > 64) count = 64;
  const std::uint32_t* rev1 = rev1_.data() + first;
  for (std::uint32_t j = 0; j < count; ++j) {
    u1[j] = toUnitFloat(reverseBits(laineKarrasPermutation(first + j, seed0)));
    u2[j] = toUnitFloat(reverseBits(laineKarrasPermutation(rev1[j], seed1)));
  }
  // cosineHemisphere and sinCos2Pi, the quadrant switch written as selects. (GCC vectorises
  // neither loop with the project's flags: kept as plain array loops for -march=native builds.)
  for (std::uint32_t j = 0; j < count; ++j) {
    const float t = 4.0f * u1[j];
    const float k = static_cast<float>(static_cast<int>(t + 0.5f));  // floor: t + 0.5 > 0
    const float a = (t - k) * (0.5f * kPif);
    const float a2 = a * a;
    const float sa = a * (1.0f + a2 * (-1.0f / 6 + a2 * (1.0f / 120 + a2 * (-1.0f / 5040))));
    const float ca =
        1.0f + a2 * (-0.5f + a2 * (1.0f / 24 + a2 * (-1.0f / 720 + a2 * (1.0f / 40320))));
    const int q = static_cast<int>(k) & 3;
    const float sinPhi = q == 0 ? sa : (q == 1 ? ca : (q == 2 ? -sa : -ca));
    const float cosPhi = q == 0 ? ca : (q == 1 ? -sa : (q == 2 ? -ca : sa));
    const float sinTheta = std::sqrt(u2[j]);
    const float cosTheta = std::sqrt(std::max(0.0f, 1.0f - u2[j]));
    x[j] = sinTheta * cosPhi;
    y[j] = sinTheta * sinPhi;
    z[j] = cosTheta;
  }
}

}  // namespace prt
