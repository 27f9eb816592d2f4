// The dense vector kernels of relighting (relight.hpp): R(p) = albedo(p) ⊙ T(p)·L, scalar and
// RGB transfer, specialised on the band count (sh::dispatchBands) and picked per CPU.

#include "kernels.hpp"

#include <algorithm>
#include <string>

#include "prt/core/cpu.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/sh_fixed.hpp"

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define PRT_RELIGHT_AVX2 1
#endif

namespace prt::relight {

namespace {

// out[v + k] = albedo(v + k) ⊙ (r[k], g[k], b[k]) for k < K: the write-back of the blocked kernels.
template <int K>
[[gnu::always_inline]] inline void writeBlock(const float* r, const float* g, const float* b,
                                              std::size_t v, const Albedo& albedo, Rgb* out) {
  for (int k = 0; k < K; ++k) {
    const Rgb a = albedo.at(v + k);
    out[v + k] = Rgb(r[k] * a.x, g[k] * a.y, b[k] * a.z);
  }
}

// Scalar transfer. `planar` holds the light as three planes (r, g, b) of `pad` floats each
// (pad = B² rounded up to a multiple of 4, zero-filled), so plane c starts at planar + c·pad.
//
// Portable form, one vertex at a time (also the last vertices of a range on SSE machines).
template <int N>
void scalarOne(const float* transfer, std::size_t stride, const float* planar, int n,
               const Albedo& albedo, Rgb* out, std::size_t begin, std::size_t end) {
  const int count = N > 0 ? N : n;
  const int pad = (count + 3) & ~3;
  for (std::size_t v = begin; v < end; ++v) {
    const float* t = transfer + v * stride;
    float acc[3] = {0.0f, 0.0f, 0.0f};
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < count; ++i) acc[c] += t[i] * planar[c * pad + i];
    const Rgb a = albedo.at(v);
    out[v] = Rgb(acc[0] * a.x, acc[1] * a.y, acc[2] * a.z);
  }
}

#if defined(__SSE2__)
// Scalar transfer, fast path for B ≤ 5: four vertices at a time in structure-of-arrays form. Each
// group of four coefficients of the four vertices (a 4×4 block of the transfer array) is transposed
// in registers (8 shuffles), after which coefficient i of all four vertices sits in one register
// and is multiplied by the broadcast light L_i,c (pre-splatted in `splat`) into three independent
// accumulators (r, g, b of four vertices): ~1.5 arithmetic ops per transfer float. (The naive
// per-vertex form is one dependent chain of N adds per vertex, latency-bound at ~4x slower.)
template <int N>
void scalarBlock4(const float* transfer, std::size_t stride, const float* splat, int n,
                  const Albedo& albedo, Rgb* out, std::size_t begin, std::size_t end) {
  const int count = N > 0 ? N : n;
  const int groups = count / 4;
  std::size_t v = begin;
  for (; v + 4 <= end; v += 4) {
    const float* t0 = transfer + v * stride;
    const float* t1 = t0 + stride;
    const float* t2 = t1 + stride;
    const float* t3 = t2 + stride;
    __m128 r = _mm_setzero_ps(), g = _mm_setzero_ps(), b = _mm_setzero_ps();
    auto madd = [&](__m128 x, int i) {
      const float* l = splat + 12 * i;
      r = _mm_add_ps(r, _mm_mul_ps(x, _mm_loadu_ps(l)));
      g = _mm_add_ps(g, _mm_mul_ps(x, _mm_loadu_ps(l + 4)));
      b = _mm_add_ps(b, _mm_mul_ps(x, _mm_loadu_ps(l + 8)));
    };
#pragma GCC unroll 32
    for (int q = 0; q < groups; ++q) {
      __m128 a0 = _mm_loadu_ps(t0 + 4 * q), a1 = _mm_loadu_ps(t1 + 4 * q);
      __m128 a2 = _mm_loadu_ps(t2 + 4 * q), a3 = _mm_loadu_ps(t3 + 4 * q);
      _MM_TRANSPOSE4_PS(a0, a1, a2, a3);  // now a_k = coefficient 4q+k of vertices v..v+3
      madd(a0, 4 * q);
      madd(a1, 4 * q + 1);
      madd(a2, 4 * q + 2);
      madd(a3, 4 * q + 3);
    }
    for (int i = 4 * groups; i < count; ++i) madd(_mm_setr_ps(t0[i], t1[i], t2[i], t3[i]), i);
    alignas(16) float rs[4], gs[4], bs[4];
    _mm_store_ps(rs, r);
    _mm_store_ps(gs, g);
    _mm_store_ps(bs, b);
    writeBlock<4>(rs, gs, bs, v, albedo, out);
  }
  for (; v < end; ++v) {  // the last 0..3 vertices
    const float* t = transfer + v * stride;
    float acc[3] = {0.0f, 0.0f, 0.0f};
    for (int i = 0; i < count; ++i)
      for (int c = 0; c < 3; ++c) acc[c] += t[i] * splat[12 * i + 4 * c];
    const Rgb a = albedo.at(v);
    out[v] = Rgb(acc[0] * a.x, acc[1] * a.y, acc[2] * a.z);
  }
}
#if defined(PRT_RELIGHT_AVX2)
// The same four-coefficient blocks for eight vertices at once on CPUs with AVX2 and FMA (picked
// at run time; the SSE2 form above stays the baseline). Rows k and k+4 share a 256-bit register
// (one per 128-bit half), so one in-lane 4×4 transpose turns both halves at once; then each
// coefficient is one fused multiply–add per channel for eight vertices: ~1 instruction per
// transfer float against ~2 for SSE2, which makes the kernel memory-bound (docs/perf/relight.md).
// FMA rounds once where SSE2 rounds twice, so results differ from the SSE2 path in the last bit;
// within one machine they are the same for any thread count.
template <int N>
__attribute__((target("avx2,fma"))) void scalarBlock8(const float* transfer, std::size_t stride,
                                                      const float* splat, int n,
                                                      const Albedo& albedo, Rgb* out,
                                                      std::size_t begin, std::size_t end) {
  const int count = N > 0 ? N : n;
  const int groups = count / 4;
  std::size_t v = begin;
  for (; v + 8 <= end; v += 8) {
    const float* t[8];
    for (int k = 0; k < 8; ++k) t[k] = transfer + (v + k) * stride;
    __m256 r = _mm256_setzero_ps(), g = r, b = r;
#define PRT_MADD8(x, i)                                      \
  do {                                                       \
    const __m256 x_ = (x);                                   \
    const float* l_ = splat + 12 * (i);                      \
    r = _mm256_fmadd_ps(x_, _mm256_broadcast_ss(l_), r);     \
    g = _mm256_fmadd_ps(x_, _mm256_broadcast_ss(l_ + 4), g); \
    b = _mm256_fmadd_ps(x_, _mm256_broadcast_ss(l_ + 8), b); \
  } while (0)
#pragma GCC unroll 32
    for (int q = 0; q < groups; ++q) {
      __m256 a[4];
      for (int k = 0; k < 4; ++k)
        a[k] = _mm256_set_m128(_mm_loadu_ps(t[k + 4] + 4 * q), _mm_loadu_ps(t[k] + 4 * q));
      const __m256 t0 = _mm256_unpacklo_ps(a[0], a[1]), t1 = _mm256_unpackhi_ps(a[0], a[1]);
      const __m256 t2 = _mm256_unpacklo_ps(a[2], a[3]), t3 = _mm256_unpackhi_ps(a[2], a[3]);
      PRT_MADD8(_mm256_shuffle_ps(t0, t2, 0x44), 4 * q);  // coefficient 4q of vertices 0..3 | 4..7
      PRT_MADD8(_mm256_shuffle_ps(t0, t2, 0xEE), 4 * q + 1);
      PRT_MADD8(_mm256_shuffle_ps(t1, t3, 0x44), 4 * q + 2);
      PRT_MADD8(_mm256_shuffle_ps(t1, t3, 0xEE), 4 * q + 3);
    }
    for (int i = 4 * groups; i < count; ++i)
      PRT_MADD8(
          _mm256_setr_ps(t[0][i], t[1][i], t[2][i], t[3][i], t[4][i], t[5][i], t[6][i], t[7][i]),
          i);
#undef PRT_MADD8
    alignas(32) float rs[8], gs[8], bs[8];
    _mm256_store_ps(rs, r);
    _mm256_store_ps(gs, g);
    _mm256_store_ps(bs, b);
    writeBlock<8>(rs, gs, bs, v, albedo, out);
  }
  // The last 0..7 vertices through the SSE2 form.
  scalarBlock4<N>(transfer, stride, splat, n, albedo, out, v, end);
}

#endif

// (At B ≤ 5 the four-vertex form wins: no per-vertex horizontal sum. At larger B its
// loop-invariant light registers no longer fit, GCC spills them and the per-vertex form below
// is ~3x faster; see docs/perf/relight.md.)
// Fast path: the vertex's coefficients four at a time against the three light planes (aligned,
// so the light loads fold into the multiplies): 1 load, 3 multiplies and 3 adds per 4 transfer
// floats, no shuffles in the loop. The three accumulators are reduced once per vertex with one
// 4×4 transpose; the 0..3 coefficients past the last multiple of 4 are added in scalar code.
// Successive vertices are independent, so out-of-order execution overlaps their add chains.
// (A per-coefficient broadcast form is one dependent chain of B² adds per vertex and ran ~4x
// slower; a 4-vertex transposed form needed ~4.4 instructions per float against ~2 here.)
template <int N>
void scalarBlock(const float* transfer, std::size_t stride, const float* planar, int n,
                 const Albedo& albedo, Rgb* out, std::size_t begin, std::size_t end) {
  const int count = N > 0 ? N : n;
  const int pad = (count + 3) & ~3;
  const int groups = count / 4;
  const float* lr = planar;
  const float* lg = planar + pad;
  const float* lb = planar + 2 * pad;
  for (std::size_t v = begin; v < end; ++v) {
    const float* t = transfer + v * stride;
    __m128 r = _mm_setzero_ps(), g = r, b = r;
#pragma GCC unroll 32
    for (int q = 0; q < groups; ++q) {
      const __m128 x = _mm_loadu_ps(t + 4 * q);
      r = _mm_add_ps(r, _mm_mul_ps(x, _mm_load_ps(lr + 4 * q)));
      g = _mm_add_ps(g, _mm_mul_ps(x, _mm_load_ps(lg + 4 * q)));
      b = _mm_add_ps(b, _mm_mul_ps(x, _mm_load_ps(lb + 4 * q)));
    }
    __m128 z = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(r, g, b, z);
    alignas(16) float s[4];
    _mm_store_ps(s, _mm_add_ps(_mm_add_ps(r, g), _mm_add_ps(b, z)));  // (Σr, Σg, Σb, 0)
    for (int i = 4 * groups; i < count; ++i) {
      s[0] += t[i] * lr[i];
      s[1] += t[i] * lg[i];
      s[2] += t[i] * lb[i];
    }
    const Rgb a = albedo.at(v);
    out[v] = Rgb(s[0] * a.x, s[1] * a.y, s[2] * a.z);
  }
}
#else
template <int N>
void scalarBlock(const float* transfer, std::size_t stride, const float* planar, int n,
                 const Albedo& albedo, Rgb* out, std::size_t begin, std::size_t end) {
  scalarOne<N>(transfer, stride, planar, n, albedo, out, begin, end);
}
#endif

// RGB transfer: the vertex's 3·N floats and the interleaved light are two contiguous arrays of
// the same layout, so their element-wise products vectorise without shuffles. We accumulate
// them in 12 lanes (the least common multiple of 3 channels and a 4-float register), so lane k
// always holds channel k mod 3; the 12 lanes are folded into (r, g, b) at the end.
template <int N>
void rgbRange(const float* transfer, std::size_t stride, const float* light3, int n,
              const Albedo& albedo, Rgb* out, std::size_t begin, std::size_t end) {
  const int m = 3 * (N > 0 ? N : n);
  for (std::size_t v = begin; v < end; ++v) {
    const float* t = transfer + v * stride;
    float acc[12] = {};
    int j = 0;
#pragma GCC unroll 8
    for (; j + 12 <= m; j += 12)
      for (int k = 0; k < 12; ++k) acc[k] += t[j + k] * light3[j + k];
    for (int k = 0; j + k < m; ++k) acc[k] += t[j + k] * light3[j + k];
    const float r = (acc[0] + acc[3]) + (acc[6] + acc[9]);
    const float g = (acc[1] + acc[4]) + (acc[7] + acc[10]);
    const float b = (acc[2] + acc[5]) + (acc[8] + acc[11]);
    const Rgb a = albedo.at(v);
    out[v] = Rgb(r * a.x, g * a.y, b * a.z);
  }
}

using RangeFn = void (*)(const float*, std::size_t, const float*, int, const Albedo&, Rgb*,
                         std::size_t, std::size_t);

#if defined(__SSE2__)
// Scalar kernels take both light layouts through one pointer: planar first, then splat.
template <int N>
void scalarKernel(const float* transfer, std::size_t stride, const float* light, int n,
                  const Albedo& albedo, Rgb* out, std::size_t begin, std::size_t end) {
  const int count = N > 0 ? N : n;
  const float* splat = light + 3 * ((count + 3) & ~3);
#if defined(PRT_RELIGHT_AVX2)
  if (N > 0 && N <= 25 && simdAvx2Fma())
    scalarBlock8<N>(transfer, stride, splat, n, albedo, out, begin, end);
  else
#endif
      if (N > 0 && N <= 25)
    scalarBlock4<N>(transfer, stride, splat, n, albedo, out, begin, end);
  else
    scalarBlock<N>(transfer, stride, light, n, albedo, out, begin, end);
}
#else
template <int N>
void scalarKernel(const float* transfer, std::size_t stride, const float* light, int n,
                  const Albedo& albedo, Rgb* out, std::size_t begin, std::size_t end) {
  scalarBlock<N>(transfer, stride, light, n, albedo, out, begin, end);
}
#endif

/// Relighting kernels are specialised for B ≤ 10 (B² ≤ 100 coefficients: the loop bounds and the
/// light registers are constants); above, the generic kernel.
constexpr int kRelightFixedBands = 10;

RangeFn pick(int bands, bool rgb) {
  return sh::dispatchBands<kRelightFixedBands>(
      bands, [rgb]<int B>() -> RangeFn { return rgb ? &rgbRange<B * B> : &scalarKernel<B * B>; },
      [rgb]() -> RangeFn { return rgb ? &rgbRange<0> : &scalarKernel<0>; });
}

}  // namespace

}  // namespace prt::relight

namespace prt::relight::detail {

void relightDenseVectors(const Transfer& transfer, const PreparedLight& light,
                         const prt::Albedo& albedo, std::span<Rgb> out) {
  const std::size_t nv = transfer.rowCount();
  const prt::Albedo& a = albedo;
  const bool rgb = transfer.channels() == 3;
  const RangeFn fn = pick(light.bands, rgb);
  const float* lightData = rgb ? light.interleaved.data() : light.planar.data();
  const int n = light.bands * light.bands;
  const std::size_t stride = transfer.stride();
  const float* t = transfer.values().data();
  Rgb* o = out.data();
  // ~16 KiB..1 MiB of transfer per task: large enough to amortise scheduling.
  const std::size_t grain = std::max<std::size_t>(256, 65536 / (stride * sizeof(float)) * 4);
  parallelFor(nv, grain,
              [&](std::size_t b, std::size_t e) { fn(t, stride, lightData, n, a, o, b, e); });
}

}  // namespace prt::relight::detail
