// SH rotation: g(ω) = f(R⁻¹ω), checked against projection of the rotated function.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/sh/project.hpp"
#include "prt/sh/rotate.hpp"

using namespace prt;
using namespace prt::sh;

// Counts every allocation in this test program, so a test can check that a code path makes none.
namespace {
std::atomic<long> gAllocations{0};
}
void* operator new(std::size_t n) {
  ++gAllocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

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

// ---- The zxzxz fast path against the dense Ivanic–Ruedenberg reference ----

namespace {

// Rotations that exercise every branch of set(): generic; identity; pure z (β = 0, δ undefined);
// β = π (σ undefined); β within 1e-9 of 0 and of π (ill-conditioned δ or σ); and half-turns
// about x, y, z (each Shepperd branch: 1 + tr, R00, R11, R22 largest).
std::vector<Mat3d> testRotations(std::mt19937& rng) {
  const Vec3d ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
  std::vector<Mat3d> rs = {
      Mat3d::identity(),
      rotationAxisAngle(ez, 0.7),
      rotationAxisAngle(ex, kPi),
      rotationAxisAngle(ey, kPi),
      rotationAxisAngle(ez, kPi),
      rotationAxisAngle(ez, 0.3) * rotationAxisAngle(ey, 1e-9) * rotationAxisAngle(ez, -1.1),
      rotationAxisAngle(ez, 0.3) * rotationAxisAngle(ey, kPi - 1e-9) * rotationAxisAngle(ez, 2.0),
      rotationAxisAngle(ex, kPi / 2)};
  for (int k = 0; k < 4; ++k) rs.push_back(randomRotation(rng));
  return rs;
}

}  // namespace

// Each band count 1..32 (the compile-time specialised kernels for bands 2..15, the runtime-size
// kernel beyond), double, float and RGB apply, against the dense reference blocks times the
// vector (computed in long double).
TEST(ShRotate, FastPathMatchesDenseReference) {
  std::mt19937 rng(10);
  const auto rs = testRotations(rng);
  for (int bands = 1; bands <= kMaxBands; ++bands) {
    std::vector<double> blocks(detail::rotationBlockOffset(bands));
    Rotation rot(bands);
    for (std::size_t ri = 0; ri < rs.size(); ++ri) {
      const Mat3d& r = rs[ri];
      detail::rotationBlocksReference(bands, r, blocks.data());
      rot.set(r);  // re-targeting the same object, as in an animation loop
      const auto f = randomCoeffs(bands, rng);
      std::vector<double> expect(bands * bands);
      for (int l = 0; l < bands; ++l) {
        const double* b = blocks.data() + detail::rotationBlockOffset(l);
        const int w = 2 * l + 1, o = l * l;
        for (int i = 0; i < w; ++i) {
          long double s = 0;
          for (int j = 0; j < w; ++j) s += (long double)b[i * w + j] * f[o + j];
          expect[o + i] = double(s);
        }
      }
      std::vector<double> gd(bands * bands);
      rot.apply(f.data(), gd.data());
      std::vector<float> ff(f.begin(), f.end()), gf(bands * bands);
      rot.apply(ff.data(), gf.data());
      std::vector<Rgb> fr(bands * bands), gr(bands * bands);
      for (int i = 0; i < bands * bands; ++i) fr[i] = Rgb(ff[i], -2 * ff[i], 0.5f * ff[i]);
      rot.apply(fr.data(), gr.data());
      double ed = 0, ef = 0, er = 0;
      for (int i = 0; i < bands * bands; ++i) {
        ed = std::fmax(ed, std::fabs(gd[i] - expect[i]));
        ef = std::fmax(ef, std::fabs(gf[i] - expect[i]));
        er = std::fmax(er, std::fabs(gr[i].x - expect[i]));
        er = std::fmax(er, std::fabs(gr[i].y + 2 * expect[i]) / 2);
        er = std::fmax(er, std::fabs(gr[i].z - 0.5 * expect[i]) * 2);
      }
      // |f_i| ≤ 1: round-off grows ~ with l (five factors, 2l+1-term sums).
      EXPECT_LT(ed, 1e-13 * bands) << "bands=" << bands << " rotation " << ri;
      EXPECT_LT(ef, 1e-6 * bands) << "bands=" << bands << " rotation " << ri;
      EXPECT_LT(er, 1e-6 * bands) << "bands=" << bands << " rotation " << ri;
    }
  }
}

// at() (O(l) per element from the factors) equals the dense reference element by element.
TEST(ShRotate, ElementsMatchDenseReference) {
  std::mt19937 rng(11);
  const auto rs = testRotations(rng);
  for (int bands : {3, 7, 20}) {
    std::vector<double> blocks(detail::rotationBlockOffset(bands));
    for (std::size_t ri = 0; ri < rs.size(); ++ri) {
      detail::rotationBlocksReference(bands, rs[ri], blocks.data());
      const Rotation rot(bands, rs[ri]);
      double worst = 0;
      for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m)
          for (int n = -l; n <= l; ++n) {
            const double ref =
                blocks[detail::rotationBlockOffset(l) + (m + l) * (2 * l + 1) + (n + l)];
            worst = std::fmax(worst, std::fabs(rot.at(l, m, n) - ref));
          }
      EXPECT_LT(worst, 1e-13) << "bands=" << bands << " rotation " << ri;
    }
  }
  EXPECT_THROW(Rotation(3).at(3, 0, 0), Error);
  EXPECT_THROW(Rotation(3).at(2, -3, 0), Error);
}

// The hot paths never allocate: construction, set() and every apply() overload except the
// RgbSh-returning convenience one.
TEST(ShRotate, SetAndApplyDoNotAllocate) {
  std::mt19937 rng(12);
  for (int bands : {6, 9, 24}) {
    const Mat3d r1 = randomRotation(rng), r2 = randomRotation(rng);
    std::vector<float> f(bands * bands, 0.25f), g(bands * bands);
    std::vector<double> fd(bands * bands, 0.25), gd(bands * bands);
    std::vector<Rgb> fr(bands * bands, Rgb(0.25f)), gr(bands * bands);
    Rotation(bands, r1).apply(f.data(), g.data());  // first use tabulates J (allocates once)
    const long before = gAllocations.load();
    Rotation rot(bands, r1);
    rot.set(r2);
    rot.apply(f.data(), g.data());
    rot.apply(fd.data(), gd.data());
    rot.apply(fr.data(), gr.data());
    EXPECT_EQ(gAllocations.load(), before) << "bands=" << bands;
    EXPECT_NE(g[4], 0.25f);  // and it did rotate something
  }
}
