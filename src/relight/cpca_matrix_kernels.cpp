// The glossy (matrix) kernel of relighting from CPCA-compressed transfer (Sloan, Hall, Hart &
// Snyder 2003, §5; the shading of Sloan, Kautz & Snyder 2002 as in relight.hpp). Per vertex v of
// cluster k, with the per-frame projections Q_k0 = M_k L and Q_kj = B_k,j−1 L (B² × RGB each,
// projectClusters):
//
//   L'_v = Q_k0 + Σ_{j<N} w_vj Q_k,j+1                    (transferred incident radiance)
//   e_v  = a_v ⊙ (d(n_v) · L'_v) + ks (g(R_v) · L'_v)     (per channel)
//
// with d and g the diffuse and lobe response vectors of the vertex (PreparedMaterial::responses:
// two SH evaluations). That is (N + 1)·3B² + 2·3B² multiply-adds per vertex against the dense
// kernel's 2B⁴ (matrix_kernels.cpp), and a read of 4 + 4N bytes instead of 4B⁴: the compressed
// kernel is compute-bound where the dense one is memory-bound. The per-frame projections read all
// K(N+1) means and bases, B⁴ floats each (K = 256, N = 8, 5 bands: 5.8 MB, 4.6× the ids and
// weights of the 35k-vertex bunny): at large K on small meshes they, not the vertices, bound
// the frame.
//
// The AVX2+FMA kernel lays the projections out per frame as, per cluster, N + 1 blocks of three
// channel planes of P = B² rounded up to 8 floats (zero-padded):
//
//   block j: [ Q_kj red (P) | Q_kj green (P) | Q_kj blue (P) ]
//
// so L'_v stays in 3P/8 registers (12 at 5 bands) while the N + 1 blocks stream past, one FMA
// per 8 floats; then a_c d + ks_c g is formed per channel plane and dotted with L'_v,c (3 sums
// across lanes per vertex). The response vectors d and g, two SH evaluations per vertex (which
// the dense kernel pays too, but there among 2B⁴ multiply-adds), are evaluated for eight
// vertices at once, one per SIMD lane (sh::evalFixed on an eight-float type, in float). The
// portable kernel does the same sums on the interleaved projections with
// PreparedMaterial::responses. Both are independent of the thread count; they differ by float
// rounding.

#include <algorithm>
#include <string>
#include <vector>

#include "kernels.hpp"
#include "prt/core/cpu.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/sh_fixed.hpp"
#include "prt/transfer/material.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define PRT_COMPRESSED_GLOSSY_AVX2 1
#endif

namespace prt::relight {

namespace {

using detail::AlignedFloats;
using detail::alignedZeros;

struct GlossyFrame {
  const Transfer* t = nullptr;
  const ClusterLight* p = nullptr;
  const PreparedMaterial* material = nullptr;
  const Surface* view = nullptr;
  Vec3f eye{0.0f};
  const Albedo* albedo = nullptr;
  std::span<Rgb> out;
  const float* planar = nullptr;  ///< AVX2 layout (above), K(N+1)·3P floats
  std::size_t P = 0;
};

void glossyPortable(const GlossyFrame& f, std::size_t b, std::size_t e) {
  const CpcaRows& t = f.t->cpca();
  const PreparedMaterial& material = *f.material;
  const std::size_t nB = static_cast<std::size_t>(f.t->coeffs()),
                    N = static_cast<std::size_t>(t.basisCount);
  const std::size_t per = 3 * nB, W = N + 1;
  const bool glossy = !material.glossy.empty();
  std::vector<float> y(nB), d(nB), g(glossy ? nB : 0), lp(per);
  for (std::size_t v = b; v < e; ++v) {
    // L'_v = (M_k L) + Σ_j w_vj (B_kj L)
    const float* q = f.p->rgb.data() + t.cluster[v] * W * per;
    std::copy_n(q, per, lp.data());
    for (std::size_t j = 0; j < N; ++j) {
      const float wj = t.weights[v * N + j];
      const float* qj = q + (j + 1) * per;
      for (std::size_t i = 0; i < per; ++i) lp[i] += wj * qj[i];
    }
    material.responses(f.view->positions[v], f.view->normals[v], f.eye, d.data(), g.data(),
                       y.data());
    Rgb diff(0.0f), spec(0.0f);
    for (std::size_t i = 0; i < nB; ++i)
      for (int c = 0; c < 3; ++c) {
        diff[c] += d[i] * lp[3 * i + c];
        if (glossy) spec[c] += g[i] * lp[3 * i + c];
      }
    f.out[v] = material.diffuseAt(*f.albedo, v) * diff + material.specular * spec;
  }
}

#if defined(PRT_COMPRESSED_GLOSSY_AVX2)
__attribute__((target("avx2,fma"))) inline float horizontalSum(__m256 x) {
  const __m128 s = _mm_add_ps(_mm256_castps256_ps128(x), _mm256_extractf128_ps(x, 1));
  const __m128 h = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(h, _mm_movehdup_ps(h)));
}

// Eight floats under GCC's vector extension, with what sh::evalFixed needs of its number type
// (construction from a constant, +, −, ×): evalFixed<B, Float8> then evaluates the SH basis at
// eight directions at once, one lane each. The operators are always_inline so that, inlined
// into the AVX2 kernel, they compile to 256-bit instructions.
typedef float Float8Raw __attribute__((vector_size(32)));
struct Float8 {
  Float8Raw v;
  Float8() = default;
  Float8(const Float8Raw& x) : v(x) {}  // by reference: no 32-byte argument in the SSE2 ABI
  Float8(double s) : v(Float8Raw{} + static_cast<float>(s)) {}
};
[[gnu::always_inline]] inline Float8 operator+(const Float8& a, const Float8& b) {
  return a.v + b.v;
}
[[gnu::always_inline]] inline Float8 operator-(const Float8& a, const Float8& b) {
  return a.v - b.v;
}
[[gnu::always_inline]] inline Float8 operator*(const Float8& a, const Float8& b) {
  return a.v * b.v;
}

// out[i] = scale[i] · Y_i at the eight directions (x, y, z)[k], renormalised first.
template <int B>
[[gnu::always_inline]] inline __attribute__((target("avx2,fma"))) void scaledBasis8(
    const float* x, const float* y, const float* z, const float* scale, Float8* out) {
  const Float8 X = *reinterpret_cast<const Float8Raw*>(x),
               Y = *reinterpret_cast<const Float8Raw*>(y),
               Z = *reinterpret_cast<const Float8Raw*>(z);
  const Float8 s = Float8(1.5) - Float8(0.5) * (X * X + Y * Y + Z * Z);
  sh::evalFixed<B, Float8>(X * s, Y * s, Z * s, out);
  for (int i = 0; i < B * B; ++i) out[i] = out[i] * Float8(scale[i]);
}

// The response vectors of eight vertices v0..v0+7 (PreparedMaterial::responses, lane k = vertex
// v0 + k): d[i][k] = (A_l/π) Y_i(n), g[i][k] = Λ_l Y_i(R) with R the view reflected about n, the
// basis evaluated in float for the eight directions at once (renormalised by one Newton step
// as sh::evalFixed's float path does; at B ≤ 9 the float recurrence stays within ~1e-6 of the
// band's largest value).
template <int B>
__attribute__((target("avx2,fma"))) void responses8(const GlossyFrame& f, std::size_t v0,
                                                    bool glossy, Float8* d, Float8* g) {
  const PreparedMaterial& material = *f.material;
  alignas(32) float nx[8], ny[8], nz[8], rx[8], ry[8], rz[8];
  for (int k = 0; k < 8; ++k) {
    const Vec3f n = f.view->normals[v0 + k];
    nx[k] = n.x, ny[k] = n.y, nz[k] = n.z;
    if (glossy) {
      const Vec3f toEye = f.eye - f.view->positions[v0 + k];
      const float len = length(toEye);
      const Vec3f r = reflectView(n, len > 0 ? toEye / len : n);
      rx[k] = r.x, ry[k] = r.y, rz[k] = r.z;
    }
  }
  scaledBasis8<B>(nx, ny, nz, material.diffuse.data(), d);
  if (glossy) scaledBasis8<B>(rx, ry, rz, material.glossy.data(), g);
}

// One vertex of glossyAvx2 given its response vectors d and g (P floats each, zero past B²).
template <int B>
[[gnu::always_inline]] inline __attribute__((target("avx2,fma"))) void shadeVertex(
    const GlossyFrame& f, std::size_t v, const float* d, const float* g) {
  constexpr int nB = B * B, V = (nB + 7) / 8;
  constexpr std::size_t P = 8 * V, block = 3 * P;
  const CpcaRows& t = f.t->cpca();
  const PreparedMaterial& material = *f.material;
  const std::size_t N = static_cast<std::size_t>(t.basisCount);
  const float* q = f.planar + t.cluster[v] * (N + 1) * block;
  const float* w = t.weights.data() + v * N;
  __m256 acc[3 * V];
  for (int r = 0; r < 3 * V; ++r) acc[r] = _mm256_load_ps(q + 8 * r);
  for (std::size_t j = 0; j < N; ++j) {
    const __m256 wj = _mm256_broadcast_ss(w + j);
    const float* qj = q + (j + 1) * block;
    for (int r = 0; r < 3 * V; ++r)
      acc[r] = _mm256_fmadd_ps(wj, _mm256_load_ps(qj + 8 * r), acc[r]);
  }
  const Rgb a = material.diffuseAt(*f.albedo, v);
  float e3[3];
  for (int c = 0; c < 3; ++c) {
    // Σ_i (a_c d_i + ks_c g_i) L'_v,c,i
    const __m256 ac = _mm256_set1_ps(a[c]), ks = _mm256_set1_ps(material.specular[c]);
    __m256 sum = _mm256_setzero_ps();
    for (int r = 0; r < V; ++r) {
      const __m256 resp = _mm256_fmadd_ps(ac, _mm256_load_ps(d + 8 * r),
                                          _mm256_mul_ps(ks, _mm256_load_ps(g + 8 * r)));
      sum = _mm256_fmadd_ps(resp, acc[c * V + r], sum);
    }
    e3[c] = horizontalSum(sum);
  }
  f.out[v] = Rgb(e3[0], e3[1], e3[2]);
}

// P = B² rounded up to 8; V = P/8 registers per channel plane, so L'_v is 3V registers.
template <int B>
__attribute__((target("avx2,fma"))) void glossyAvx2(const GlossyFrame& f, std::size_t b,
                                                    std::size_t e) {
  constexpr int nB = B * B, V = (nB + 7) / 8;
  constexpr std::size_t P = 8 * V;
  const PreparedMaterial& material = *f.material;
  const bool glossy = !material.glossy.empty();
  alignas(32) float d[P] = {}, g[P] = {}, y[P] = {};  // zero past B²: the padding adds nothing
  alignas(32) Float8 d8[nB], g8[nB];
  for (int i = 0; i < nB; ++i) g8[i] = Float8(0.0);  // stays zero without a lobe
  std::size_t v = b;
  for (; v + 8 <= e; v += 8) {  // responses eight vertices at a time, then each vertex
    responses8<B>(f, v, glossy, d8, g8);
    for (int k = 0; k < 8; ++k) {
      for (int i = 0; i < nB; ++i) {
        d[i] = d8[i].v[k];
        g[i] = g8[i].v[k];
      }
      shadeVertex<B>(f, v + k, d, g);
    }
  }
  for (; v < e; ++v) {  // the last 0..7
    material.responses(f.view->positions[v], f.view->normals[v], f.eye, d, glossy ? g : nullptr, y);
    shadeVertex<B>(f, v, d, g);
  }
}

using GlossyRangeFn = void (*)(const GlossyFrame&, std::size_t, std::size_t);

/// The AVX2 kernel for B ≤ 9; nullptr where there is none.
GlossyRangeFn pickGlossyAvx2(int bands) {
  static constexpr GlossyRangeFn table[] = {&glossyAvx2<1>, &glossyAvx2<2>, &glossyAvx2<3>,
                                            &glossyAvx2<4>, &glossyAvx2<5>, &glossyAvx2<6>,
                                            &glossyAvx2<7>, &glossyAvx2<8>, &glossyAvx2<9>};
  return bands >= 1 && bands <= int(std::size(table)) && simdAvx2Fma() ? table[bands - 1] : nullptr;
}
#endif

}  // namespace

namespace detail {

void relightCpcaMatrices(const Transfer& t, const PreparedLight& light,
                         const PreparedMaterial& material, const Surface& surface, const Vec3f& eye,
                         const Albedo& albedo, std::span<Rgb> out) {
  const ClusterLight p = projectClusters(t, light);
  GlossyFrame f;
  f.t = &t;
  f.p = &p;
  f.material = &material;
  f.view = &surface;
  f.eye = eye;
  f.albedo = &albedo;
  f.out = out;
  const CpcaRows& cp = t.cpca();
  const std::size_t nB = static_cast<std::size_t>(t.coeffs());
  void (*fn)(const GlossyFrame&, std::size_t, std::size_t) = &glossyPortable;
  AlignedFloats planar;
#if defined(PRT_COMPRESSED_GLOSSY_AVX2)
  const std::size_t V = (nB + 7) / 8;
  if (const GlossyRangeFn avx2 = pickGlossyAvx2(t.bands())) {
    // The projections into the planar, padded layout (above).
    const std::size_t P = 8 * V,
                      blocks = static_cast<std::size_t>(cp.clusters) * (cp.basisCount + 1);
    planar = alignedZeros(blocks * 3 * P);
    for (std::size_t q = 0; q < blocks; ++q)
      for (std::size_t i = 0; i < nB; ++i)
        for (std::size_t c = 0; c < 3; ++c)
          planar[q * 3 * P + c * P + i] = p.rgb[(q * nB + i) * 3 + c];
    f.planar = planar.get();
    f.P = P;
    fn = avx2;
  }
#else
  (void)nB;
#endif
  parallelFor(t.rowCount(), 256, [&](std::size_t b, std::size_t e) { fn(f, b, e); });
}

}  // namespace detail

}  // namespace prt::relight
