// The edge-avoiding à-trous filter of per-texel transfer (denoise_texels.hpp gives the maths).

#include "prt/transport/denoise_texels.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transport/lightmap_seam_fix.hpp"
#include "texel_domain.hpp"

namespace prt {

namespace {

constexpr std::array<double, 5> kB3 = {1.0 / 16, 4.0 / 16, 6.0 / 16, 4.0 / 16, 1.0 / 16};

/// The UV chart of every triangle: its connected component through shared vertices (a chart's
/// seam duplicates its vertices, which carry one lightmap UV each).
std::vector<std::int32_t> triangleCharts(const Mesh& mesh, std::size_t* count) {
  std::vector<std::uint32_t> parent(mesh.vertexCount());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : mesh.triangles) {
    const std::uint32_t a = find(t[0]);
    parent[find(t[1])] = a;
    parent[find(t[2])] = a;
  }
  std::vector<std::int32_t> id(mesh.vertexCount(), -1), chart(mesh.triangleCount());
  std::int32_t next = 0;
  for (std::size_t i = 0; i < mesh.triangleCount(); ++i) {
    const std::uint32_t root = find(mesh.triangles[i][0]);
    if (id[root] < 0) id[root] = next++;
    chart[i] = id[root];
  }
  if (count) *count = std::size_t(next);
  return chart;
}

/// The guide of every texel of the lightmap: its chart (−1: not valid), point and normal.
struct Guide {
  int width = 0, height = 0;
  std::vector<std::int32_t> chart;
  std::vector<Vec3f> position, normal;
  std::vector<std::uint32_t> valid;  ///< ascending
  std::size_t charts = 0;
  bool same(std::size_t p, std::size_t q) const { return chart[q] >= 0 && chart[q] == chart[p]; }
};

Guide makeGuide(const Mesh& mesh, const bakedetail::TexelDomain& d) {
  Guide g;
  g.width = d.width, g.height = d.height;
  g.chart.assign(d.texels(), -1);
  g.position.assign(d.texels(), Vec3f(0.0f));
  g.normal.assign(d.texels(), Vec3f(0.0f));
  std::size_t charts = 0;
  const std::vector<std::int32_t> triChart = triangleCharts(mesh, &charts);
  std::vector<std::uint8_t> used(charts, 0);
  const auto& s = d.samples.samples;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (d.inside[i]) continue;
    const std::size_t t = s[i].texel;
    g.chart[t] = triChart[s[i].triangle];
    g.position[t] = d.points[i].position;
    g.normal[t] = d.points[i].normal;
    used[std::size_t(g.chart[t])] = 1;
  }
  for (std::size_t t = 0; t < d.texels(); ++t)
    if (g.chart[t] >= 0) g.valid.push_back(std::uint32_t(t));
  g.charts = std::size_t(std::count(used.begin(), used.end(), std::uint8_t(1)));
  return g;
}

/// s: the median distance between horizontally or vertically neighbouring valid texels of one
/// chart (0 when no two are neighbours).
double texelSize(const Guide& g) {
  std::vector<float> d;
  const std::size_t w = std::size_t(g.width);
  for (std::uint32_t t : g.valid) {
    const std::size_t x = t % w;
    if (x + 1 < w && g.same(t, t + 1)) d.push_back(length(g.position[t + 1] - g.position[t]));
    if (t + w < g.chart.size() && g.same(t, t + w))
      d.push_back(length(g.position[t + w] - g.position[t]));
  }
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(d.size() / 2), d.end());
  return d[d.size() / 2];
}

/// σ_p² of every valid texel (see the header): the median over its chart's 5 × 5 window of the
/// scaled residuals against the 4-neighbours' mean.
std::vector<double> noiseVariance(const Guide& g, const float* rows, std::size_t k) {
  const std::size_t n = g.chart.size(), w = std::size_t(g.width);
  std::vector<double> r2(n, -1.0);  // −1: none (its 2 × 2 block leaves its chart)
  parallelFor(g.valid.size(), 256, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const std::size_t p = g.valid[i], x = p % w, y = p / w;
      if (x + 1 >= w || y + 1 >= std::size_t(g.height)) continue;
      const std::size_t px = p + 1, py = p + w, pxy = p + w + 1;
      if (!g.same(p, px) || !g.same(p, py) || !g.same(p, pxy)) continue;
      double s = 0;
      for (std::size_t c = 0; c < k; ++c) {
        const double h = 0.5 * (double(rows[p * k + c]) - rows[px * k + c] - rows[py * k + c] +
                                rows[pxy * k + c]);
        s += h * h;
      }
      r2[p] = s;
    }
  });
  std::vector<double> var(n, 0.0);
  parallelFor(g.valid.size(), 256, [&](std::size_t b, std::size_t e) {
    std::vector<double> window;
    for (std::size_t i = b; i < e; ++i) {
      const std::size_t p = g.valid[i];
      const int x = int(p % w), y = int(p / w);
      window.clear();
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) continue;
          const std::size_t q = std::size_t(qy) * w + std::size_t(qx);
          if (g.same(p, q) && r2[q] >= 0) window.push_back(r2[q]);
        }
      if (window.empty()) continue;
      std::nth_element(window.begin(), window.begin() + std::ptrdiff_t(window.size() / 2),
                       window.end());
      var[p] = window[window.size() / 2];
    }
  });
  return var;
}

/// The unshadowed transfer U(n_p) at every valid texel (W·H rows of `k` floats, zero elsewhere):
/// a vector's (A_l/π) Y_lm(n), a matrix's H(n), the same for every channel (interleaved after
/// each coefficient) — the part of a row its bake's control variate made exact.
std::vector<float> unshadowedRows(const Guide& g, const Transfer& t) {
  const std::size_t k = t.stride(), nc = std::size_t(t.bands()) * std::size_t(t.bands());
  const std::size_t channels = std::size_t(t.channels());
  std::vector<float> u(g.chart.size() * k, 0.0f);
  std::vector<Vec3f> normals(g.valid.size());
  for (std::size_t i = 0; i < g.valid.size(); ++i) normals[i] = normalize(g.normal[g.valid[i]]);
  if (t.isMatrix()) {
    const std::vector<float> h = bakedetail::unshadowedMatrixRows(t.bands(), normals);
    for (std::size_t i = 0; i < g.valid.size(); ++i)
      for (std::size_t e = 0; e < nc * nc; ++e)
        for (std::size_t c = 0; c < channels; ++c)
          u[g.valid[i] * k + e * channels + c] = h[i * nc * nc + e];
    return u;
  }
  const std::vector<double> a = sh::clampedCosineKernel(t.bands());
  std::vector<float> y(nc);
  for (std::size_t i = 0; i < g.valid.size(); ++i) {
    sh::eval(t.bands(), normals[i], y.data());
    for (int l = 0, e = 0; l < t.bands(); ++l)
      for (int m = -l; m <= l; ++m, ++e)
        for (std::size_t c = 0; c < channels; ++c)
          u[g.valid[i] * k + std::size_t(e) * channels + c] = float(a[std::size_t(l)] / kPi) * y[std::size_t(e)];
  }
  return u;
}

double rmsOf(const std::vector<double>& var, const Guide& g) {
  if (g.valid.empty()) return 0;
  double s = 0;
  for (std::uint32_t t : g.valid) s += var[t];
  return std::sqrt(s / double(g.valid.size()));
}

}  // namespace

void checkDenoiseSettings(const DenoiseSettings& s) {
  if (s.iterations < 1 || s.iterations > 8)
    throw Error("denoise: iterations must be 1..8, got " + std::to_string(s.iterations));
  if (!(s.strength > 0) || !std::isfinite(s.strength))
    throw Error("denoise: strength must be a positive number");
  if (!(s.normalPower >= 0) || !std::isfinite(s.normalPower))
    throw Error("denoise: the normals' exponent must be a number ≥ 0");
}

Transfer denoiseTexels(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                       const DenoiseSettings& settings, DenoiseStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  checkDenoiseSettings(settings);
  const std::string& name = mesh.source;
  if (transfer.domain() != TransferDomain::Texels)
    throw Error(name, "denoising filters per-texel transfer in its lightmap (bake with --domain "
                      "texels)");
  if (transfer.compressed())
    throw Error(name, "holds compressed transfer: denoise before compressing");
  const TransferShape::LightmapSize lm = transfer.shape().lightmap;
  if (transfer.rows().first != 0 || transfer.rows().count != lm.texels())
    throw Error(name, "holds texels " + std::to_string(transfer.rows().first) + ".." +
                          std::to_string(transfer.rows().end()) + " of " +
                          std::to_string(lm.texels()) +
                          ": the filter reads neighbours across the whole lightmap (merge first)");
  const bakedetail::TexelDomain d = bakedetail::makeTexelDomain(
      mesh, occluder, mesh.lightmapUvs, lm.width, lm.height, lm.padding, {0, lm.texels()});
  const Guide g = makeGuide(mesh, d);
  const std::size_t k = transfer.stride(), n = lm.texels(), w = std::size_t(lm.width);
  // The filter runs on the residual D = U − T, the part of each row its Monte Carlo estimated
  // (the blocked light, the bounces): U(n) is exact and carries most of a row's change across a
  // curved surface, which a filter of T would have to follow; D is zero where nothing blocks.
  const std::vector<float> u = unshadowedRows(g, transfer);
  std::vector<float> cur(transfer.values().begin(), transfer.values().end());
  for (std::uint32_t p : g.valid)
    for (std::size_t c = 0; c < k; ++c) cur[p * k + c] = u[p * k + c] - cur[p * k + c];
  std::vector<double> var = noiseVariance(g, cur.data(), k);
  const double s = texelSize(g);
  DenoiseStats st;
  st.texels = g.valid.size();
  st.charts = g.charts;
  st.texelSize = s;
  st.noiseBefore = rmsOf(var, g);
  const double k2 = settings.strength * settings.strength;
  std::vector<float> next(cur);
  std::vector<double> nextVar(var);
  for (int level = 0; level < settings.iterations; ++level) {
    const int step = 1 << level;
    // The taps' reach in the world: 2^(i+1) texels (a chart's distortion or a fold moves a
    // tap farther than that).
    const double reach = 2.0 * step * s, posScale = reach > 0 ? 1.0 / (2 * reach * reach) : 0.0;
    parallelFor(g.valid.size(), 64, [&](std::size_t b, std::size_t e) {
      std::vector<double> sum(k);
      for (std::size_t i = b; i < e; ++i) {
        const std::size_t p = g.valid[i];
        const int x = int(p % w), y = int(p / w);
        // The taps and their weights, then the fit: the value at p of the weighted
        // least-squares plane over the taps' lightmap offsets (the weighted mean where the taps
        // do not span a plane: a one-texel-wide strip of a chart).
        std::array<std::size_t, 25> tq{};
        std::array<double, 25> tw{}, ta{}, tb{};
        int taps = 0;
        for (int a = -2; a <= 2; ++a)
          for (int bb = -2; bb <= 2; ++bb) {
            const int qx = x + a * step, qy = y + bb * step;
            if (qx < 0 || qy < 0 || qx >= lm.width || qy >= lm.height) continue;
            const std::size_t q = std::size_t(qy) * w + std::size_t(qx);
            if (!g.same(p, q)) continue;
            double wt = kB3[std::size_t(a + 2)] * kB3[std::size_t(bb + 2)];
            if (q != p) {
              const double c = std::max(0.0f, dot(g.normal[p], g.normal[q]));
              wt *= std::pow(c, settings.normalPower);
              const Vec3f dx = g.position[p] - g.position[q];
              wt *= std::exp(-double(dot(dx, dx)) * posScale);
              double d2 = 0;
              for (std::size_t c2 = 0; c2 < k; ++c2) {
                const double dv = double(cur[p * k + c2]) - cur[q * k + c2];
                d2 += dv * dv;
              }
              const double noise = var[p] + var[q];
              wt *= noise > 0 ? std::exp(-d2 / (2 * k2 * noise)) : (d2 == 0 ? 1.0 : 0.0);
            }
            if (wt <= 0) continue;
            tq[taps] = q, tw[taps] = wt, ta[taps] = a, tb[taps] = bb, ++taps;
          }
        // λ_q: the weights of the fit's value at p, α = Σ λ_q T_q.
        std::array<double, 25> lambda{};
        double wsum = 0;
        for (int t = 0; t < taps; ++t) wsum += tw[t];
        for (int t = 0; t < taps; ++t) lambda[t] = tw[t] / wsum;
        {
          double A[3][3] = {};
          for (int t = 0; t < taps; ++t) {
            const double f[3] = {1, ta[t], tb[t]};
            for (int i2 = 0; i2 < 3; ++i2)
              for (int j2 = 0; j2 < 3; ++j2) A[i2][j2] += tw[t] * f[i2] * f[j2];
          }
          // l = A⁻¹ e₁ (its first column, by cofactors), when A is well conditioned.
          const double c00 = A[1][1] * A[2][2] - A[1][2] * A[2][1];
          const double c10 = A[1][2] * A[2][0] - A[1][0] * A[2][2];
          const double c20 = A[1][0] * A[2][1] - A[1][1] * A[2][0];
          const double det = A[0][0] * c00 + A[0][1] * c10 + A[0][2] * c20;
          const double scale = A[0][0] * A[1][1] * A[2][2];
          if (scale > 0 && det > 1e-3 * scale) {
            const double l[3] = {c00 / det, c10 / det, c20 / det};
            for (int t = 0; t < taps; ++t) lambda[t] = tw[t] * (l[0] + l[1] * ta[t] + l[2] * tb[t]);
          }
        }
        std::fill(sum.begin(), sum.end(), 0.0);
        double v = 0;
        for (int t = 0; t < taps; ++t) {
          const std::size_t q = tq[t];
          for (std::size_t c2 = 0; c2 < k; ++c2) sum[c2] += lambda[t] * cur[q * k + c2];
          v += lambda[t] * lambda[t] * var[q];
        }
        for (std::size_t c2 = 0; c2 < k; ++c2) next[p * k + c2] = float(sum[c2]);
        nextVar[p] = v;
      }
    });
    cur.swap(next);
    var.swap(nextVar);
    // (next and nextVar now hold the previous level; every valid texel is rewritten above.)
  }
  st.noiseAfter = rmsOf(var, g);
  for (std::uint32_t p : g.valid)
    for (std::size_t c = 0; c < k; ++c) cur[p * k + c] = u[p * k + c] - cur[p * k + c];

  // Laid out as the bake lays out its result: the gutter dilated, texels inside geometry refilled.
  std::vector<std::uint8_t> filled;
  std::vector<float> image = d.layOut(cur.data(), {0, n}, k, TexelDilation::Mean, filled);
  if (lm.padding == 0)
    for (std::size_t t = 0; t < n; ++t)
      if (d.samples.sampleOfTexel[t] < 0) std::fill_n(image.begin() + std::ptrdiff_t(t * k), k, 0.0f);
  TransferShape shape = transfer.shape();
  shape.lightmap.denoised = true;
  shape.lightmap.seamsFixed = false;
  Transfer out = Transfer::dense(shape, FloatArray(std::move(image)));
  // Filtering within charts moves the two sides of a seam apart again: fix them again.
  if (lm.seamsFixed) out = fixLightmapSeams(mesh, out);
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = st;
  return out;
}

}  // namespace prt
