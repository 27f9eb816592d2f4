#include "prt/relight/compressed.hpp"

#include <algorithm>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/sh.hpp"

namespace prt::relight {

namespace {

void checkShapes(const CompressedTransfer& t, const PreparedLight& light, std::size_t outSize,
                 std::size_t albedoSize) {
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

}  // namespace

ClusterLight projectClusters(const CompressedTransfer& t, const PreparedLight& light) {
  const std::size_t C = static_cast<std::size_t>(t.channels),
                    nB = static_cast<std::size_t>(t.bands * t.bands);
  const std::size_t nb = static_cast<std::size_t>(light.bands * light.bands);
  const std::size_t W = static_cast<std::size_t>(t.basisCount) + 1;
  const float* L = light.interleaved.data();  // (r, g, b) per coefficient
  // Scalar vectors: the light's channels apart, so each projection is three contiguous dots.
  std::vector<float> planar(C == 1 && t.layout == TransferLayout::Vector ? 3 * nb : 0);
  for (std::size_t i = 0; i < planar.size() / 3; ++i)
    for (std::size_t c = 0; c < 3; ++c) planar[c * nb + i] = L[3 * i + c];
  ClusterLight p;
  p.clusters = t.clusters;
  p.basisCount = t.basisCount;
  p.coeffs = t.layout == TransferLayout::Matrix ? static_cast<int>(nB) : 1;
  const std::size_t per = static_cast<std::size_t>(p.coeffs) * 3;
  p.rgb.assign(static_cast<std::size_t>(t.clusters) * W * per, 0.0f);
  parallelFor(static_cast<std::size_t>(t.clusters), 4, [&](std::size_t kb, std::size_t ke) {
    for (std::size_t k = kb; k < ke; ++k)
      for (std::size_t j = 0; j < W; ++j) {
        const float* x = j == 0 ? t.mean(k) : t.basisVector(k, j - 1);
        float* o = p.rgb.data() + (k * W + j) * per;
        if (t.layout == TransferLayout::Vector && C == 1) {
          // o_c = Σ_{i<nb} x_i L_{i,c}: scalar transfer multiplies all three light channels.
          for (std::size_t c = 0; c < 3; ++c) o[c] = dot8(x, planar.data() + c * nb, nb);
        } else if (t.layout == TransferLayout::Vector) {
          // RGB rows (i·3 + c) against the interleaved light: one elementwise product of 3·nb
          // floats, summed per channel.
          rgbDot(x, L, nb, o);
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

void relightCompressed(const CompressedTransfer& t, const ClusterLight& p,
                       std::span<const Rgb> albedo, std::span<Rgb> out) {
  if (t.layout != TransferLayout::Vector || p.coeffs != 1)
    throw Error("relight: diffuse relighting needs vector transfer (this one holds matrices)");
  if (p.clusters != t.clusters || p.basisCount != t.basisCount)
    throw Error("relight: cluster projections were made for another compressed transfer");
  const std::size_t nv = t.vertexCount, N = static_cast<std::size_t>(t.basisCount);
  if (out.size() != nv) throw Error("relight: output size does not match the vertex count");
  // The projections padded to 4 floats (r, g, b, 0) per vector, so the per-vertex sum is one
  // 4-wide multiply-add per weight (the compiler's SLP vectoriser); same operations in the same
  // order per channel as the 3-wide form.
  const std::size_t W4 = 4 * (N + 1);
  std::vector<float> table(static_cast<std::size_t>(t.clusters) * W4, 0.0f);
  for (std::size_t q = 0; q < static_cast<std::size_t>(t.clusters) * (N + 1); ++q)
    for (std::size_t c = 0; c < 3; ++c) table[4 * q + c] = p.rgb[3 * q + c];
  const float* proj = table.data();
  const float* w = t.weights.data();
  const std::uint32_t* id = t.cluster.data();
  const bool perVertex = albedo.size() == nv && nv > 1;
  const Rgb uniform = albedo.size() == 1 ? albedo[0] : Rgb(1.0f);
  parallelFor(nv, 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t v = b; v < e; ++v) {
      const float* q = proj + id[v] * W4;
      const float* wv = w + v * N;
      float acc[4] = {q[0], q[1], q[2], q[3]};
      for (std::size_t j = 0; j < N; ++j) {
        const float wj = wv[j];
        const float* qj = q + 4 + 4 * j;
        for (int c = 0; c < 4; ++c) acc[c] += wj * qj[c];
      }
      const Rgb a = perVertex ? albedo[v] : uniform;
      out[v] = Rgb(acc[0] * a.x, acc[1] * a.y, acc[2] * a.z);
    }
  });
}

void relightCompressed(const CompressedTransfer& t, const PreparedLight& light,
                       std::span<const Rgb> albedo, std::span<Rgb> out) {
  if (t.layout != TransferLayout::Vector)
    throw Error("relight: diffuse relighting needs vector transfer (this one holds matrices)");
  checkShapes(t, light, out.size(), albedo.size());
  relightCompressed(t, projectClusters(t, light), albedo, out);
}

void relightCompressedGlossy(const CompressedTransfer& t, const PreparedLight& light,
                             const PreparedMaterial& material, const GlossyView& view,
                             std::span<const Rgb> albedo, std::span<Rgb> out) {
  if (t.layout != TransferLayout::Matrix)
    throw Error("relight: glossy relighting needs matrix transfer");
  checkShapes(t, light, out.size(), albedo.size());
  const std::size_t nv = t.vertexCount;
  if (material.bands != t.bands)
    throw Error("relight: material prepared for " + std::to_string(material.bands) +
                " bands, transfer has " + std::to_string(t.bands));
  if (view.positions.size() != nv || view.normals.size() != nv)
    throw Error("relight: positions and normals must hold one value per vertex (" +
                std::to_string(nv) + ")");
  const ClusterLight p = projectClusters(t, light);
  const int bands = t.bands;
  const std::size_t nB = static_cast<std::size_t>(bands * bands),
                    N = static_cast<std::size_t>(t.basisCount);
  const std::size_t per = 3 * nB, W = N + 1;
  const bool glossy = !material.glossy.empty();
  parallelFor(nv, 256, [&](std::size_t b, std::size_t e) {
    std::vector<float> y(nB), d(nB), g(glossy ? nB : 0), lp(per);
    for (std::size_t v = b; v < e; ++v) {
      // L'_v = (M_k L) + Σ_j w_vj (B_kj L)
      const float* q = p.rgb.data() + t.cluster[v] * W * per;
      std::copy_n(q, per, lp.data());
      for (std::size_t j = 0; j < N; ++j) {
        const float wj = t.weights[v * N + j];
        const float* qj = q + (j + 1) * per;
        for (std::size_t i = 0; i < per; ++i) lp[i] += wj * qj[i];
      }
      material.responses(view.positions[v], view.normals[v], view.eye, d.data(), g.data(),
                         y.data());
      Rgb diff(0.0f), spec(0.0f);
      for (std::size_t i = 0; i < nB; ++i)
        for (int c = 0; c < 3; ++c) {
          diff[c] += d[i] * lp[3 * i + c];
          if (glossy) spec[c] += g[i] * lp[3 * i + c];
        }
      out[v] = material.diffuseAt(albedo, v, nv) * diff + material.specular * spec;
    }
  });
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
