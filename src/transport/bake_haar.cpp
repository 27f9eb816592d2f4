// Haar transfer (Ng, Ramamoorthi & Hanrahan 2003, §5): each row's occluded diffuse transfer over
// the texels of a cube map, D_j = (1/π) ∫_texel j (1 − V(ω)) max(n·ω, 0) dω = U_j − T_j,
// wavelet-transformed (haar/cube_haar.hpp) and pruned to the row's budget of terms
// (transfer/haar_rows.hpp). The unshadowed part U is not stored: relighting takes it from the
// light's SH in closed form (haar/haar_light.hpp), so the terms go to the shadow alone — an
// unoccluded vertex needs none, and a smooth cosine lobe never spends the budget a piecewise
// constant basis needs for it. (Ng et al. store T itself; measured here, at 64 terms per vertex
// storing D halves the error under a sun: docs/validation.md.)
//
// The estimator, as the SH bake's control variate:
//     D_j ≈ (1/S) Σ_s [ω_s blocked] max(n·ω_s, 0)/π · (2/N)² / |d_s|³
// with S rays per texel (the bake's samples) at points uniform on the texel's square of the
// face plane, jittered per row from (seed, row): unbiased, exactly 0 for unshadowed transfer
// and where nothing is blocked. Texels wholly below the horizon cast nothing. Noise estimate: Σ_j Var(T_j) ≤ Σ_s x_s² / S² (each single-ray
// term x_s; one ray per texel leaves no spread to measure, so the bound uses E[x²] ≥ Var x) —
// the variance of the row's response to the constant light, reported as the SH bake reports
// √(4π) T₀'s (so BakeStats' constant-light error means the same in both bases).

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "bake_common.hpp"
#include "bake_haar.hpp"
#include "prt/core/hash.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/transfer/haar_rows.hpp"

namespace prt::bakedetail {

namespace {

constexpr std::size_t kBatch = 64;
constexpr std::size_t kRowGrain = 2;

struct Scratch {
  std::vector<float> coeffs;
  std::vector<std::uint32_t> order;
  std::array<Ray, kBatch> rays;
  std::array<float, kBatch> value;  ///< max(n·ω,0)/π · weight / S of each ray
  std::array<std::uint32_t, kBatch> texel;
  std::array<std::uint8_t, kBatch> blocked;
};

/// One row at q into out (2 · terms floats); returns the variance bound above, over 4π.
double haarRow(const Occluder& occluder, const HaarSetup& setup, const RowPoint& q, Scratch& s,
               float* out, std::uint64_t& cast) {
  const haar::CubeTexels& cube = setup.texels;
  const int n = cube.resolution();
  const std::size_t count = cube.count();
  const Vec3d normal(q.normal);
  s.coeffs.assign(count, 0.0f);
  double variance = 0;
  if (setup.settings.mode != TransferMode::Unshadowed) {
    const int perTexel = setup.settings.samples;
    const Vec3f origin = q.position + q.normal * occluder.rayOffset(q.position);
    Pcg32 rng(deriveSeed(setup.settings.seed, static_cast<std::uint64_t>(q.id)));
    std::size_t nr = 0;
    const auto flush = [&] {
      if (nr == 0) return;
      occluder.occluded(std::span<const Ray>(s.rays.data(), nr),
                        std::span<std::uint8_t>(s.blocked.data(), nr));
      cast += nr;
      for (std::size_t r = 0; r < nr; ++r)
        if (s.blocked[r]) {
          s.coeffs[s.texel[r]] += s.value[r];
          variance += double(s.value[r]) * s.value[r];
        }
      nr = 0;
    };
    for (std::uint32_t j = 0; j < count; ++j) {
      if (!cube.aboveHorizon(j, normal)) continue;
      for (int k = 0; k < perTexel; ++k) {
        float w = 0;
        const float u = rng.uniform(), v = rng.uniform();
        const Vec3f d = cube.sample(j, u, v, w);
        const float c = dot(q.normal, d);
        if (c <= 0.0f) continue;  // the part of a texel below the horizon: 0, no ray
        s.rays[nr] = Ray{origin, d, 0.0f, std::numeric_limits<float>::infinity()};
        s.value[nr] = c * float(1.0 / kPi) * w / float(perTexel);
        s.texel[nr] = j;
        if (++nr == kBatch) flush();
      }
    }
    flush();
  }
  haar::forward(s.coeffs.data(), n);
  haar::pruneRow(s.coeffs.data(), n, std::size_t(setup.settings.haar.terms), out, s.order);
  return variance / (4.0 * kPi);
}

template <typename PointOf>
std::uint64_t computeRows(const Occluder& occluder, const HaarSetup& setup, std::size_t rows,
                          const PointOf& pointOf, float* out, double* variance,
                          Progress* progress) {
  const std::size_t stride = 2 * std::size_t(setup.settings.haar.terms);
  std::atomic<std::uint64_t> rays{0};
  parallelFor(rows, kRowGrain, [&](std::size_t b, std::size_t e) {
    if (progress) progress->check();
    Scratch s;
    std::uint64_t cast = 0;
    for (std::size_t r = b; r < e; ++r) {
      const double var = haarRow(occluder, setup, pointOf(r), s, out + r * stride, cast);
      if (variance) variance[r] = var;
    }
    rays.fetch_add(cast, std::memory_order_relaxed);
    if (progress) progress->advance(e - b);
  });
  return rays.load();
}

}  // namespace

std::shared_ptr<const HaarSetup> makeHaarSetup(const BakeSettings& s) {
  return std::make_shared<const HaarSetup>(HaarSetup{s, haar::CubeTexels(s.haar.resolution)});
}

std::uint64_t computeHaarRows(const Mesh& mesh, const Occluder& occluder, const HaarSetup& setup,
                              RowRange rows, float* out, double* variance, Progress* progress) {
  return computeRows(
      occluder, setup, rows.count,
      [&](std::size_t r) {
        const std::size_t v = rows.first + r;
        return RowPoint{mesh.positions[v], mesh.normals[v], v};
      },
      out, variance, progress);
}

std::uint64_t computeHaarTexelRows(const Occluder& occluder, const HaarSetup& setup,
                                   std::span<const RowPoint> points, float* out, double* variance,
                                   Progress* progress) {
  return computeRows(
      occluder, setup, points.size(), [&](std::size_t r) { return points[r]; }, out, variance,
      progress);
}

}  // namespace prt::bakedetail
