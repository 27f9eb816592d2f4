#include "prt/relight/compressed.hpp"

#include "compressed_internal.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/sh.hpp"

namespace prt::relight {

void checkCompressedShapes(const CompressedTransfer& t, const PreparedLight& light,
                           std::size_t outSize, std::size_t albedoSize) {
  if (light.bands < 1 || light.bands > t.bands)
    throw Error("relight: prepared light has " + std::to_string(light.bands) +
                " bands, transfer has " + std::to_string(t.bands));
  const std::size_t nv = t.vertexCount, N = static_cast<std::size_t>(t.basisCount);
  if (t.cluster.size() != nv || t.weights.size() != nv * N ||
      t.means.size() != static_cast<std::size_t>(t.clusters) * t.stride() ||
      t.basis.size() != static_cast<std::size_t>(t.clusters) * N * t.stride())
    throw Error("relight: compressed transfer arrays do not match its shape");
  if (outSize != nv)
    throw Error("relight: output holds " + std::to_string(outSize) + " values for " +
                std::to_string(nv) + " vertices");
  if (albedoSize > 1 && albedoSize != nv)
    throw Error("relight: " + std::to_string(albedoSize) + " albedo values for " +
                std::to_string(nv) + " vertices (expected one per vertex, one, or none)");
}

namespace {

#if defined(__GNUC__) && !defined(__clang__)
#define PRT_PROJECT_CLONES [[gnu::target_clones("arch=haswell", "default")]]
#else
#define PRT_PROJECT_CLONES
#endif
// o[3i + c] = Σ_{l<nb} X_il L_lc for one scalar B² × B² matrix X (the glossy per-frame step,
// K(N+1) matrices): each row against the three light planes (`pad` floats each, zero past nb)
// in eight independent lanes, so the loop vectorises without reassociating a sum (the lanes are
// added in a fixed order at the end: the result does not depend on the thread count).
// Compiled for AVX2 and the baseline, picked at load time.
PRT_PROJECT_CLONES void projectScalarMatrix(const float* x, std::size_t nB, std::size_t nb,
                                            const float* planes, std::size_t pad, float* o) {
  for (std::size_t i = 0; i < nB; ++i) {
    const float* row = x + i * nB;
    float acc[3][8] = {};
    std::size_t l = 0;
    for (; l + 8 <= nb; l += 8)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 8; ++k) acc[c][k] += row[l + k] * planes[c * pad + l + k];
    for (int k = 0; l + k < nb; ++k)  // the last nb mod 8 columns
      for (int c = 0; c < 3; ++c) acc[c][k] += row[l + k] * planes[c * pad + l + k];
    for (int c = 0; c < 3; ++c)
      o[3 * i + c] = ((acc[c][0] + acc[c][1]) + (acc[c][2] + acc[c][3])) +
                     ((acc[c][4] + acc[c][5]) + (acc[c][6] + acc[c][7]));
  }
}

}  // namespace

AlignedFloats alignedZeros(std::size_t n) {
  const std::size_t bytes = std::max<std::size_t>(32, (n * sizeof(float) + 31) & ~std::size_t(31));
  float* p = static_cast<float*>(std::aligned_alloc(32, bytes));
  if (!p) throw Error("relight: out of memory (" + std::to_string(bytes) + " bytes)");
  std::fill_n(p, bytes / sizeof(float), 0.0f);
  return AlignedFloats(p);
}

ClusterLight projectClusters(const CompressedTransfer& t, const PreparedLight& light) {
  const std::size_t C = static_cast<std::size_t>(t.channels),
                    nB = static_cast<std::size_t>(t.bands * t.bands);
  const std::size_t nb = static_cast<std::size_t>(light.bands * light.bands);
  const std::size_t W = static_cast<std::size_t>(t.basisCount) + 1;
  const float* L = light.interleaved.data();  // (r, g, b) per coefficient
  ClusterLight p;
  p.clusters = t.clusters;
  p.basisCount = t.basisCount;
  p.coeffs = t.layout == TransferLayout::Matrix ? static_cast<int>(nB) : 1;
  const std::size_t per = static_cast<std::size_t>(p.coeffs) * 3;
  p.rgb.assign(static_cast<std::size_t>(t.clusters) * W * per, 0.0f);
  // The light as three zero-padded planes for the scalar-matrix products.
  const std::size_t pad = (nb + 7) & ~std::size_t(7);
  std::vector<float> planes(3 * pad, 0.0f);
  for (std::size_t l = 0; l < nb; ++l)
    for (std::size_t c = 0; c < 3; ++c) planes[c * pad + l] = L[3 * l + c];
  parallelFor(static_cast<std::size_t>(t.clusters), 4, [&](std::size_t kb, std::size_t ke) {
    for (std::size_t k = kb; k < ke; ++k)
      for (std::size_t j = 0; j < W; ++j) {
        const float* x = j == 0 ? t.mean(k) : t.basisVector(k, j - 1);
        float* o = p.rgb.data() + (k * W + j) * per;
        if (t.layout == TransferLayout::Vector) {
          // Row index (i·C + c); scalar transfer (C = 1) multiplies all three light channels.
          for (std::size_t i = 0; i < nb; ++i)
            for (std::size_t c = 0; c < 3; ++c) o[c] += x[i * C + (C == 1 ? 0 : c)] * L[3 * i + c];
        } else if (C == 1) {
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

void relightCompressed(const CompressedTransfer& t, const PreparedLight& light,
                       std::span<const Rgb> albedo, std::span<Rgb> out) {
  if (t.layout != TransferLayout::Vector)
    throw Error("relight: diffuse relighting needs vector transfer (this one holds matrices)");
  checkCompressedShapes(t, light, out.size(), albedo.size());
  relightCompressed(t, projectClusters(t, light), albedo, out);
}

RelightInfo relightCompressed(const CompressedTransfer& t, const sh::RgbSh& light,
                              const Material& material, const GlossyView& view,
                              std::span<const Rgb> albedo, std::span<Rgb> out,
                              const Mat3d& rotation) {
  RelightInfo info;
  const int bands = std::min(light.bands, t.bands);
  const sh::Rotation rot(bands, rotation);
  const PreparedLight p = prepareLight(light, t.bands, &rot, &info);
  if (t.layout == TransferLayout::Matrix)
    relightCompressedGlossy(t, p, prepareMaterial(material, t.bands), view, albedo, out);
  else
    relightCompressed(t, p, material.diffuseOr(albedo), out);
  return info;
}

}  // namespace prt::relight
