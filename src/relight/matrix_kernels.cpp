// The dense matrix (glossy) kernels of relighting (relight.hpp) and viewTransfer
// (view_transfer.hpp): per row, u = M_pᵀ d and w = M_pᵀ g in one pass over the matrix, then
// e_c = kd_c (u·L_c) + ks_c (w·L_c), or the collapsed vector t_c = kd_c u + ks_c w.

#include "prt/relight/view_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "kernels.hpp"
#include "prt/core/cpu.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"

namespace prt::relight {

namespace {

// u += d_i · row, w += g_i · row over the matrix's rows: the whole per-vertex cost. The portable
// form; compiled a second time for AVX2+FMA below (accumulateRowsWide), picked per call by
// simdAvx2Fma() so that tests can force either.
[[gnu::always_inline]] inline void accumulateRowsBody(const float* m, std::size_t rows,
                                                      std::size_t rowStride, std::size_t width,
                                                      const float* d, const float* g, float* u,
                                                      float* w) {
  std::fill_n(u, width, 0.0f);
  if (g) std::fill_n(w, width, 0.0f);
  for (std::size_t i = 0; i < rows; ++i) {
    const float* row = m + i * rowStride;
    const float di = d[i];
    if (g) {
      const float gi = g[i];
      for (std::size_t j = 0; j < width; ++j) {
        u[j] += di * row[j];
        w[j] += gi * row[j];
      }
    } else {
      for (std::size_t j = 0; j < width; ++j) u[j] += di * row[j];
    }
  }
}

void accumulateRows(const float* m, std::size_t rows, std::size_t rowStride, std::size_t width,
                    const float* d, const float* g, float* u, float* w) {
  accumulateRowsBody(m, rows, rowStride, width, d, g, u, w);
}

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define PRT_GLOSSY_AVX2 1

// The portable loop compiled for AVX2+FMA (rows wider than the register-resident kernel holds).
__attribute__((target("avx2,fma"))) void accumulateRowsWide(const float* m, std::size_t rows,
                                                            std::size_t rowStride,
                                                            std::size_t width, const float* d,
                                                            const float* g, float* u, float* w) {
  accumulateRowsBody(m, rows, rowStride, width, d, g, u, w);
}

// The same sums with u and w held in registers across all rows (NV vectors of 8 floats each,
// the last one masked): one load and two FMAs per 8 matrix floats and no stores until the end.
// The portable loop above reloads and stores u and w for every row, which at B ≤ 5 costs more
// than the matrix read itself. Rounding differs from the portable loop (FMA), not between
// threads.
template <int NV, bool Glossy>
__attribute__((target("avx2,fma"))) void accumulateRowsAvx2(const float* m, std::size_t rows,
                                                            std::size_t rowStride,
                                                            std::size_t width, const float* d,
                                                            const float* g, float* u, float* w) {
  __m256 U[NV], W[NV];
  for (int k = 0; k < NV; ++k) U[k] = W[k] = _mm256_setzero_ps();
  const int tail = static_cast<int>(width) - 8 * (NV - 1);  // 1..8 lanes in the last vector
  const __m256i mask =
      _mm256_cmpgt_epi32(_mm256_set1_epi32(tail), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  for (std::size_t i = 0; i < rows; ++i) {
    const float* row = m + i * rowStride;
    const __m256 di = _mm256_set1_ps(d[i]);
    const __m256 gi = Glossy ? _mm256_set1_ps(g[i]) : _mm256_setzero_ps();
    for (int k = 0; k < NV - 1; ++k) {
      const __m256 x = _mm256_loadu_ps(row + 8 * k);
      U[k] = _mm256_fmadd_ps(di, x, U[k]);
      if constexpr (Glossy) W[k] = _mm256_fmadd_ps(gi, x, W[k]);
    }
    const __m256 x = _mm256_maskload_ps(row + 8 * (NV - 1), mask);
    U[NV - 1] = _mm256_fmadd_ps(di, x, U[NV - 1]);
    if constexpr (Glossy) W[NV - 1] = _mm256_fmadd_ps(gi, x, W[NV - 1]);
  }
  for (int k = 0; k < NV - 1; ++k) {
    _mm256_storeu_ps(u + 8 * k, U[k]);
    if constexpr (Glossy) _mm256_storeu_ps(w + 8 * k, W[k]);
  }
  _mm256_maskstore_ps(u + 8 * (NV - 1), mask, U[NV - 1]);
  if constexpr (Glossy) _mm256_maskstore_ps(w + 8 * (NV - 1), mask, W[NV - 1]);
}

using RowsFn = void (*)(const float*, std::size_t, std::size_t, std::size_t, const float*,
                        const float*, float*, float*);

/// The AVX2+FMA kernel for rows of `width` floats: register-resident up to 48 floats (B ≤ 6
/// scalar, B ≤ 4 RGB), the wide loop above that; nullptr without AVX2 (the portable loop).
RowsFn pickRows(std::size_t width, bool glossy) {
  if (!simdAvx2Fma() || width == 0) return nullptr;
  if (width > 48) return &accumulateRowsWide;
  const std::size_t nv = (width + 7) / 8;
  static constexpr RowsFn glossyTable[] = {
      &accumulateRowsAvx2<1, true>, &accumulateRowsAvx2<2, true>, &accumulateRowsAvx2<3, true>,
      &accumulateRowsAvx2<4, true>, &accumulateRowsAvx2<5, true>, &accumulateRowsAvx2<6, true>};
  static constexpr RowsFn diffuseTable[] = {
      &accumulateRowsAvx2<1, false>, &accumulateRowsAvx2<2, false>, &accumulateRowsAvx2<3, false>,
      &accumulateRowsAvx2<4, false>, &accumulateRowsAvx2<5, false>, &accumulateRowsAvx2<6, false>};
  return glossy ? glossyTable[nv - 1] : diffuseTable[nv - 1];
}
#endif

}  // namespace

namespace {

/// The one pass over the matrices: for every row r, in parallel, u = M_rᵀ d and w = M_rᵀ g
/// over the first `columns` source coefficients (u, w: columns × channels floats, channel
/// fastest; w empty without a lobe), handed to visit(r, u, w). Allocation-free per row.
template <class Visit>
void forEachResponse(const Transfer& transfer, const PreparedMaterial& material,
                     const Surface& surface, const Vec3f& eye, std::size_t columns,
                     const Visit& visit) {
  const std::size_t nB = static_cast<std::size_t>(transfer.coeffs());
  const std::size_t ch = static_cast<std::size_t>(transfer.channels());
  const std::size_t width = columns * ch, rowStride = nB * ch;
  const bool glossy = !material.glossy.empty();
  const float* M = transfer.values().data();
  const std::size_t stride = transfer.stride();
  const std::size_t grain = std::max<std::size_t>(16, 16384 / (nB * nB * ch));
#if defined(PRT_GLOSSY_AVX2)
  const RowsFn fast = pickRows(width, glossy);
#endif
  parallelFor(transfer.rowCount(), grain, [&](std::size_t begin, std::size_t end) {
    std::vector<float> y(nB), d(nB), g(glossy ? nB : 0), u(width), w(glossy ? width : 0);
    for (std::size_t v = begin; v < end; ++v) {
      material.responses(surface.positions[v], surface.normals[v], eye, d.data(), g.data(),
                         y.data());
#if defined(PRT_GLOSSY_AVX2)
      if (fast)
        fast(M + v * stride, nB, rowStride, width, d.data(), glossy ? g.data() : nullptr, u.data(),
             w.data());
      else
#endif
        accumulateRows(M + v * stride, nB, rowStride, width, d.data(), glossy ? g.data() : nullptr,
                       u.data(), w.data());
      visit(v, u, w);
    }
  });
}

}  // namespace

namespace detail {

void relightDenseMatrices(const Transfer& transfer, const PreparedLight& light,
                          const PreparedMaterial& material, const Surface& surface,
                          const Vec3f& eye, const Albedo& albedo, std::span<Rgb> out) {
  const std::size_t nb = static_cast<std::size_t>(light.bands * light.bands);
  const std::size_t ch = static_cast<std::size_t>(transfer.channels());
  const bool glossy = !material.glossy.empty();
  const float* L = light.interleaved.data();  // (r, g, b) per coefficient
  forEachResponse(transfer, material, surface, eye, nb,
                  [&](std::size_t v, const std::vector<float>& u, const std::vector<float>& w) {
                    Rgb diff(0.0f), spec(0.0f);
                    for (std::size_t j = 0; j < nb; ++j)
                      for (std::size_t c = 0; c < 3; ++c) {
                        const std::size_t k = j * ch + (ch == 1 ? 0 : c);
                        diff[c] += u[k] * L[3 * j + c];
                        if (glossy) spec[c] += w[k] * L[3 * j + c];
                      }
                    out[v] = material.diffuseAt(albedo, v) * diff + material.specular * spec;
                  });
}

}  // namespace detail

Transfer viewTransfer(const Transfer& transfer, const PreparedMaterial& material,
                      const Surface& surface, const Vec3f& eye) {
  if (!transfer.isMatrix() || transfer.compressed())
    throw Error("relight: viewTransfer needs dense matrix transfer");
  const std::size_t nv = transfer.rowCount();
  if (material.bands != transfer.bands())
    throw Error("relight: the material is prepared for " + std::to_string(material.bands) +
                " bands, the transfer has " + std::to_string(transfer.bands()));
  if (surface.positions.size() != nv || surface.normals.size() != nv)
    throw Error("relight: glossy transfer needs one position and normal per row (" +
                std::to_string(nv) + ")");
  const Albedo albedo(surface.albedo, nv);
  const std::size_t nB = static_cast<std::size_t>(transfer.coeffs());
  const std::size_t ch = static_cast<std::size_t>(transfer.channels());
  const bool glossy = !material.glossy.empty();
  TransferShape shape = transfer.shape();
  shape.layout = TransferLayout::Vector;
  shape.channels = 3;
  Transfer t = Transfer::zeros(shape);
  float* const values = t.mutableValues();
  forEachResponse(transfer, material, surface, eye, nB,
                  [&](std::size_t v, const std::vector<float>& u, const std::vector<float>& w) {
                    const Rgb kd = material.diffuseAt(albedo, v);
                    float* row = values + v * 3 * nB;
                    for (std::size_t j = 0; j < nB; ++j)
                      for (std::size_t c = 0; c < 3; ++c) {
                        const std::size_t k = j * ch + (ch == 1 ? 0 : c);
                        row[3 * j + c] =
                            kd[c] * u[k] + (glossy ? material.specular[c] * w[k] : 0.0f);
                      }
                  });
  return t;
}

Transfer diffuseTransfer(const Transfer& matrices, std::span<const Vec3f> normals) {
  if (!matrices.isMatrix()) throw Error("relight: the diffuse part of a vector transfer is itself");
  if (normals.size() != matrices.rowCount())
    throw Error("relight: " + std::to_string(normals.size()) + " normals for " +
                std::to_string(matrices.rowCount()) + " rows");
  const Transfer dense = matrices.toDense();
  const PreparedMaterial lambert = prepareMaterial(Material{}, dense.bands());
  const std::size_t nB = static_cast<std::size_t>(dense.coeffs());
  const std::size_t ch = static_cast<std::size_t>(dense.channels());
  TransferShape shape = dense.shape();
  shape.layout = TransferLayout::Vector;
  Transfer t = Transfer::zeros(shape);
  float* const values = t.mutableValues();
  const Surface surface{normals, normals, {}};  // positions only steer the lobe: none here
  forEachResponse(dense, lambert, surface, Vec3f(0.0f), nB,
                  [&](std::size_t v, const std::vector<float>& u, const std::vector<float>&) {
                    std::copy_n(u.data(), nB * ch, values + v * nB * ch);
                  });
  return t;
}

}  // namespace prt::relight
