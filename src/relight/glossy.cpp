#include "prt/relight/glossy.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"

namespace prt::relight {

namespace {

// u += d_i · row, w += g_i · row over the matrix's rows: the whole per-vertex cost. Compiled for
// AVX2+FMA and for the baseline, picked at load time (GCC function multi-versioning).
// (GCC only: clang 14, used by the fuzz build, emits no symbol for multiversioned functions.)
#if defined(__GNUC__) && !defined(__clang__)
#define PRT_GLOSSY_CLONES [[gnu::target_clones("arch=haswell", "default")]]
#else
#define PRT_GLOSSY_CLONES
#endif
PRT_GLOSSY_CLONES void accumulateRows(const float* m, std::size_t rows, std::size_t rowStride,
                                      std::size_t width, const float* d, const float* g, float* u,
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

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define PRT_GLOSSY_AVX2 1

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

/// The register-resident kernel for rows of up to 48 floats (B ≤ 6 scalar, B ≤ 4 RGB) on CPUs
/// with AVX2 and FMA; nullptr otherwise (the portable loop).
RowsFn pickRows(std::size_t width, bool glossy) {
  static const bool avx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  if (!avx2 || width == 0 || width > 48) return nullptr;
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

/// Checks shared by the kernels over matrix transfer (light bands checked by the caller).
void checkGlossyInputs(const TransferField& transfer, const PreparedMaterial& material,
                       const GlossyView& view, std::span<const Rgb> albedo) {
  const std::size_t nv = transfer.vertexCount;
  if (!transfer.isMatrix()) throw Error("relight: glossy relighting needs matrix transfer");
  if (transfer.channels != 1 && transfer.channels != 3)
    throw Error("relight: transfer has " + std::to_string(transfer.channels) + " channels");
  if (transfer.data.size() != nv * transfer.stride())
    throw Error("relight: transfer holds " + std::to_string(transfer.data.size()) +
                " floats, expected " + std::to_string(nv * transfer.stride()));
  if (material.bands != transfer.bands)
    throw Error("relight: material prepared for " + std::to_string(material.bands) +
                " bands, transfer has " + std::to_string(transfer.bands));
  if (view.positions.size() != nv || view.normals.size() != nv)
    throw Error("relight: positions and normals must hold one value per vertex (" +
                std::to_string(nv) + ")");
  if (!albedo.empty() && albedo.size() != 1 && albedo.size() != nv)
    throw Error("relight: " + std::to_string(albedo.size()) + " albedo values for " +
                std::to_string(nv) + " vertices (expected one per vertex, one, or none)");
}

/// The one pass over the matrices: for every vertex v, in parallel, u = M_vᵀ d and w = M_vᵀ g
/// over the first `columns` source coefficients (u, w: columns × channels floats, channel
/// fastest; w empty without a lobe), handed to visit(v, u, w). Allocation-free per vertex.
template <class Visit>
void forEachResponse(const TransferField& transfer, const PreparedMaterial& material,
                     const GlossyView& view, std::size_t columns, const Visit& visit) {
  const std::size_t nB = static_cast<std::size_t>(transfer.bands * transfer.bands);
  const std::size_t ch = static_cast<std::size_t>(transfer.channels);
  const std::size_t width = columns * ch, rowStride = nB * ch;
  const bool glossy = !material.glossy.empty();
  const float* M = transfer.data.data();
  const std::size_t grain = std::max<std::size_t>(16, 16384 / (nB * nB * ch));
#if defined(PRT_GLOSSY_AVX2)
  const RowsFn fast = pickRows(width, glossy);
#endif
  parallelFor(transfer.vertexCount, grain, [&](std::size_t begin, std::size_t end) {
    std::vector<float> y(nB), d(nB), g(glossy ? nB : 0), u(width), w(glossy ? width : 0);
    for (std::size_t v = begin; v < end; ++v) {
      material.responses(view.positions[v], view.normals[v], view.eye, d.data(), g.data(),
                         y.data());
#if defined(PRT_GLOSSY_AVX2)
      if (fast)
        fast(M + v * transfer.stride(), nB, rowStride, width, d.data(), glossy ? g.data() : nullptr,
             u.data(), w.data());
      else
#endif
        accumulateRows(M + v * transfer.stride(), nB, rowStride, width, d.data(),
                       glossy ? g.data() : nullptr, u.data(), w.data());
      visit(v, u, w);
    }
  });
}

}  // namespace

void relightGlossy(const TransferField& transfer, const PreparedLight& light,
                   const PreparedMaterial& material, const GlossyView& view,
                   std::span<const Rgb> albedo, std::span<Rgb> out) {
  checkGlossyInputs(transfer, material, view, albedo);
  const std::size_t nv = transfer.vertexCount;
  if (light.bands < 1 || light.bands > transfer.bands)
    throw Error("relight: prepared light has " + std::to_string(light.bands) +
                " bands, transfer has " + std::to_string(transfer.bands));
  if (out.size() != nv)
    throw Error("relight: output must hold one value per vertex (" + std::to_string(nv) + ")");
  const std::size_t nb = static_cast<std::size_t>(light.bands * light.bands);
  const std::size_t ch = static_cast<std::size_t>(transfer.channels);
  const bool glossy = !material.glossy.empty();
  const float* L = light.interleaved.data();  // (r, g, b) per coefficient
  forEachResponse(transfer, material, view, nb,
                  [&](std::size_t v, const std::vector<float>& u, const std::vector<float>& w) {
                    Rgb diff(0.0f), spec(0.0f);
                    for (std::size_t j = 0; j < nb; ++j)
                      for (std::size_t c = 0; c < 3; ++c) {
                        const std::size_t k = j * ch + (ch == 1 ? 0 : c);
                        diff[c] += u[k] * L[3 * j + c];
                        if (glossy) spec[c] += w[k] * L[3 * j + c];
                      }
                    out[v] = material.diffuseAt(albedo, v, nv) * diff + material.specular * spec;
                  });
}

TransferField viewTransfer(const TransferField& transfer, const PreparedMaterial& material,
                           const GlossyView& view, std::span<const Rgb> albedo) {
  checkGlossyInputs(transfer, material, view, albedo);
  const std::size_t nv = transfer.vertexCount;
  const std::size_t nB = static_cast<std::size_t>(transfer.bands * transfer.bands);
  const std::size_t ch = static_cast<std::size_t>(transfer.channels);
  const bool glossy = !material.glossy.empty();
  TransferField t = TransferField::zeros(TransferLayout::Vector, transfer.bands, 3, nv);
  forEachResponse(transfer, material, view, nB,
                  [&](std::size_t v, const std::vector<float>& u, const std::vector<float>& w) {
                    const Rgb kd = material.diffuseAt(albedo, v, nv);
                    float* row = t.vertex(v);
                    for (std::size_t j = 0; j < nB; ++j)
                      for (std::size_t c = 0; c < 3; ++c) {
                        const std::size_t k = j * ch + (ch == 1 ? 0 : c);
                        row[3 * j + c] =
                            kd[c] * u[k] + (glossy ? material.specular[c] * w[k] : 0.0f);
                      }
                  });
  return t;
}

RelightInfo relightGlossy(const TransferField& transfer, const sh::RgbSh& light,
                          const Material& material, const GlossyView& view,
                          std::span<const Rgb> albedo, std::span<Rgb> out, const Mat3d& rotation) {
  RelightInfo info;
  const int bands = std::min(light.bands, transfer.bands);
  const sh::Rotation rot(bands, rotation);
  const PreparedLight p = prepareLight(light, transfer.bands, &rot, &info);
  relightGlossy(transfer, p, prepareMaterial(material, transfer.bands), view, albedo, out);
  return info;
}

}  // namespace prt::relight
