// The once-per-frame projections of compressed transfer onto the light (cluster_projection.hpp).

#include "prt/relight/cluster_projection.hpp"

#include "kernels.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "prt/core/cpu.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/sh.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace prt::relight {

namespace {

/// Σ_{i<n} a_i b_i with eight running sums (a fixed order, so the compiler vectorises it without
/// reassociating: the result does not depend on the machine).
float dot8(const float* a, const float* b, std::size_t n) {
  float acc[8] = {};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t u = 0; u < 8; ++u) acc[u] += a[i + u] * b[i + u];
  for (std::size_t u = 0; i < n; ++i, ++u) acc[u] += a[i] * b[i];
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

/// out_c = Σ_{i<n} x_{3i+c} L_{3i+c}: twelve running sums (four per channel), fixed order.
void rgbDot(const float* x, const float* L, std::size_t n, float* out) {
  float acc[12] = {};
  const std::size_t m = 3 * n;
  std::size_t j = 0;
  for (; j + 12 <= m; j += 12)
    for (std::size_t u = 0; u < 12; ++u) acc[u] += x[j + u] * L[j + u];
  for (std::size_t u = 0; j < m; ++j, ++u) acc[u] += x[j] * L[j];
  for (std::size_t c = 0; c < 3; ++c) out[c] = (acc[c] + acc[c + 3]) + (acc[c + 6] + acc[c + 9]);
}

// o[3i + c] = Σ_{l<nb} X_il L_lc for one scalar B² × B² matrix X (the glossy per-frame step,
// K(N+1) matrices), the light as three planes of `pad` floats (zero past nb). Portable form.
void projectScalarMatrix(const float* x, std::size_t nB, std::size_t nb, const float* planes,
                         std::size_t pad, float* o) {
  for (std::size_t i = 0; i < nB; ++i) {
    const float* row = x + i * nB;
    for (std::size_t c = 0; c < 3; ++c) {
      float sum = 0.0f;
      for (std::size_t l = 0; l < nb; ++l) sum += row[l] * planes[c * pad + l];
      o[3 * i + c] = sum;
    }
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2,fma"))) inline float sumLanes(__m256 v) {
  const __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  const __m128 h = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(h, _mm_movehdup_ps(h)));
}

// The same with AVX2+FMA: per row, eight columns at a time (the last nb mod 8 by a masked load)
// into three accumulators, one sum across lanes per channel. Each row's sum runs in a fixed
// order, so the result does not depend on the thread count. (GCC's own vectorisation of an
// eight-lane portable loop, with permutes across channels, made this step 3.2 ms of a 6.3 ms
// glossy frame at K = 256, N = 8 on the loaded reference machine: ~1.4 G multiply-adds/s.)
__attribute__((target("avx2,fma"))) void projectScalarMatrixAvx2(const float* x, std::size_t nB,
                                                                 std::size_t nb,
                                                                 const float* planes,
                                                                 std::size_t pad, float* o) {
  const int tail = static_cast<int>(nb % 8);
  const __m256i mask =
      _mm256_cmpgt_epi32(_mm256_set1_epi32(tail), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  for (std::size_t i = 0; i < nB; ++i) {
    const float* row = x + i * nB;
    __m256 r = _mm256_setzero_ps(), g = r, b = r;
    std::size_t l = 0;
    for (; l + 8 <= nb; l += 8) {
      const __m256 v = _mm256_loadu_ps(row + l);
      r = _mm256_fmadd_ps(v, _mm256_loadu_ps(planes + l), r);
      g = _mm256_fmadd_ps(v, _mm256_loadu_ps(planes + pad + l), g);
      b = _mm256_fmadd_ps(v, _mm256_loadu_ps(planes + 2 * pad + l), b);
    }
    if (tail) {  // the planes are zero-padded to `pad` ≥ l + 8: only the row load is masked
      const __m256 v = _mm256_maskload_ps(row + l, mask);
      r = _mm256_fmadd_ps(v, _mm256_loadu_ps(planes + l), r);
      g = _mm256_fmadd_ps(v, _mm256_loadu_ps(planes + pad + l), g);
      b = _mm256_fmadd_ps(v, _mm256_loadu_ps(planes + 2 * pad + l), b);
    }
    o[3 * i] = sumLanes(r);
    o[3 * i + 1] = sumLanes(g);
    o[3 * i + 2] = sumLanes(b);
  }
}
#endif

}  // namespace

namespace detail {

AlignedFloats alignedZeros(std::size_t n) {
  const std::size_t bytes = std::max<std::size_t>(32, (n * sizeof(float) + 31) & ~std::size_t(31));
  float* p = static_cast<float*>(std::aligned_alloc(32, bytes));
  if (!p) throw Error("relight: out of memory (" + std::to_string(bytes) + " bytes)");
  std::fill_n(p, bytes / sizeof(float), 0.0f);
  return AlignedFloats(p);
}

}  // namespace detail

ClusterLight projectClusters(const Transfer& t, const PreparedLight& light) {
  if (!t.compressed()) throw Error("relight: cluster projections need compressed transfer");
  if (light.bands < 1 || light.bands > t.bands())
    throw Error("relight: the prepared light has " + std::to_string(light.bands) +
                " bands, the transfer " + std::to_string(t.bands()));
  const CpcaRows& cp = t.cpca();
  const std::size_t C = static_cast<std::size_t>(t.channels()),
                    nB = static_cast<std::size_t>(t.coeffs());
  const std::size_t nb = static_cast<std::size_t>(light.bands * light.bands);
  const std::size_t W = static_cast<std::size_t>(cp.basisCount) + 1;
  const float* L = light.interleaved.data();  // (r, g, b) per coefficient
  ClusterLight p;
  p.clusters = cp.clusters;
  p.basisCount = cp.basisCount;
  p.coeffs = t.isMatrix() ? static_cast<int>(nB) : 1;
  const std::size_t per = static_cast<std::size_t>(p.coeffs) * 3;
  p.rgb.assign(static_cast<std::size_t>(cp.clusters) * W * per, 0.0f);
  // The light as three zero-padded planes (channels apart) for scalar transfer: each projection
  // of a scalar vector is three contiguous dots, of a scalar matrix three per row.
  const std::size_t pad = (nb + 7) & ~std::size_t(7);
  std::vector<float> planes(3 * pad, 0.0f);
  for (std::size_t l = 0; l < nb; ++l)
    for (std::size_t c = 0; c < 3; ++c) planes[c * pad + l] = L[3 * l + c];
  parallelFor(static_cast<std::size_t>(cp.clusters), 4, [&](std::size_t kb, std::size_t ke) {
    for (std::size_t k = kb; k < ke; ++k)
      for (std::size_t j = 0; j < W; ++j) {
        const float* x = j == 0 ? t.clusterMean(k) : t.basisVector(k, j - 1);
        float* o = p.rgb.data() + (k * W + j) * per;
        if (!t.isMatrix() && C == 1) {
          // o_c = Σ_{i<nb} x_i L_{i,c}: scalar transfer multiplies all three light channels.
          for (std::size_t c = 0; c < 3; ++c) o[c] = dot8(x, planes.data() + c * pad, nb);
        } else if (!t.isMatrix()) {
          // RGB rows (i·3 + c) against the interleaved light: one elementwise product of 3·nb
          // floats, summed per channel.
          rgbDot(x, L, nb, o);
        } else if (C == 1) {
#if defined(__x86_64__) && defined(__GNUC__)
          if (simdAvx2Fma())
            projectScalarMatrixAvx2(x, nB, nb, planes.data(), pad, o);
          else
#endif
            projectScalarMatrix(x, nB, nb, planes.data(), pad, o);
        } else {
          // (X L_c)_i = Σ_{j<nb} X_{ij} L_{j,c}, entry (i·B² + j)·C + c.
          for (std::size_t i = 0; i < nB; ++i)
            for (std::size_t l = 0; l < nb; ++l)
              for (std::size_t c = 0; c < 3; ++c)
                o[3 * i + c] += x[(i * nB + l) * C + (C == 1 ? 0 : c)] * L[3 * l + c];
        }
      }
  });
  return p;
}

}  // namespace prt::relight
