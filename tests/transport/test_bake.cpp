// Physics and invariants of the diffuse transfer bake (prt/transport/bake.hpp), each against an
// analytic answer or an exact property of the estimator:
//  * convex sphere: nothing self-shadows, so shadowed == unshadowed bit for bit;
//  * white furnace: L = 1 relights a convex object to exactly 1 with cosine-Sobol' sampling,
//    and to 1 within the stated standard error with uniform random sampling;
//  * unshadowed transfer == the clamped-cosine lobe (A_l/π) Y_lm(n) (Ramamoorthi & Hanrahan 2001);
//  * sphere above a plane: the cosine-weighted unoccluded fraction below it is 1 − (r/h)²;
//  * inter-reflection in a box with albedo 1: radiance rises toward 1, never above it, the gap
//    shrinking geometrically; with albedo ρ each bounce is at most ρ times the previous one;
//  * RGB transfer channels equal scalar bakes with the channel's albedo;
//  * determinism over threads and vertex ranges; rejection of bad settings; cancellation.

#include <gtest/gtest.h>

#include "common/builtin_scene.hpp"
#include "common/random_data.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transport/bake.hpp"

namespace prt {
namespace {

const double kSqrt4Pi = std::sqrt(4.0 * kPi);

using Scene = testdata::BuiltinScene;

BakeSettings settings(TransferMode mode, int bands, int samples) {
  BakeSettings s;
  s.mode = mode;
  s.bands = bands;
  s.samples = samples;
  s.seed = 1234;
  return s;
}

TEST(Bake, ConvexSphereHasNoSelfShadowing) {
  Scene scene("builtin:sphere?subdiv=3");
  BakeStats stats;
  const auto unshadowed =
      bake(scene.mesh, *scene.occluder, settings(TransferMode::Unshadowed, 4, 256));
  const auto shadowed =
      bake(scene.mesh, *scene.occluder, settings(TransferMode::Shadowed, 4, 256), &stats);
  ASSERT_EQ(shadowed.values().size(), scene.mesh.vertexCount() * 16);
  EXPECT_EQ(testdata::valuesOf(shadowed),
            testdata::valuesOf(unshadowed));  // bit-identical: every ray escapes
  EXPECT_EQ(stats.rays, scene.mesh.vertexCount() * 256);
  EXPECT_GT(stats.raysPerSecond, 0.0);
}

TEST(Bake, WhiteFurnaceOnConvexObjectIsExactWithCosineSobol) {
  // Under L = 1 (only L00 = √(4π)), T·L = √(4π) T₀ = (1/N) Σ √(4π) Y00 V = 1 exactly when every
  // sample is visible: only float rounding remains.
  Scene scene("builtin:sphere?subdiv=3");
  BakeStats stats;
  const auto t =
      bake(scene.mesh, *scene.occluder, settings(TransferMode::Shadowed, 3, 512), &stats);
  for (std::size_t v = 0; v < t.rowCount(); ++v)
    ASSERT_NEAR(t.row(v)[0] * kSqrt4Pi, 1.0, 2e-6) << "vertex " << v;
  // The i.i.d. standard error of a zero-variance estimator is zero.
  EXPECT_LT(stats.stdErrConstMax, 1e-6);
}

TEST(Bake, WhiteFurnaceWithUniformRandomWithinStatedError) {
  Scene scene("builtin:sphere?subdiv=2");
  BakeSettings s = settings(TransferMode::Shadowed, 3, 1024);
  s.sampling = Sampling::UniformRandom;
  BakeStats stats;
  const auto t = bake(scene.mesh, *scene.occluder, s, &stats);
  // Per sample 4 max(cos,0) · √(4π) Y00 has mean 1 and variance 4·(1/2)·... = 1 (E[16 cos²]/2
  // over the sphere = 16/6 → Var = 8/3 − 1 = 5/3); the reported error must say so.
  const double expectedSe = std::sqrt(5.0 / 3.0 / 1024);
  EXPECT_NEAR(stats.stdErrConstMean, expectedSe, 0.1 * expectedSe);
  double worst = 0, sumSq = 0;
  for (std::size_t v = 0; v < t.rowCount(); ++v) {
    const double e = t.row(v)[0] * kSqrt4Pi - 1.0;
    worst = std::max(worst, std::abs(e));
    sumSq += e * e;
  }
  // RMS over vertices within 20% of the stated error; no vertex beyond 5 standard errors.
  EXPECT_NEAR(std::sqrt(sumSq / t.rowCount()), expectedSe, 0.2 * expectedSe);
  EXPECT_LT(worst, 5 * expectedSe);
}

TEST(Bake, UnshadowedEqualsClampedCosineLobe) {
  // T_lm(n) = (A_l/π) Y_lm(n): A_0 = π, A_1 = 2π/3, A_2 = π/4, A_3 = 0, A_4 = -π/24.
  // Cosine-Sobol' bakes it in closed form (exact to float rounding); uniform random sampling
  // estimates it, within a few standard errors of 4 max(cos,0) Y_lm (< 5/√N per coefficient).
  const int bands = 5;
  const auto A = sh::clampedCosineKernel(bands);
  ASSERT_NEAR(A[2], kPi / 4, 1e-12);
  ASSERT_NEAR(A[3], 0.0, 1e-12);
  ASSERT_NEAR(A[4], -kPi / 24, 1e-12);
  Scene scene("builtin:sphere?subdiv=2");
  for (Sampling sampling : {Sampling::CosineSobol, Sampling::UniformRandom}) {
    BakeSettings s = settings(TransferMode::Unshadowed, bands, 1024);
    s.sampling = sampling;
    const auto t = bake(scene.mesh, *scene.occluder, s);
    double worst = 0, sumSq = 0;
    std::vector<double> y(bands * bands);
    for (std::size_t v = 0; v < t.rowCount(); ++v) {
      sh::evalReference(bands, Vec3d(scene.mesh.normals[v]), y.data());
      for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) {
          const int i = sh::index(l, m);
          const double e = t.row(v)[i] - A[l] / kPi * y[i];
          worst = std::max(worst, std::abs(e));
          sumSq += e * e;
        }
    }
    if (sampling == Sampling::CosineSobol) {
      EXPECT_LT(worst, 1e-6);
    } else {
      // RMS error ~ 1/√N (the per-sample values have variance ≲ 1); never 0.
      const double rms = std::sqrt(sumSq / (t.rowCount() * bands * bands));
      EXPECT_GT(rms, 0.1 / std::sqrt(1024.0));
      EXPECT_LT(rms, 1.5 / std::sqrt(1024.0));
    }
  }
}

TEST(Bake, ScrambledSobolCosineEstimateOfTheLobeIsAccurate) {
  // The control variate behind cosine-Sobol' shadowed bakes relies on (1/N) Σ Y_i(ω_s) over the
  // vertex's scrambled points reproducing (A_l/π) Y_lm(n): check it at 1024 points, to 1e-3 in
  // every coefficient, for many normals and seeds, with the same sampler the bake uses.
  const int bands = 5, n = 1024;
  const auto A = sh::clampedCosineKernel(bands);
  const OwenSobol2D sobol(n);
  std::vector<float> y(bands * bands);
  std::vector<double> sum(bands * bands), ref(bands * bands);
  double worst = 0;
  Pcg32 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3f nrm = uniformSphere(rng.uniform(), rng.uniform());
    Vec3f t, b;
    orthonormalBasis(nrm, t, b);
    const std::uint64_t key = deriveSeed(77, trial);
    std::fill(sum.begin(), sum.end(), 0.0);
    for (int s = 0; s < n; ++s) {
      const Point2 u = sobol.point(s, std::uint32_t(key), std::uint32_t(key >> 32));
      const Vec3f l = cosineHemisphere(u.x, u.y);
      sh::eval(bands, t * l.x + b * l.y + nrm * l.z, y.data());
      for (int i = 0; i < bands * bands; ++i) sum[i] += y[i];
    }
    sh::evalReference(bands, Vec3d(nrm), ref.data());
    for (int l = 0; l < bands; ++l)
      for (int i = l * l; i < (l + 1) * (l + 1); ++i)
        worst = std::max(worst, std::abs(sum[i] / n - A[l] / kPi * ref[i]));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(worst, 0.0);
}

TEST(Bake, SphereAbovePlaneOccludesOneMinusRatioSquared) {
  const double r = 0.5, h = 1.25;
  Scene scene("builtin:sphere-plane?r=0.5&h=1.25&grid=32&subdiv=5");
  // The plane vertex right below the sphere's centre.
  std::size_t below = 0;
  for (std::size_t v = 0; v < scene.mesh.vertexCount(); ++v)
    if (length(scene.mesh.positions[v]) < length(scene.mesh.positions[below])) below = v;
  ASSERT_LT(length(scene.mesh.positions[below]), 1e-6f);
  ASSERT_GT(scene.mesh.normals[below].y, 0.999f);
  const double expected = 1.0 - (r / h) * (r / h);
  for (Sampling sampling : {Sampling::CosineSobol, Sampling::UniformRandom}) {
    BakeSettings s = settings(TransferMode::Shadowed, 3, 4096);
    s.sampling = sampling;
    s.rows = {below, 1};
    BakeStats stats;
    const auto t = bake(scene.mesh, *scene.occluder, s, &stats);
    ASSERT_EQ(t.rowCount(), 1u);
    const double lit = t.row(0)[0] * kSqrt4Pi;
    EXPECT_GT(stats.stdErrConstMax, 1e-3);  // the estimate is not degenerate
    EXPECT_NEAR(lit, expected, 3 * stats.stdErrConstMax) << toString(sampling);
  }
}

// Mean and max over vertices of √(4π) T₀ (radiance under L = 1, albedo applied outside).
struct Summary {
  double mean = 0, max = 0;
};
Summary summarise(const Transfer& t) {
  Summary s;
  for (std::size_t v = 0; v < t.rowCount(); ++v) {
    const double x = t.row(v)[0] * kSqrt4Pi;
    s.mean += x;
    s.max = std::max(s.max, x);
  }
  s.mean /= double(t.rowCount());
  return s;
}

// The inside of a unit icosphere (faces and normals turned inward) with the cap y > yCut cut
// away. Inside a sphere the cosine-weighted solid angle of any patch, seen from any point of the
// sphere, is its area fraction (the form factor dA/(4πR²) does not depend on the viewer), so
// every point sees the hole with weight f = area fraction of the hole, and the rest of the cavity
// with weight 1 − f.
struct Cavity {
  Mesh mesh;
  double holeFraction = 0;
};
Cavity sphericalCavity(int subdiv, float yCut) {
  const Mesh sphere = builtinScene("builtin:sphere?subdiv=" + std::to_string(subdiv));
  Cavity c;
  std::vector<std::uint32_t> remap(sphere.vertexCount(), UINT32_MAX);
  double kept = 0, total = 0;
  for (const auto& t : sphere.triangles) {
    const Vec3f a = sphere.positions[t[0]], b = sphere.positions[t[1]], d = sphere.positions[t[2]];
    const double area = 0.5 * length(cross(b - a, d - a));
    total += area;
    if (a.y > yCut && b.y > yCut && d.y > yCut) continue;
    kept += area;
    std::array<std::uint32_t, 3> out{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = t[k == 0 ? 0 : 3 - k];  // reversed winding: front faces inward
      if (remap[v] == UINT32_MAX) {
        remap[v] = static_cast<std::uint32_t>(c.mesh.positions.size());
        c.mesh.positions.push_back(sphere.positions[v]);
        c.mesh.normals.push_back(-sphere.normals[v]);
      }
      out[k] = remap[v];
    }
    c.mesh.triangles.push_back(out);
  }
  c.mesh.source = "cavity";
  c.holeFraction = 1.0 - kept / total;
  return c;
}

TEST(Bake, InterreflectionWhiteFurnaceInSphericalCavity) {
  // Albedo 1, L = 1: the exact radiance is 1 everywhere. In the cavity, bounce k adds
  // f (1 − f)^k, so after K bounces the radiance is 1 − (1 − f)^(K+1) at every point: it rises
  // with every bounce, never exceeds 1, and the gap to 1 shrinks by the factor (1 − f).
  Cavity cavity = sphericalCavity(3, 0.55f);
  const double f = cavity.holeFraction;
  ASSERT_GT(f, 0.15);
  ASSERT_LT(f, 0.3);
  auto occluder = makeEmbreeOccluder(cavity.mesh);
  BakeSettings s = settings(TransferMode::Interreflected, 3, 256);
  s.material.diffuse = Rgb(1.0f);
  std::vector<Summary> sums;
  std::vector<Transfer> bakes;
  for (int k = 0; k <= 4; ++k) {
    s.bounces = k;
    BakeStats stats;
    bakes.push_back(bake(cavity.mesh, *occluder, s, &stats));
    EXPECT_EQ(bakes.back().channels(), 1);
    sums.push_back(summarise(bakes.back()));
    const double exact = 1.0 - std::pow(1.0 - f, k + 1);
    // Mean over vertices: Monte Carlo error averages out; what remains is the polyhedral
    // approximation of the sphere (measured ~1e-3 at 642 vertices).
    EXPECT_NEAR(sums[k].mean, exact, 0.004) << "bounces " << k;
    // No vertex above the exact value (< 1) beyond 4 stated standard errors.
    EXPECT_LT(sums[k].max, exact + 4 * stats.stdErrConstMax) << "bounces " << k;
    EXPECT_LT(sums[k].max, 1.0);
  }
  for (int k = 1; k <= 4; ++k) {
    EXPECT_GT(sums[k].mean, sums[k - 1].mean) << "bounce " << k;
    // Per vertex the series never decreases.
    for (std::size_t i = 0; i < bakes[k].values().size(); i += 9)
      ASSERT_GE(bakes[k].values()[i], testdata::valuesOf(bakes[k - 1])[i] - 1e-6f);
    const double ratio = (1 - sums[k].mean) / (1 - sums[k - 1].mean);
    EXPECT_NEAR(ratio, 1.0 - f, 0.005) << "bounce " << k;
  }
}

TEST(Bake, EachBounceAtMostAlbedoTimesThePrevious) {
  // Tᵏ(p) = (1/N) Σ ρ Tᵏ⁻¹(h_s) ≤ ρ max Tᵏ⁻¹: exact for the estimator (weights are 1).
  Scene scene("builtin:cornell?grid=10");
  const float rho = 0.6f;
  BakeSettings s = settings(TransferMode::Interreflected, 2, 128);
  s.material.diffuse = Rgb(rho);
  std::vector<Transfer> bakes;
  for (int k = 0; k <= 3; ++k) {
    s.bounces = k;
    bakes.push_back(bake(scene.mesh, *scene.occluder, s));
  }
  double prevMax = 0;
  for (std::size_t v = 0; v < bakes[0].rowCount(); ++v)
    prevMax = std::max(prevMax, double(bakes[0].row(v)[0]));
  for (int k = 1; k <= 3; ++k) {
    double maxBounce = 0;
    for (std::size_t v = 0; v < bakes[k].rowCount(); ++v)
      maxBounce = std::max(maxBounce, double(bakes[k].row(v)[0] - bakes[k - 1].row(v)[0]));
    EXPECT_GT(maxBounce, 0.0) << "bounce " << k;
    EXPECT_LE(maxBounce, rho * prevMax * (1 + 1e-4) + 1e-6) << "bounce " << k;
    prevMax = maxBounce;
  }
}

TEST(Bake, ColouredAlbedoGivesRgbTransferMatchingScalarBakes) {
  Scene scene("builtin:cornell?grid=8");
  BakeSettings s = settings(TransferMode::Interreflected, 3, 64);
  s.bounces = 2;
  const Rgb rho(0.9f, 0.5f, 0.2f);
  s.material.diffuse = rho;
  const auto rgb = bake(scene.mesh, *scene.occluder, s);
  ASSERT_EQ(rgb.channels(), 3);
  // Without an override, the Cornell box's own red and green walls make the transfer RGB.
  BakeSettings own = s;
  own.material.diffuse.reset();
  EXPECT_EQ(bake(scene.mesh, *scene.occluder, own).channels(), 3);
  for (int c = 0; c < 3; ++c) {
    s.material.diffuse = Rgb(rho[c]);
    const auto grey = bake(scene.mesh, *scene.occluder, s);
    ASSERT_EQ(grey.channels(), 1);
    double worst = 0;
    for (std::size_t v = 0; v < grey.rowCount(); ++v)
      for (int i = 0; i < 9; ++i)
        worst = std::max(worst, double(std::abs(rgb.row(v)[i * 3 + c] - grey.row(v)[i])));
    EXPECT_LT(worst, 1e-6) << "channel " << c;
  }
  // Shadowed bakes ignore albedo: always scalar.
  s.mode = TransferMode::Shadowed;
  s.material.diffuse = rho;
  EXPECT_EQ(bake(scene.mesh, *scene.occluder, s).channels(), 1);
}

TEST(Bake, FewerBandsEqualTheLeadingCoefficients) {
  Scene scene("builtin:sphere-plane?grid=8&subdiv=2");
  const auto t5 = bake(scene.mesh, *scene.occluder, settings(TransferMode::Shadowed, 5, 128));
  const auto t3 = bake(scene.mesh, *scene.occluder, settings(TransferMode::Shadowed, 3, 128));
  const auto cut = t5.cut(3);
  ASSERT_EQ(cut.values().size(), t3.values().size());
  for (std::size_t i = 0; i < t3.values().size(); ++i)
    ASSERT_NEAR(cut.values()[i], t3.values()[i], 1e-6f);
}

TEST(Bake, DeterministicOverThreadsAndRanges) {
  Scene scene("builtin:sphere-plane?grid=10&subdiv=2");
  for (TransferMode mode : {TransferMode::Shadowed, TransferMode::Interreflected}) {
    BakeSettings s = settings(mode, 3, 64);
    s.bounces = 2;
    s.material.diffuse = Rgb(0.7f, 0.6f, 0.5f);
    Transfer one, two;
    {
      ThreadLimit limit(1);
      one = bake(scene.mesh, *scene.occluder, s);
    }
    {
      ThreadLimit limit(2);
      two = bake(scene.mesh, *scene.occluder, s);
    }
    EXPECT_EQ(testdata::valuesOf(one), testdata::valuesOf(two)) << toString(mode);
    // A range bake equals the same rows of the full bake.
    const std::size_t a = 37, b = scene.mesh.vertexCount() - 11;
    s.rows = {a, b - a};
    const auto part = bake(scene.mesh, *scene.occluder, s);
    ASSERT_EQ(part.rowCount(), b - a);
    ASSERT_EQ(part.channels(), one.channels());
    const std::vector<float> all = testdata::valuesOf(one);
    const std::vector<float> rows(all.begin() + a * one.stride(), all.begin() + b * one.stride());
    EXPECT_EQ(testdata::valuesOf(part), rows) << toString(mode);
    // And a different seed gives a different bake.
    s.seed = 99;
    EXPECT_NE(testdata::valuesOf(bake(scene.mesh, *scene.occluder, s)), testdata::valuesOf(part));
  }
}

void expectError(const Mesh& mesh, const Occluder& occ, const BakeSettings& s,
                 const std::string& needle) {
  try {
    bake(mesh, occ, s);
    ADD_FAILURE() << "no error, expected one mentioning '" << needle << "'";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(needle), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(Bake, RejectsBadSettings) {
  Scene scene("builtin:sphere?subdiv=1");
  auto s = settings(TransferMode::Shadowed, 3, 16);
  auto bad = s;
  bad.samples = 0;
  expectError(scene.mesh, *scene.occluder, bad, "samples");
  bad.samples = (1 << 24) + 1;
  expectError(scene.mesh, *scene.occluder, bad, "samples");
  bad = s;
  bad.bands = 0;
  expectError(scene.mesh, *scene.occluder, bad, "bands");
  bad.bands = 33;
  expectError(scene.mesh, *scene.occluder, bad, "bands");
  bad = s;
  bad.bounces = -1;
  expectError(scene.mesh, *scene.occluder, bad, "bounces");
  bad.bounces = 17;
  expectError(scene.mesh, *scene.occluder, bad, "bounces");
  bad = s;
  bad.rows = {scene.mesh.vertexCount(), 0};
  expectError(scene.mesh, *scene.occluder, bad, "vertex range");
  bad.rows = {1, scene.mesh.vertexCount()};
  expectError(scene.mesh, *scene.occluder, bad, "vertex range");
  Mesh empty;
  empty.source = "empty.obj";
  expectError(empty, *scene.occluder, s, "empty.obj: cannot bake an empty mesh");
  EXPECT_THROW(parseSampling("stratified"), Error);
  EXPECT_EQ(parseSampling("uniform"), Sampling::UniformRandom);
}

TEST(Bake, CancelThrowsCancelled) {
  Scene scene("builtin:sphere?subdiv=3");
  int calls = 0;
  EXPECT_THROW(bake(scene.mesh, *scene.occluder, settings(TransferMode::Shadowed, 3, 64), nullptr,
                    [&](double) { return ++calls < 3; }),
               Cancelled);
  EXPECT_GE(calls, 3);
  // Progress reaches 1 on a complete bake.
  double last = 0;
  bake(scene.mesh, *scene.occluder, settings(TransferMode::Shadowed, 3, 16), nullptr,
       [&](double f) {
         last = std::max(last, f);
         return true;
       });
  EXPECT_DOUBLE_EQ(last, 1.0);
}

}  // namespace
}  // namespace prt
