// The diffuse (vector) kernel of relighting from CPCA-compressed transfer (Sloan, Hall, Hart &
// Snyder 2003, §5): per vertex v of cluster k,
//
//   out[v] = albedo(v) ⊙ ( c_k + Σ_{j<N} w_vj d_kj ),   c_k = M_k·L, d_kj = B_kj·L  (RGB),
//
// with the K(N+1) RGB projections made once per frame (projectClusters). Per vertex the kernel
// reads a cluster id (4 bytes) and N weights (4N bytes) and writes 12 bytes; the projections are
// a K(N+1)-row table (K = 256, N = 8: 40 KiB, within the reference machine's 48 KiB L1).
//
// The per-frame table, one row of `rowFloats` floats per cluster (a multiple of 8, so a row
// starts 32-byte aligned in a 32-byte aligned table):
//
//   [ c_r c_g c_b 0 | 0 0 0 0 | d_0 (r g b 0) | d_1 (r g b 0) | ... | d_N−1 | (0 0 0 0 if N odd) ]
//
// so basis vectors 2q and 2q+1 are one 256-bit load, and c_k is one too (upper half zero).
//
// Two kernels over that table, picked at run time:
//   - portable: per vertex, N four-wide multiply-adds on (r, g, b, 0), left to the compiler
//     (any target);
//   - AVX2+FMA: per vertex, acc = [c_k | 0]; for each pair q: acc += [w_2q ×4 | w_2q+1 ×4] ⊙
//     [d_2q | d_2q+1] (one 8-byte load and one permute make the weight pattern), then the two
//     halves are added: N/2 FMAs, N/2 + 1 shuffles per vertex instead of N broadcasts and N
//     multiply-adds. Four vertices' (r, g, b, 0) results are packed into three 16-byte vectors
//     of the output's r g b r | g b r g | b r g b order with three shuffles, multiplied by the
//     albedo in the same order (three loads, no per-vertex scalar work) and stored whole. For
//     outputs larger than the caches the stores are non-temporal (the 12 output bytes per
//     vertex are then written without first being read, a sixth of the kernel's memory
//     traffic); smaller outputs stay in cache for whoever reads them next.
// Both give results equal to relighting the reconstructed transfer up to float rounding (the
// AVX2 form rounds once per FMA); each is independent of the thread count and vertex order.
// Profile of the portable form before this kernel (perf record -e cpu-clock, perf annotate,
// docs/performance.md): GCC vectorised its run-time-N weight loop across j, four weights at a
// time with deinterleaving shuffles of the table (~45 instructions per four weights), and 42%
// of the kernel's samples sat on the load of a vertex's weights (waiting for memory). The
// instructions are what this kernel cuts; the stalls are the bandwidth floor, lowered only by
// moving fewer bytes (the non-temporal stores).

#include <algorithm>
#include <cstdint>
#include <string>

#include "kernels.hpp"
#include "prt/core/cpu.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define PRT_COMPRESSED_AVX2 1
#endif

namespace prt::relight {

namespace {

// Table row length in floats: 8 (c_k and zeros) + 4 per basis vector, rounded up to 8.
std::size_t tableRowFloats(std::size_t basisCount) {
  return (8 + 4 * basisCount + 7) & ~std::size_t(7);
}

// Everything one kernel call needs; rows of `table` are `rowFloats` apart.
struct DiffuseFrame {
  const float* table = nullptr;
  std::size_t rowFloats = 0;
  const std::uint32_t* id = nullptr;
  const float* weights = nullptr;
  std::size_t basisCount = 0;
  const Rgb* albedo = nullptr;  ///< per vertex, or null for `uniform`
  Rgb uniform{1.0f};
  Rgb* out = nullptr;
  bool stream = false;  ///< non-temporal stores (AVX2 kernel)
};

void diffusePortable(const DiffuseFrame& f, std::size_t begin, std::size_t end) {
  const std::size_t N = f.basisCount;
  for (std::size_t v = begin; v < end; ++v) {
    const float* row = f.table + f.id[v] * f.rowFloats;
    const float* w = f.weights + v * N;
    float acc[4] = {row[0], row[1], row[2], row[3]};
    for (std::size_t j = 0; j < N; ++j) {
      const float wj = w[j];
      const float* d = row + 8 + 4 * j;
      for (int c = 0; c < 4; ++c) acc[c] += wj * d[c];
    }
    const Rgb a = f.albedo ? f.albedo[v] : f.uniform;
    f.out[v] = Rgb(acc[0] * a.x, acc[1] * a.y, acc[2] * a.z);
  }
}

#if defined(PRT_COMPRESSED_AVX2)
// (r, g, b, 0) of one vertex, before the albedo.
[[gnu::always_inline]] inline __attribute__((target("avx2,fma"))) __m128 vertexSum(
    const DiffuseFrame& f, std::size_t v, __m256i pairIndex) {
  const std::size_t N = f.basisCount;
  const float* row = f.table + f.id[v] * f.rowFloats;
  const float* w = f.weights + v * N;
  __m256 acc = _mm256_load_ps(row);  // [c_k | 0]
  std::size_t j = 0;
  for (; j + 2 <= N; j += 2) {
    // [w_j w_j w_j w_j | w_j+1 w_j+1 w_j+1 w_j+1] from one 8-byte load and one permute.
    const __m128 two = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(w + j)));
    const __m256 pattern = _mm256_permutevar8x32_ps(_mm256_castps128_ps256(two), pairIndex);
    acc = _mm256_fmadd_ps(pattern, _mm256_load_ps(row + 8 + 4 * j), acc);
  }
  if (j < N) {  // odd N: the last basis vector, upper half of the pattern zero
    const __m256 pattern =
        _mm256_permutevar8x32_ps(_mm256_castps128_ps256(_mm_load_ss(w + j)), pairIndex);
    acc = _mm256_fmadd_ps(pattern, _mm256_load_ps(row + 8 + 4 * j), acc);
  }
  return _mm_add_ps(_mm256_castps256_ps128(acc), _mm256_extractf128_ps(acc, 1));
}

// One vertex written with 12-byte stores (range ends, unaligned starts).
[[gnu::always_inline]] inline __attribute__((target("avx2,fma"))) void storeOne(
    const DiffuseFrame& f, std::size_t v, __m128 sum) {
  const Rgb a = f.albedo ? f.albedo[v] : f.uniform;
  alignas(16) float s[4];
  _mm_store_ps(s, _mm_mul_ps(sum, _mm_setr_ps(a.x, a.y, a.z, 0.0f)));
  f.out[v] = Rgb(s[0], s[1], s[2]);
}

template <bool Stream>
__attribute__((target("avx2,fma"))) void diffuseAvx2(const DiffuseFrame& f, std::size_t begin,
                                                     std::size_t end) {
  const __m256i pairIndex = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
  std::size_t v = begin;
  // Up to 3 vertices one at a time, until out + v is 16-byte aligned (a float array reaches it
  // within 4 vertices of 12 bytes), so the groups below store aligned 16-byte vectors.
  while (v < end && (reinterpret_cast<std::uintptr_t>(f.out + v) & 15) != 0) {
    storeOne(f, v, vertexSum(f, v, pairIndex));
    ++v;
  }
  const Rgb u = f.uniform;
  const __m128 u0 = _mm_setr_ps(u.x, u.y, u.z, u.x), u1 = _mm_setr_ps(u.y, u.z, u.x, u.y),
               u2 = _mm_setr_ps(u.z, u.x, u.y, u.z);
  for (; v + 4 <= end; v += 4) {
    const __m128 x0 = vertexSum(f, v, pairIndex), x1 = vertexSum(f, v + 1, pairIndex);
    const __m128 x2 = vertexSum(f, v + 2, pairIndex), x3 = vertexSum(f, v + 3, pairIndex);
    // Four (r, g, b, 0) into the output's order: r0 g0 b0 r1 | g1 b1 r2 g2 | b2 r3 g3 b3.
    __m128 o0 = _mm_blend_ps(x0, _mm_shuffle_ps(x1, x1, _MM_SHUFFLE(0, 0, 0, 0)), 0x8);
    __m128 o1 = _mm_shuffle_ps(x1, x2, _MM_SHUFFLE(1, 0, 2, 1));
    __m128 o2 = _mm_blend_ps(_mm_shuffle_ps(x3, x3, _MM_SHUFFLE(2, 1, 0, 0)),
                             _mm_shuffle_ps(x2, x2, _MM_SHUFFLE(2, 2, 2, 2)), 0x1);
    if (f.albedo) {  // per-vertex albedo is an Rgb array: the same 12-float order
      const float* a = reinterpret_cast<const float*>(f.albedo + v);
      o0 = _mm_mul_ps(o0, _mm_loadu_ps(a));
      o1 = _mm_mul_ps(o1, _mm_loadu_ps(a + 4));
      o2 = _mm_mul_ps(o2, _mm_loadu_ps(a + 8));
    } else {
      o0 = _mm_mul_ps(o0, u0);
      o1 = _mm_mul_ps(o1, u1);
      o2 = _mm_mul_ps(o2, u2);
    }
    float* o = reinterpret_cast<float*>(f.out + v);
    if constexpr (Stream) {
      _mm_stream_ps(o, o0);
      _mm_stream_ps(o + 4, o1);
      _mm_stream_ps(o + 8, o2);
    } else {
      _mm_store_ps(o, o0);
      _mm_store_ps(o + 4, o1);
      _mm_store_ps(o + 8, o2);
    }
  }
  for (; v < end; ++v) storeOne(f, v, vertexSum(f, v, pairIndex));
  if constexpr (Stream) _mm_sfence();  // make the non-temporal stores visible before returning
}
#endif

// Outputs at least this large are written with non-temporal stores: beyond the two cores'
// second-level caches (2 × 2 MiB on the reference machine, more than most desktop L2s) the
// output would be evicted before anyone reads it, and a normal store first reads its line.
constexpr std::size_t kStreamOutputBytes = std::size_t(4) << 20;

}  // namespace

namespace detail {

void relightCpcaVectors(const Transfer& t, const ClusterLight& p, const prt::Albedo& albedo,
                        std::span<Rgb> out) {
  const CpcaRows& cp = t.cpca();
  if (t.isMatrix() || p.coeffs != 1)
    throw Error("relight: diffuse relighting needs vector transfer (this one holds matrices)");
  if (p.clusters != cp.clusters || p.basisCount != cp.basisCount ||
      p.rgb.size() != static_cast<std::size_t>(cp.clusters) * (cp.basisCount + 1) * 3)
    throw Error("relight: cluster projections were made for another compressed transfer");
  const std::size_t nv = t.rowCount(), N = static_cast<std::size_t>(cp.basisCount);
  // Ids are not checked here (a pass over 4 bytes per vertex, ~7% of the kernel's traffic):
  // Transfer::check, which the bake-file loader runs, guarantees they are below K.

  // The table (layout at the top of this file).
  const std::size_t K = static_cast<std::size_t>(cp.clusters), rowFloats = tableRowFloats(N);
  const AlignedFloats table = alignedZeros(K * rowFloats);
  for (std::size_t k = 0; k < K; ++k) {
    float* row = table.get() + k * rowFloats;
    const float* src = p.rgb.data() + k * (N + 1) * 3;
    for (std::size_t c = 0; c < 3; ++c) row[c] = src[c];
    for (std::size_t j = 0; j < N; ++j)
      for (std::size_t c = 0; c < 3; ++c) row[8 + 4 * j + c] = src[3 * (j + 1) + c];
  }

  DiffuseFrame f;
  f.table = table.get();
  f.rowFloats = rowFloats;
  f.id = cp.cluster.data();
  f.weights = cp.weights.data();
  f.basisCount = N;
  f.albedo = albedo.perRow();
  f.uniform = albedo.uniform();
  f.out = out.data();
  f.stream = nv * sizeof(Rgb) >= kStreamOutputBytes;

  using RangeFn = void (*)(const DiffuseFrame&, std::size_t, std::size_t);
  RangeFn fn = &diffusePortable;
#if defined(PRT_COMPRESSED_AVX2)
  if (simdAvx2Fma()) fn = f.stream ? &diffuseAvx2<true> : &diffuseAvx2<false>;
#endif
  // 4096 vertices (~150 KB of ids and weights) per task amortise the scheduling.
  parallelFor(nv, 4096, [&](std::size_t b, std::size_t e) { fn(f, b, e); });
}

}  // namespace detail

}  // namespace prt::relight
