// SH rotation: g(ω) = f(R⁻¹ω), checked against projection of the rotated function.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/sh/project.hpp"
#include "prt/sh/rotate.hpp"

using namespace prt;
using namespace prt::sh;

namespace {

// Uniformly random rotation from a random unit quaternion.
Mat3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  double w = g(rng), x = g(rng), y = g(rng), z = g(rng);
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  Mat3d r;
  r.m = {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
  return r;
}

std::vector<double> randomCoeffs(int bands, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> c(bands * bands);
  for (double& v : c) v = u(rng);
  return c;
}

double evalSum(int bands, const std::vector<double>& c, const Vec3d& d) {
  std::vector<double> y(bands * bands);
  evalReference(bands, d, y.data());
  double s = 0;
  for (int i = 0; i < bands * bands; ++i) s += c[i] * y[i];
  return s;
}

}  // namespace

// Project-then-rotate equals rotate-then-project, for random rotations at every B = 1..16.
TEST(ShRotate, CommutesWithProjection) {
  std::mt19937 rng(5);
  for (int bands = 1; bands <= 16; ++bands) {
    const Mat3d r = randomRotation(rng);
    const Mat3d rinv = r.transposed();
    const auto f = randomCoeffs(bands, rng);
    const ShCoeffs g = projectFunction(
        bands, [&](const Vec3d& d) { return evalSum(bands, f, rinv * d); }, bands);
    const Rotation rot(bands, r);
    std::vector<double> out(bands * bands);
    rot.apply(f.data(), out.data());
    double worst = 0;
    for (int i = 0; i < bands * bands; ++i) worst = std::fmax(worst, std::fabs(out[i] - g.c[i]));
    EXPECT_LT(worst, 2e-5) << "bands=" << bands;
  }
}

// A lobe pointing along d moves to R d.
TEST(ShRotate, LobeMovesToRotatedDirection) {
  const int bands = 8;
  const Vec3d d = normalize(Vec3d(0.3, 0.8, -0.2));
  const Mat3d r = rotationAxisAngle(normalize(Vec3d(1, -2, 0.5)), 1.1);
  auto lobe = [](const Vec3d& axis) {
    return [axis](const Vec3d& w) { return std::exp(4 * dot(w, axis)); };
  };
  const ShCoeffs f = projectFunction(bands, lobe(d), 40);
  const ShCoeffs expect = projectFunction(bands, lobe(r * d), 40);
  ShCoeffs g(bands);
  Rotation(bands, r).apply(f.c.data(), g.c.data());
  for (int i = 0; i < bands * bands; ++i) EXPECT_NEAR(g.c[i], expect.c[i], 2e-5) << i;
  // And the rotated reconstruction peaks at R d, not at Rᵀ d.
  EXPECT_GT(reconstruct(g, Vec3f(r * d)), reconstruct(g, Vec3f(r.transposed() * d)) + 1);
}

TEST(ShRotate, BlocksOrthogonalAndEnergyPreserved) {
  std::mt19937 rng(6);
  for (int bands : {2, 5, 16, kMaxBands}) {
    const Rotation rot(bands, randomRotation(rng));
    double worst = 0;
    for (int l = 0; l < bands; ++l)
      for (int a = -l; a <= l; ++a)
        for (int b = -l; b <= l; ++b) {
          double s = 0;
          for (int k = -l; k <= l; ++k) s += rot.at(l, a, k) * rot.at(l, b, k);
          worst = std::fmax(worst, std::fabs(s - (a == b)));
        }
    EXPECT_LT(worst, 1e-9) << "bands=" << bands;
    const auto f = randomCoeffs(bands, rng);
    std::vector<double> g(bands * bands);
    rot.apply(f.data(), g.data());
    for (int l = 0; l < bands; ++l) {
      double ef = 0, eg = 0;
      for (int m = -l; m <= l; ++m)
        ef += f[index(l, m)] * f[index(l, m)], eg += g[index(l, m)] * g[index(l, m)];
      EXPECT_NEAR(eg, ef, 1e-9 * (1 + ef)) << "bands=" << bands << " l=" << l;
    }
  }
}

TEST(ShRotate, Composition) {
  std::mt19937 rng(7);
  const int bands = 9;
  const Mat3d r1 = randomRotation(rng), r2 = randomRotation(rng);
  const auto f = randomCoeffs(bands, rng);
  std::vector<double> a(bands * bands), b(bands * bands), c(bands * bands);
  Rotation rot(bands, r2);
  rot.apply(f.data(), a.data());
  rot.set(r1);  // rebuild in place
  rot.apply(a.data(), b.data());
  Rotation(bands, r1 * r2).apply(f.data(), c.data());
  for (int i = 0; i < bands * bands; ++i) EXPECT_NEAR(b[i], c[i], 1e-10) << i;
  // Identity leaves f alone; R then Rᵀ returns f.
  Rotation(bands).apply(f.data(), a.data());
  for (int i = 0; i < bands * bands; ++i) EXPECT_NEAR(a[i], f[i], 1e-14);
}

TEST(ShRotate, RotateZMatchesGeneralRotation) {
  std::mt19937 rng(8);
  for (int bands : {1, 3, 9, 16}) {
    const double angle = 0.37 * bands + 0.1;
    const auto fd = randomCoeffs(bands, rng);
    std::vector<float> f(fd.begin(), fd.end()), a(bands * bands), b(bands * bands);
    rotateZ(bands, angle, f.data(), a.data());
    Rotation(bands, rotationAxisAngle(Vec3d(0, 0, 1), angle)).apply(f.data(), b.data());
    for (int i = 0; i < bands * bands; ++i) EXPECT_NEAR(a[i], b[i], 1e-5) << "bands=" << bands;
    std::vector<Rgb> fr(bands * bands), ar(bands * bands);
    for (int i = 0; i < bands * bands; ++i) fr[i] = Rgb(f[i], 2 * f[i], -f[i]);
    rotateZ(bands, angle, fr.data(), ar.data());
    for (int i = 0; i < bands * bands; ++i) EXPECT_NEAR(ar[i].y, 2 * a[i], 1e-5);
  }
}

TEST(ShRotate, RgbApplyAndErrors) {
  std::mt19937 rng(9);
  const int bands = 4;
  const Rotation rot(bands, randomRotation(rng));
  RgbSh f(bands);
  std::vector<float> s(bands * bands), g(bands * bands);
  for (int i = 0; i < bands * bands; ++i) {
    s[i] = float(i % 5) - 2;
    f.c[i] = Rgb(s[i], 0, 3 * s[i]);
  }
  const RgbSh out = rot.apply(f);
  rot.apply(s.data(), g.data());
  for (int i = 0; i < bands * bands; ++i) {
    EXPECT_NEAR(out.c[i].x, g[i], 1e-6);
    EXPECT_NEAR(out.c[i].z, 3 * g[i], 1e-5);
  }
  EXPECT_THROW(rot.apply(RgbSh(3)), Error);
  EXPECT_THROW(Rotation(0), Error);
}
