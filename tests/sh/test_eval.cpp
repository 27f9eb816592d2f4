// Conventions and accuracy of SH evaluation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/sh/project.hpp"
#include "prt/sh/sh.hpp"

using namespace prt;
using namespace prt::sh;

namespace {

std::vector<Vec3d> testDirections(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<Vec3d> dirs;
  for (int i = 0; i < count; ++i) dirs.push_back(normalize(Vec3d(g(rng), g(rng), g(rng))));
  // Poles and near-poles, where sin θ → 0 and φ is ill-defined.
  for (double z : {1.0, -1.0, 1 - 1e-7, -(1 - 1e-7), 1 - 1e-4, -(1 - 1e-4)}) {
    const double s = std::sqrt(std::fmax(0.0, 1 - z * z));
    for (double phi : {0.0, 0.7, 2.5, -1.9})
      dirs.push_back({s * std::cos(phi), s * std::sin(phi), z});
  }
  // Equator and axes.
  dirs.push_back({1, 0, 0});
  dirs.push_back({0, 1, 0});
  dirs.push_back({-1, 0, 0});
  dirs.push_back({0, -1, 0});
  return dirs;
}

}  // namespace

TEST(ShEval, ClosedFormFirstThreeBands) {
  for (const Vec3d& d : testDirections(50, 1)) {
    double y[9];
    eval(3, d, y);
    const double x = d.x, yy = d.y, z = d.z;
    const double expect[9] = {0.282095,
                              -0.488603 * yy,
                              0.488603 * z,
                              -0.488603 * x,
                              1.092548 * x * yy,
                              -1.092548 * yy * z,
                              0.315392 * (3 * z * z - 1),
                              -1.092548 * x * z,
                              0.546274 * (x * x - yy * yy)};
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(y[i], expect[i], 2e-6) << "i=" << i;
    double r[9];
    evalReference(3, d, r);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(r[i], expect[i], 2e-6) << "reference i=" << i;
  }
}

TEST(ShEval, DoubleMatchesReferenceAllBands) {
  const auto dirs = testDirections(200, 2);
  std::vector<double> a(kMaxBands * kMaxBands), r(kMaxBands * kMaxBands);
  for (int bands = 1; bands <= kMaxBands; ++bands) {
    double worst = 0;
    for (const Vec3d& d : dirs) {
      eval(bands, d, a.data());
      evalReference(bands, d, r.data());
      for (int i = 0; i < bands * bands; ++i) worst = std::fmax(worst, std::fabs(a[i] - r[i]));
    }
    EXPECT_LT(worst, 1e-12 * bands) << "bands=" << bands;
  }
}

// Float path: per band l, |float − reference| ≤ 1e-6 · max_m |Y_lm(dir)| (the reference is
// evaluated at the float direction's exact double value, renormalised).
TEST(ShEval, FloatMatchesReferenceAllBandsIncludingPoles) {
  const auto dirs = testDirections(500, 3);
  std::vector<float> f(kMaxBands * kMaxBands);
  std::vector<double> r(kMaxBands * kMaxBands);
  for (int bands = 1; bands <= kMaxBands; ++bands) {
    double worst = 0;
    for (const Vec3d& d : dirs) {
      const Vec3f df(d);
      eval(bands, df, f.data());
      evalReference(bands, Vec3d(df), r.data());
      for (int l = 0; l < bands; ++l) {
        double bandMax = 0, err = 0;
        for (int m = -l; m <= l; ++m) {
          bandMax = std::fmax(bandMax, std::fabs(r[index(l, m)]));
          err = std::fmax(err, std::fabs(f[index(l, m)] - r[index(l, m)]));
        }
        worst = std::fmax(worst, err / bandMax);
      }
    }
    EXPECT_LT(worst, 1e-6) << "bands=" << bands;
  }
}

TEST(ShEval, BatchEqualsSingle) {
  const auto dd = testDirections(37, 4);
  std::vector<Vec3f> dirs;
  for (auto& d : dd) dirs.emplace_back(d);
  for (int bands : {1, 4, 9, 16, 17, 32}) {
    const int n = bands * bands;
    std::vector<float> batch(dirs.size() * n), one(n);
    evalBatch(bands, dirs, batch.data());
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      eval(bands, dirs[k], one.data());
      for (int i = 0; i < n; ++i) ASSERT_EQ(batch[k * n + i], one[i]);
    }
  }
}

TEST(ShEval, RejectsBadBandCounts) {
  float y[4];
  EXPECT_THROW(eval(0, Vec3f(0, 0, 1), y), Error);
  EXPECT_THROW(eval(kMaxBands + 1, Vec3f(0, 0, 1), y), Error);
  EXPECT_THROW(checkBands(-3), Error);
  EXPECT_NO_THROW(checkBands(kMaxBands));
}

// ⟨Y_i, Y_j⟩ under a quadrature exact for their product: δ_ij to 1e-10 up to 16 bands.
TEST(ShEval, OrthonormalUnderQuadrature) {
  const int bands = 16;
  const int n = bands * bands;
  const SphereQuadrature q = gaussLegendreSphere(bands + 1);
  double wsum = 0;
  for (double w : q.weights) wsum += w;
  EXPECT_NEAR(wsum, 4 * kPi, 1e-12);
  std::vector<double> gram(n * n, 0.0), y(n);
  for (std::size_t k = 0; k < q.dirs.size(); ++k) {
    eval(bands, q.dirs[k], y.data());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) gram[i * n + j] += q.weights[k] * y[i] * y[j];
  }
  double worst = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) worst = std::fmax(worst, std::fabs(gram[i * n + j] - (i == j)));
  EXPECT_LT(worst, 1e-10);
}

TEST(ShEval, ReconstructSumsBasis) {
  RgbSh f(3);
  f.c[index(1, 0)] = Rgb(1, 2, 3);
  f.c[0] = Rgb(0.5f);
  const Rgb v = reconstruct(f, Vec3f(0, 0, 1));
  EXPECT_NEAR(v.x, 0.5 * 0.282095 + 0.488603, 1e-5);
  EXPECT_NEAR(v.z, 0.5 * 0.282095 + 3 * 0.488603, 1e-5);
  const RgbSh t = f.truncated(1);
  EXPECT_EQ(t.c.size(), 1u);
  EXPECT_EQ(t.c[0], Rgb(0.5f));
  EXPECT_THROW(f.truncated(4), Error);
}
