// Haar transfer (Ng, Ramamoorthi & Hanrahan 2003, §5): each row's occluded diffuse transfer over
// the texels of a cube map, D_j = (1/π) ∫_texel j (1 − V(ω)) max(n·ω, 0) dω = U_j − T_j — or,
// for a row that sees less than half its sky, the visible part T_j — wavelet-transformed
// (haar/cube_haar.hpp) and pruned to the row's budget of terms (transfer/haar_rows.hpp). The
// unshadowed part U of an occluded-part row is not stored: relighting takes it from the light in
// closed form (haar/haar_light.hpp), so the terms go to the shadow alone — an unoccluded vertex
// needs none, and a smooth cosine lobe never spends the budget a piecewise constant basis needs
// for it. (Ng et al. store T itself; measured here, at 64 terms per vertex storing D lowers the
// error under a sun from 13.7% to 5.0%: docs/haar.md.)
//
// The estimator: per texel above the horizon, S rays (the bake's samples) through points
// uniform on the texel's square of the face plane, jittered per row from (seed, row), and
//     D_j ≈ U_j · Σ_s [blocked] c_s w_s / Σ_s c_s w_s,   c = max(n·ω, 0), w = (2/N)²/|d|³,
// the texel's exact cosine integral U_j (Lambert's formula, haar/cube_texels.hpp) times the
// cosine-weighted share of its rays that are blocked: a ratio estimator, consistent, and exact
// where a texel is wholly open or wholly blocked — so in a sun's umbra the occluded part cancels
// the unshadowed part exactly, whatever the noise elsewhere. (The plain estimator
// Σ [blocked] c w / S left 1 in 20 of the bunny's vertices relit negative in the umbra.) Texels
// wholly below the horizon, and whole faces, cast nothing.
//
// Noise estimate: Var D_j ≈ U_j² p(1 − p)/S_j with p the blocked share of the rays of the texel
// and its eight neighbours on the face (one ray per texel leaves nothing to measure alone), summed
// over the texels — zero where a neighbourhood agrees, as inside a shadow or out of one — and
// reported over 4π, as the SH bake reports √(4π) T₀'s (so BakeStats' constant-light error means
// the same in both bases).

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "bake_common.hpp"
#include "bake_haar.hpp"
#include "prt/core/error.hpp"
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
  std::vector<std::pair<float, std::uint32_t>> order;
  std::vector<float> blockedWeight, totalWeight;  ///< per texel: Σ c w of blocked / all rays
  std::vector<std::uint8_t> blocked, cast;        ///< per texel: rays blocked / cast
  std::vector<std::uint8_t> near;                 ///< per texel: within one of a blocked ray
  std::array<Ray, kBatch> rays;
  std::array<float, kBatch> weight;  ///< c w of each ray
  std::array<std::uint32_t, kBatch> texel;
  std::array<std::uint8_t, kBatch> hit;
};

/// One row at q into out (haarRowFloats(terms) floats); returns the noise estimate above, over
/// 4π.
double haarRow(const Occluder& occluder, const HaarSetup& setup, const RowPoint& q, Scratch& s,
               float* out, std::uint64_t& rayCount) {
  const haar::CubeTexels& cube = setup.texels;
  const int n = cube.resolution();
  const std::size_t count = cube.count(), faceTexels = std::size_t(n) * std::size_t(n);
  const Vec3d normal(q.normal);
  s.coeffs.assign(count, 0.0f);
  double variance = 0;
  if (setup.settings.mode != TransferMode::Unshadowed) {
    s.blockedWeight.assign(count, 0.0f);
    s.totalWeight.assign(count, 0.0f);
    s.blocked.assign(count, 0);
    s.cast.assign(count, 0);
    const int perTexel = setup.settings.samples;
    const Vec3f origin = q.position + q.normal * occluder.rayOffset(q.position);
    Pcg32 rng(deriveSeed(setup.settings.seed, static_cast<std::uint64_t>(q.id)));
    std::size_t nr = 0;
    const auto flush = [&] {
      if (nr == 0) return;
      occluder.occluded(std::span<const Ray>(s.rays.data(), nr),
                        std::span<std::uint8_t>(s.hit.data(), nr));
      rayCount += nr;
      for (std::size_t r = 0; r < nr; ++r) {
        const std::uint32_t j = s.texel[r];
        s.totalWeight[j] += s.weight[r];
        ++s.cast[j];
        if (s.hit[r]) {
          s.blockedWeight[j] += s.weight[r];
          ++s.blocked[j];
        }
      }
      nr = 0;
    };
    for (int f = 0; f < 6; ++f) {
      const haar::CubeTexels::FaceSide side = cube.faceSide(f, q.normal);
      if (side == haar::CubeTexels::FaceSide::Below) continue;
      const auto first = std::uint32_t(std::size_t(f) * faceTexels);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::uint32_t j = first + std::uint32_t(y * n + x);
          if (side == haar::CubeTexels::FaceSide::Across && !cube.aboveHorizon(j, normal)) continue;
          for (int k = 0; k < perTexel; ++k) {
            float w = 0;
            const float u = rng.uniform(), v = rng.uniform();
            const Vec3f d = cube.sample(f, x, y, u, v, w);
            const float c = dot(q.normal, d);
            if (c <= 0.0f) continue;  // the part of a texel below the horizon: no ray
            s.rays[nr] = Ray{origin, d, 0.0f, std::numeric_limits<float>::infinity()};
            s.weight[nr] = c * w;
            s.texel[nr] = j;
            if (++nr == kBatch) flush();
          }
        }
    }
    flush();
    // Only texels within one of a blocked ray can hold D or be mixed: mark them first.
    s.near.assign(count, 0);
    for (std::uint32_t j = 0; j < count; ++j) {
      if (s.blocked[j] == 0) continue;
      const std::size_t r = j % faceTexels, face = j - r;
      const int x = int(r % std::size_t(n)), y = int(r / std::size_t(n));
      for (int yy = std::max(0, y - 1); yy <= std::min(n - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(n - 1, x + 1); ++xx)
          s.near[face + std::size_t(yy) * std::size_t(n) + std::size_t(xx)] = 1;
    }
    for (std::uint32_t j = 0; j < count; ++j) {
      if (!s.near[j] || s.cast[j] == 0) continue;
      const std::size_t r = j % faceTexels, face = j - r;
      const int x = int(r % std::size_t(n)), y = int(r / std::size_t(n));
      // The blocked share of the neighbourhood's rays, for the noise estimate.
      int b = 0, c = 0;
      for (int yy = std::max(0, y - 1); yy <= std::min(n - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(n - 1, x + 1); ++xx) {
          const std::size_t k = face + std::size_t(yy) * std::size_t(n) + std::size_t(xx);
          b += s.blocked[k];
          c += s.cast[k];
        }
      const bool mixed = b > 0 && b < c;
      if (s.blocked[j] == 0 && !mixed) continue;
      const double u = cube.clampedCosine(j, normal);
      if (s.blocked[j] > 0) s.coeffs[j] = float(u * s.blockedWeight[j] / s.totalWeight[j]);
      if (mixed) {
        const double p = double(b) / c;
        variance += u * u * p * (1 - p) / s.cast[j];
      }
    }
  }
  // The smaller half (haar_rows.hpp): past half its sky occluded (Σ_j U_j = 1), the visible
  // part T_j = U_j − D_j over every texel above the horizon.
  double occluded = 0;
  for (float d : s.coeffs) occluded += d;
  haar::HaarRowKind kind = haar::HaarRowKind::Occluded;
  if (occluded > haar::kVisibleRowAbove) {
    kind = haar::HaarRowKind::Visible;
    for (int f = 0; f < 6; ++f) {
      const haar::CubeTexels::FaceSide side = cube.faceSide(f, q.normal);
      const auto first = std::uint32_t(std::size_t(f) * faceTexels);
      for (std::uint32_t j = first; j < first + faceTexels; ++j) {
        if (side == haar::CubeTexels::FaceSide::Below ||
            (side == haar::CubeTexels::FaceSide::Across && !cube.aboveHorizon(j, normal))) {
          s.coeffs[j] = 0.0f;
          continue;
        }
        s.coeffs[j] = float(cube.clampedCosine(j, normal)) - s.coeffs[j];
      }
    }
  }
  haar::forward(s.coeffs.data(), n);
  haar::pruneRow(s.coeffs.data(), n, std::size_t(setup.settings.haar.terms), kind, out, s.order);
  return variance / (4.0 * kPi);
}

template <typename PointOf>
std::uint64_t computeRows(const Occluder& occluder, const HaarSetup& setup, std::size_t rows,
                          const PointOf& pointOf, HaarBounceSource bounce, std::size_t stride,
                          float* out, double* variance, Progress* progress) {
  const std::size_t pairs = haar::haarRowFloats(setup.settings.haar.terms);
  PRT_CHECK(stride == pairs + (bounce.values ? bounce.stride : 0), "a Haar row and its bounce");
  std::atomic<std::uint64_t> rays{0};
  parallelFor(rows, kRowGrain, [&](std::size_t b, std::size_t e) {
    if (progress) progress->check();
    Scratch s;
    std::uint64_t cast = 0;
    for (std::size_t r = b; r < e; ++r) {
      const RowPoint q = pointOf(r);
      const double var = haarRow(occluder, setup, q, s, out + r * stride, cast);
      if (bounce.values)
        std::copy_n(bounce.values + q.id * bounce.stride, bounce.stride, out + r * stride + pairs);
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
                              RowRange rows, HaarBounceSource bounce, std::size_t stride,
                              float* out, double* variance, Progress* progress) {
  return computeRows(
      occluder, setup, rows.count,
      [&](std::size_t r) {
        const std::size_t v = rows.first + r;
        return RowPoint{mesh.positions[v], mesh.normals[v], v};
      },
      bounce, stride, out, variance, progress);
}

std::uint64_t computeHaarTexelRows(const Occluder& occluder, const HaarSetup& setup,
                                   std::span<const RowPoint> points, HaarBounceSource bounce,
                                   std::size_t stride, float* out, double* variance,
                                   Progress* progress) {
  return computeRows(
      occluder, setup, points.size(), [&](std::size_t r) { return points[r]; }, bounce, stride, out,
      variance, progress);
}

}  // namespace prt::bakedetail
