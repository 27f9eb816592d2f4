// Lighting in the Haar basis (haar/project_light.hpp): texel means keep the environment's power,
// the terms are the largest by the rule stated, rotation resamples, and the whole cube is exact.

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "prt/core/error.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/envmap/project.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/haar/project_light.hpp"

namespace prt::haar {
namespace {

envmap::Environment constant(float v) {
  return envmap::Environment::analytic([v](const Vec3f&) { return Rgb(v); }, {});
}

/// A small bright disc over a dim sky: the power of the disc is known exactly.
envmap::Environment sun(const Vec3f& dir, double halfAngle, float radiance) {
  envmap::Cap cap;
  cap.direction = normalize(dir);
  cap.halfAngle = halfAngle;
  cap.radiance = Rgb(radiance);
  return envmap::Environment::analytic([](const Vec3f&) { return Rgb(0.0f); }, {cap});
}

double power(const std::vector<Rgb>& means, int n, int channel) {
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(n);
  double p = 0;
  for (std::size_t k = 0; k < means.size(); ++k)
    p += double(means[k][std::size_t(channel)]) * omega[k % omega.size()];
  return p;
}

TEST(HaarLight, ConstantEnvironmentHasConstantMeans) {
  const std::vector<Rgb> m = cubeMeans(constant(2.5f), 8);
  ASSERT_EQ(m.size(), coefficientCount(8));
  for (const Rgb& c : m) ASSERT_NEAR(c.x, 2.5f, 1e-5f);
}

TEST(HaarLight, DiscKeepsItsPowerAndLandsWhereItPoints) {
  // (Off every texel boundary of both cubes: the disc lies inside one texel.)
  const Vec3f dir = normalize(Vec3f(0.31f, 0.8f, -0.37f));
  const envmap::Environment env = sun(dir, 0.01, 1000.0f);
  const double expected = 1000.0 * 2 * kPi * (1 - std::cos(0.01));
  for (int n : {8, 32}) {
    const std::vector<Rgb> m = cubeMeans(env, n);
    EXPECT_NEAR(power(m, n, 0), expected, 1e-4 * expected) << n;
    std::size_t brightest = 0;
    for (std::size_t k = 0; k < m.size(); ++k)
      if (m[k].x > m[brightest].x) brightest = k;
    EXPECT_EQ(brightest, texelOf(dir, n)) << n;
    // Rotated by R, the disc lands in the texel of R d (the environment is resampled).
    const Mat3d r = rotationEulerXYZ(20, 75, -30);
    const std::vector<Rgb> mr = cubeMeans(env, n, r);
    std::size_t b2 = 0;
    for (std::size_t k = 0; k < mr.size(); ++k)
      if (mr[k].x > mr[b2].x) b2 = k;
    EXPECT_EQ(b2, texelOf(Vec3f(r * Vec3d(dir)), n)) << n;
    EXPECT_NEAR(power(mr, n, 0), expected, 1e-4 * expected);
  }
}

TEST(HaarLight, AllTermsReproduceTheCube) {
  const int n = 8;
  const envmap::Environment env = sun(Vec3f(0, 1, 0.2f), 0.2, 5.0f);
  const std::vector<Rgb> m = cubeMeans(env, n);
  const HaarLight all = approximate(m, n, coefficientCount(n));
  EXPECT_EQ(all.terms(), coefficientCount(n));  // zeros are kept too when all are asked for
  EXPECT_NEAR(all.energyKept, 1.0, 1e-12);
  std::vector<float> r(coefficientCount(n));
  const std::vector<Rgb> dense = all.dense();
  for (std::size_t k = 0; k < r.size(); ++k) r[k] = dense[k].x;
  inverse(r.data(), n);
  for (std::size_t k = 0; k < r.size(); ++k) ASSERT_NEAR(r[k], m[k].x, 1e-4f * (1 + m[k].x));
}

TEST(HaarLight, TermsAreTheLargestByTheirRule) {
  const int n = 16;
  const std::vector<Rgb> m = cubeMeans(envmap::builtinEnvironment("builtin:sky", 64), n);
  for (Selection sel : {Selection::Magnitude, Selection::AreaWeighted}) {
    const HaarLight l = approximate(m, n, 40, sel);
    ASSERT_EQ(l.terms(), 40u);
    EXPECT_NO_THROW({
      HaarLight c = l;
      c.unshadowed.bands = kUnshadowedBands;
      c.unshadowed.c.assign(std::size_t(kUnshadowedBands * kUnshadowedBands), Rgb(0.0f));
      c.check("light");
    });
    const HaarLight all = approximate(m, n, coefficientCount(n), sel);
    const std::vector<Rgb> dense = all.dense();
    const auto score = [&](std::size_t k) {
      const Rgb& c = dense[k];
      const double side = supportSide(k, n);
      return std::sqrt(double(c.x) * c.x + double(c.y) * c.y + double(c.z) * c.z) *
             (sel == Selection::AreaWeighted ? side * side : 1.0);
    };
    double smallestKept = 1e300;
    std::vector<bool> kept(dense.size());
    for (std::uint32_t k : l.index) {
      kept[k] = true;
      smallestKept = std::min(smallestKept, score(k));
    }
    for (std::size_t k = 0; k < dense.size(); ++k)
      if (!kept[k]) {
        ASSERT_LE(score(k), smallestKept) << toString(sel) << " " << k;
      }
    EXPECT_LT(l.energyKept, 1.0);
    EXPECT_GT(l.energyKept, 0.5);
  }
  // Magnitude keeps the most energy for its count (it is the L2-optimal choice).
  EXPECT_GE(approximate(m, n, 40, Selection::Magnitude).energyKept,
            approximate(m, n, 40, Selection::AreaWeighted).energyKept);
}

TEST(HaarLight, BrightTexelsAndTheShOfTheRestAddUpToTheEnvironment) {
  // The unshadowed part lit by the bright texels exactly and by the SH of the rest: for a
  // normal, their sum is the SH irradiance of the whole environment to the patches' quadrature
  // and the bands' truncation of the patches (a small texel's SH at 12 bands rings).
  const int n = 16;
  const envmap::Environment sky = envmap::builtinEnvironment("builtin:sky", 256);
  const std::vector<Rgb> means = cubeMeans(sky, n);
  const UnshadowedPart part = unshadowedPart(sky, means, n);
  ASSERT_EQ(part.bright.size(), kBrightTexels);
  // The brightest texel holds the sun.
  const Vec3f sun = sky.caps().front().direction;
  EXPECT_EQ(part.bright.front().texel, texelOf(sun, n));
  // What was taken out of the SH is the bright texels' power: the DC term drops by
  // Σ L_b Ω_b · Y00.
  const sh::RgbSh whole = envmap::projectEnvironment(sky, kUnshadowedBands);
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(n);
  double taken = 0;
  for (const BrightTexel& b : part.bright) taken += b.radiance.x * omega[b.texel % omega.size()];
  EXPECT_NEAR((whole.c[0].x - part.sh.c[0].x) / 0.28209479177387814, taken, 1e-3 * taken);
}

TEST(HaarLight, BadArgumentsAreRefused) {
  EXPECT_THROW(cubeMeans(constant(1), 12), Error);
  EXPECT_THROW(approximate(std::vector<Rgb>(10), 8, 5), Error);
  EXPECT_THROW(approximate(std::vector<Rgb>(coefficientCount(8)), 8, 0), Error);
  HaarLight l = projectLight(constant(1), 4, 3);
  EXPECT_NO_THROW(l.check("l"));
  HaarLight bad = l;
  bad.index[1] = bad.index[0];
  EXPECT_THROW(bad.check("l"), Error);
  bad = l;
  bad.index.back() = std::uint32_t(coefficientCount(4));
  EXPECT_THROW(bad.check("l"), Error);
  bad = l;
  bad.value[0].y = std::nanf("");
  EXPECT_THROW(bad.check("l"), Error);
  bad = l;
  bad.bright.push_back(bad.bright.front());  // a bright texel twice
  EXPECT_THROW(bad.check("l"), Error);
}

}  // namespace
}  // namespace prt::haar
