// Relighting against analytic answers and an independent double-precision reference.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/random_data.hpp"
#include "prt/core/cpu.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/relight/relight.hpp"
#include "prt/sh/project.hpp"
#include "prt/sh/rotate.hpp"

namespace prt {
namespace {

Transfer randomTransfer(int bands, int channels, std::size_t vertices, std::uint32_t seed) {
  Transfer t =
      Transfer::zeros(testdata::shapeOf(TransferLayout::Vector, bands, channels, vertices));
  float* x = t.mutableValues();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t i = 0; i < t.values().size(); ++i) x[i] = u(rng);
  return t;
}

/// Vector relighting through the one entry point (a Lambert material: the albedo is kd).
std::vector<Rgb> relightVectors(const Transfer& t, const sh::RgbSh& light,
                                std::span<const Rgb> albedo,
                                const Mat3d& rotation = Mat3d::identity(),
                                relight::RelightInfo* info = nullptr) {
  return relight::relight(t, light, Material{}, {{}, {}, albedo}, Vec3f(0.0f), rotation, info);
}

sh::RgbSh randomLight(int bands, std::uint32_t seed) {
  sh::RgbSh l(bands);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (Rgb& c : l.c) c = Rgb(u(rng), u(rng), u(rng));
  return l;
}

std::vector<Rgb> randomAlbedo(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.05f, 1.0f);
  std::vector<Rgb> a(n);
  for (Rgb& x : a) x = Rgb(u(rng), u(rng), u(rng));
  return a;
}

// Straightforward double-precision evaluation of R_c = a_c Σ_i T_i(,c) L_i,c over `bands` bands.
Rgbd reference(const Transfer& t, const sh::RgbSh& l, int bands, std::size_t v, Rgb albedo) {
  Rgbd r(0.0);
  for (int i = 0; i < bands * bands; ++i)
    for (int c = 0; c < 3; ++c) {
      const double ti = t.channels() == 1 ? t.row(v)[i] : t.row(v)[3 * i + c];
      r[c] += ti * double(l.c[i][c]);
    }
  return r * Rgbd(albedo);
}

// Float accumulation of B² terms of magnitude ≤ 1: error grows like B²·ε.
double tolerance(int bands) {
  return 2e-6 * bands * bands;
}

TEST(Relight, ConstantEnvironmentGivesAlbedoTimesT0) {
  // A constant environment of radiance c has L00 = c ∫ Y00 dω = c √(4π), all else zero, so
  // R = albedo ⊙ T0 √(4π) c whatever the upper transfer coefficients hold.
  const Rgb c(0.7f, 1.3f, 2.1f);
  for (int channels : {1, 3}) {
    for (int bands : {1, 2, 3, 5, 9, 12}) {
      const Transfer t = randomTransfer(bands, channels, 1000, 7 + bands);
      const auto albedo = randomAlbedo(t.rowCount(), 11);
      sh::RgbSh light(bands);
      light.c[0] = c * float(std::sqrt(4.0 * kPi));
      const auto out = relightVectors(t, light, albedo);
      ASSERT_EQ(out.size(), t.rowCount());
      for (std::size_t v = 0; v < t.rowCount(); ++v)
        for (int ch = 0; ch < 3; ++ch) {
          const double t0 = channels == 1 ? t.row(v)[0] : t.row(v)[ch];
          const double expected = albedo[v][ch] * t0 * std::sqrt(4.0 * kPi) * c[ch];
          ASSERT_NEAR(out[v][ch], expected, 1e-6 * (1 + std::abs(expected)))
              << "channels " << channels << " bands " << bands << " vertex " << v;
        }
    }
  }
}

TEST(Relight, WhiteFurnaceOnUnshadowedTransfer) {
  // Unshadowed transfer of normal n, T_i = (1/π) ∫ Y_i max(n·ω, 0) dω = (Λ_l/π) Y_lm(n) by
  // Funk–Hecke, with Λ_0 = π, Λ_1 = 2π/3, Λ_2 = π/4 (Ramamoorthi & Hanrahan 2001). A white
  // environment (L00 = √(4π)) relights it to exactly the albedo; a linear gradient
  // L(ω) = g·ω relights to albedo · (2/3) g·n, the clamped-cosine average of a linear function.
  const int bands = 3;
  const double lambda[3] = {kPi, 2 * kPi / 3, kPi / 4};
  const std::vector<Vec3d> normals = {{0, 1, 0}, {1, 0, 0}, normalize(Vec3d(1, -2, 3))};
  std::vector<float> values;
  for (const Vec3d& n : normals) {
    double y[9];
    sh::evalReference(bands, n, y);
    for (int l = 0; l < bands; ++l)
      for (int m = -l; m <= l; ++m) values.push_back(float(lambda[l] / kPi * y[sh::index(l, m)]));
  }
  const Transfer t = testdata::denseTransfer(TransferLayout::Vector, bands, 1, values);
  sh::RgbSh white(bands);
  white.c[0] = Rgb(float(std::sqrt(4.0 * kPi)));
  const std::vector<Rgb> albedo = {Rgb(0.8f, 0.5f, 0.2f)};  // uniform
  const auto out = relightVectors(t, white, albedo);
  for (const Rgb& r : out)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r[c], albedo[0][c], 1e-6);
  // Gradient g·ω = Σ_i L_i Y_i with L_{1,-1} = -g_y c, L_{1,0} = g_z c, L_{1,1} = -g_x c,
  // c = √(4π/3) (since Y1,-1 = -√(3/4π) y etc.).
  const Vec3d g(0.3, -0.7, 0.5);
  const double c1 = std::sqrt(4 * kPi / 3);
  sh::RgbSh grad(bands);
  grad.c[sh::index(1, -1)] = Rgb(float(-g.y * c1));
  grad.c[sh::index(1, 0)] = Rgb(float(g.z * c1));
  grad.c[sh::index(1, 1)] = Rgb(float(-g.x * c1));
  const auto lit = relightVectors(t, grad, albedo);
  for (std::size_t v = 0; v < normals.size(); ++v)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(lit[v][c], albedo[0][c] * 2.0 / 3.0 * dot(g, normals[v]), 1e-6);
}

TEST(Relight, MatchesDoubleReferenceAtEveryBandCount) {
  // Covers the compile-time specialised kernels (bands 1..10) and the generic one (11, 12),
  // the SIMD ones where the CPU has them and the portable ones, forced, on every machine.
  for (Simd simd : {Simd::Auto, Simd::Portable})
    for (int channels : {1, 3}) {
      const ScopedSimd policy(simd);
      for (int bands = 1; bands <= 12; ++bands) {
        const Transfer t = randomTransfer(bands, channels, 517, 100 + bands);
        const sh::RgbSh light = randomLight(bands, 200 + bands);
        const auto albedo = randomAlbedo(t.rowCount(), 300 + bands);
        const auto out = relightVectors(t, light, albedo);
        for (std::size_t v = 0; v < t.rowCount(); ++v) {
          const Rgbd ref = reference(t, light, bands, v, albedo[v]);
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(out[v][c], ref[c], tolerance(bands))
                << "channels " << channels << " bands " << bands << " vertex " << v;
        }
      }
    }
}

TEST(Relight, UniformAndMissingAlbedo) {
  const Transfer t = randomTransfer(3, 3, 64, 1);
  const sh::RgbSh light = randomLight(3, 2);
  const Rgb a(0.25f, 0.5f, 0.75f);
  const std::vector<Rgb> uniform = {a};
  const auto withUniform = relightVectors(t, light, uniform);
  const auto white = relightVectors(t, light, {});
  for (std::size_t v = 0; v < t.rowCount(); ++v) {
    const Rgbd ref = reference(t, light, 3, v, Rgb(1.0f));
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(white[v][c], ref[c], tolerance(3));
      EXPECT_NEAR(withUniform[v][c], ref[c] * a[c], tolerance(3));
    }
  }
}

TEST(Relight, LightWithMoreBandsIsCutExactly) {
  const Transfer t = randomTransfer(3, 1, 200, 5);
  const sh::RgbSh light = randomLight(9, 6);
  relight::RelightInfo info;
  const auto out = relightVectors(t, light, {}, Mat3d::identity(), &info);
  EXPECT_EQ(info.bands, 3);
  EXPECT_TRUE(info.lightTruncated);
  EXPECT_FALSE(info.transferTruncated);
  EXPECT_TRUE(info.warning().empty());
  const auto cut = relightVectors(t, light.truncated(3), {});
  for (std::size_t v = 0; v < t.rowCount(); ++v)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out[v][c], cut[v][c]);
}

TEST(Relight, LightWithFewerBandsUsesItsBandsAndSaysSo) {
  for (int channels : {1, 3}) {
    const Transfer t = randomTransfer(5, channels, 200, 8);
    const sh::RgbSh light = randomLight(3, 9);
    relight::RelightInfo info;
    const auto out = relightVectors(t, light, {}, Mat3d::identity(), &info);
    EXPECT_EQ(info.bands, 3);
    EXPECT_TRUE(info.transferTruncated);
    EXPECT_FALSE(info.lightTruncated);
    EXPECT_NE(info.warning().find("3 bands"), std::string::npos) << info.warning();
    for (std::size_t v = 0; v < t.rowCount(); ++v) {
      const Rgbd ref = reference(t, light, 3, v, Rgb(1.0f));
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(out[v][c], ref[c], tolerance(3));
    }
  }
}

// A smooth coloured lobe around d (one von Mises–Fisher-like lobe per channel, different
// sharpness), so that projection by quadrature converges to float precision at any rotation.
Rgbd lobe(const Vec3d& d, const Vec3d& w) {
  const double x = dot(d, w);
  return {std::exp(2.0 * (x - 1)), std::exp(4.0 * (x - 1)), 0.3 + std::exp(6.0 * (x - 1))};
}

TEST(Relight, RotatedLightEqualsReprojectedRotatedFunction) {
  // Rotating the coefficients by R must equal projecting the rotated function
  // g(ω) = f(R⁻¹ω) — i.e. the lobe about R d.
  const int bands = 6;
  const Vec3d d = normalize(Vec3d(0.3, 0.8, -0.5));
  const sh::RgbSh light = sh::projectFunctionRgb(
      bands, [&](const Vec3d& w) { return lobe(d, w); }, 64);
  for (int channels : {1, 3}) {
    const Transfer t = randomTransfer(bands, channels, 300, 21);
    const auto albedo = randomAlbedo(t.rowCount(), 22);
    for (const Mat3d& R : {rotationEulerXYZ(30, 0, 0), rotationEulerXYZ(0, 125, 0),
                           rotationEulerXYZ(-40, 70, 200)}) {
      const Vec3d rd = R * d;
      const sh::RgbSh reprojected = sh::projectFunctionRgb(
          bands, [&](const Vec3d& w) { return lobe(rd, w); }, 64);
      const auto rotated = relightVectors(t, light, albedo, R);
      const auto direct = relightVectors(t, reprojected, albedo);
      double maxDiff = 0, maxVal = 0;
      for (std::size_t v = 0; v < t.rowCount(); ++v)
        for (int c = 0; c < 3; ++c) {
          maxDiff = std::max(maxDiff, double(std::abs(rotated[v][c] - direct[v][c])));
          maxVal = std::max(maxVal, double(std::abs(direct[v][c])));
        }
      EXPECT_LT(maxDiff, 2e-5 * (1 + maxVal)) << "channels " << channels;
      // And the rotation did something: the unrotated relighting differs.
      const auto unrotated = relightVectors(t, light, albedo);
      double moved = 0;
      for (std::size_t v = 0; v < t.rowCount(); ++v)
        moved = std::max(moved, double(std::abs(unrotated[v].y - direct[v].y)));
      EXPECT_GT(moved, 100 * maxDiff);
    }
  }
}

TEST(Relight, PreparedLightWithReusedRotation) {
  // A rotation built once for more bands than needed (viewer use) gives the same result.
  const Transfer t = randomTransfer(3, 1, 100, 31);
  const sh::RgbSh light = randomLight(3, 32);
  const Mat3d R = rotationEulerXYZ(10, 20, 30);
  const sh::Rotation rot(5, R);
  const relight::PreparedLight p = relight::prepareLight(light, t.bands(), &rot);
  std::vector<Rgb> out(t.rowCount());
  relight::relightPrepared(t, p, PreparedMaterial{}, {}, Vec3f(0.0f), out);
  const auto ref = relightVectors(t, light, {}, R);
  for (std::size_t v = 0; v < t.rowCount(); ++v)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[v][c], ref[v][c], 1e-5);
}

TEST(Relight, IndependentOfThreadCount) {
  const Transfer t = randomTransfer(4, 3, 50000, 41);
  const sh::RgbSh light = randomLight(4, 42);
  std::vector<Rgb> one, all;
  {
    ThreadLimit limit(1);
    one = relightVectors(t, light, {});
  }
  all = relightVectors(t, light, {});
  ASSERT_EQ(one.size(), all.size());
  for (std::size_t v = 0; v < one.size(); ++v) ASSERT_EQ(one[v], all[v]);
}

TEST(Relight, RejectsMismatchedSizes) {
  const Transfer t = randomTransfer(3, 1, 10, 51);
  const sh::RgbSh light = randomLight(3, 52);
  std::vector<Rgb> out(9);
  EXPECT_THROW(relight::relight(t, light, Material{}, {}, Vec3f(0.0f), out), Error);
  const std::vector<Rgb> albedo(7, Rgb(1.0f));
  EXPECT_THROW(relightVectors(t, light, albedo), Error);
  EXPECT_THROW(Transfer::dense(t.shape(), FloatArray(std::vector<float>(5))), Error);
  TransferShape two = t.shape();
  two.channels = 2;
  EXPECT_THROW(relightVectors(Transfer::zeros(two), light, {}), Error);
}

}  // namespace
}  // namespace prt
