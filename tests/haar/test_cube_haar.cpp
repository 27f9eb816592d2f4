// The Haar basis over cube maps (haar/cube_haar.hpp, cube_texels.hpp): the transform is
// orthonormal and inverts, supports are where the pyramid says, texels and directions agree,
// and the texels' exact cosine integrals add up to the hemisphere's.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/haar/cube_texels.hpp"

namespace prt::haar {
namespace {

std::vector<float> randomCube(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> v(coefficientCount(n));
  for (float& x : v) x = u(rng);
  return v;
}

TEST(CubeHaar, TransformIsOrthonormalAndInverts) {
  for (int n : {2, 4, 16, 32}) {
    const std::vector<float> a = randomCube(n, 1), b = randomCube(n, 2);
    std::vector<float> ta = a, tb = b;
    forward(ta.data(), n);
    forward(tb.data(), n);
    double dot = 0, tdot = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      dot += double(a[k]) * b[k];
      tdot += double(ta[k]) * tb[k];
    }
    EXPECT_NEAR(tdot, dot, 1e-4 * std::abs(dot) + 1e-4) << n;  // Parseval: W orthonormal
    inverse(ta.data(), n);
    for (std::size_t k = 0; k < a.size(); ++k) ASSERT_NEAR(ta[k], a[k], 1e-5f) << n << " " << k;
  }
}

TEST(CubeHaar, ConstantFaceHasOnlyItsScalingCoefficient) {
  const int n = 8;
  std::vector<float> v(coefficientCount(n), 0.0f);
  for (int k = 0; k < n * n; ++k) v[std::size_t(2 * n * n + k)] = 3.0f;  // face +Y only
  forward(v.data(), n);
  for (std::size_t k = 0; k < v.size(); ++k) {
    // The face's mean times n (the normalised scaling function is 1/n over the face).
    const float expected = k == std::size_t(2 * n * n) ? 3.0f * n : 0.0f;
    ASSERT_NEAR(v[k], expected, 1e-5f) << k;
  }
}

TEST(CubeHaar, SupportsFollowThePyramid) {
  const int n = 16;
  EXPECT_EQ(supportSide(0, n), 16);                   // scaling
  EXPECT_EQ(supportSide(1, n), 16);                   // coarsest detail (h = 1)
  EXPECT_EQ(supportSide(2, n), 8);                    // h = 2
  EXPECT_EQ(supportSide(std::uint32_t(15 * n + 15), n), 2);  // finest
  EXPECT_EQ(supportSide(std::uint32_t(n * n + 8), n), 2);     // face 1, x = 8, y = 0
  // A unit texel's coefficients: non-zero exactly on the supports that contain it.
  std::vector<float> v(coefficientCount(n), 0.0f);
  const int x = 5, y = 11;
  v[std::size_t(y * n + x)] = 1.0f;
  forward(v.data(), n);
  int nonZero = 0;
  for (std::size_t k = 0; k < std::size_t(n * n); ++k)
    if (v[k] != 0.0f) {
      ++nonZero;
      EXPECT_NEAR(std::abs(v[k]), 1.0f / supportSide(std::uint32_t(k), n), 1e-6f) << k;
    }
  EXPECT_EQ(nonZero, 1 + 3 * 4);  // the scaling and three details at each of log2(16) levels
}

TEST(CubeHaar, TexelOfATexelsCentreIsThatTexel) {
  const int n = 8;
  for (std::uint32_t j = 0; j < coefficientCount(n); ++j) {
    const CubeTexel t = cubeTexel(j, n);
    const Vec3d d = envmap::cubeFaceDirection(t.face, 2.0 * (t.x + 0.5) / n - 1.0,
                                              2.0 * (t.y + 0.5) / n - 1.0);
    ASSERT_EQ(texelOf(Vec3f(normalize(d)), n), j);
  }
}

TEST(CubeHaar, ResolutionsAreChecked) {
  EXPECT_THROW(checkResolution(24, "x"), Error);
  EXPECT_THROW(checkResolution(1, "x"), Error);
  EXPECT_THROW(checkResolution(512, "x"), Error);
  EXPECT_NO_THROW(checkResolution(32, "x"));
}

TEST(CubeTexels, CosineIntegralsSumToTheHemisphere) {
  // (1/π) ∫ max(n·ω, 0) dω over the whole sphere is 1 for every normal: the exact per-texel
  // integrals (Lambert's formula, clipped at the horizon) must add up to it.
  const CubeTexels cube(16);
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3d nrm = normalize(Vec3d(g(rng), g(rng), g(rng)));
    double sum = 0, omega = 0;
    for (std::uint32_t j = 0; j < cube.count(); ++j) {
      sum += cube.clampedCosine(j, nrm);
      omega += cube.solidAngle(j);
    }
    EXPECT_NEAR(sum, 1.0, 1e-9) << trial;
    EXPECT_NEAR(omega, 4 * kPi, 1e-9);
  }
}

TEST(CubeTexels, CosineIntegralMatchesQuadratureAcrossTheHorizon) {
  // Against a fine midpoint rule over the texel's square (dω = dA / |d|³), for texels the
  // horizon crosses and texels wholly above it.
  const int n = 4;
  const CubeTexels cube(n);
  const Vec3d nrm = normalize(Vec3d(0.3, 0.8, -0.52));
  int crossed = 0;
  for (std::uint32_t j = 0; j < cube.count(); ++j) {
    const CubeTexel t = cubeTexel(j, n);
    const int m = 400;
    double q = 0;
    for (int b = 0; b < m; ++b)
      for (int a = 0; a < m; ++a) {
        const double s = -1.0 + 2.0 * (t.x + (a + 0.5) / m) / n;
        const double tt = -1.0 + 2.0 * (t.y + (b + 0.5) / m) / n;
        const Vec3d d = envmap::cubeFaceDirection(t.face, s, tt);
        const double len = length(d);
        const double dA = (2.0 / n / m) * (2.0 / n / m);
        q += std::max(0.0, dot(nrm, d / len)) / kPi * dA / (len * len * len);
      }
    int above = 0;
    for (const Vec3d& c : cube.corners(j)) above += dot(c, nrm) >= 0;
    crossed += above > 0 && above < 4;
    EXPECT_NEAR(cube.clampedCosine(j, nrm), q, 2e-6) << j;
  }
  EXPECT_GT(crossed, 4);  // the horizon's clipping was exercised
}

TEST(CubeTexels, SamplesAreUnbiasedForTheSolidAngle) {
  // E[weight] over uniform (u, v) is the texel's solid angle.
  const CubeTexels cube(8);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::uint32_t j : {0u, 37u, 200u, 383u}) {
    double sum = 0;
    const int k = 200000;
    for (int i = 0; i < k; ++i) {
      float w = 0;
      const float a = u(rng), b = u(rng);
      const Vec3f d = cube.sample(j, a, b, w);
      // (At the texel's very edge rounding may tip the direction into the neighbour.)
      if (a > 0.01f && a < 0.99f && b > 0.01f && b < 0.99f) {
        ASSERT_EQ(texelOf(d, 8), j);
      }
      sum += w;
    }
    EXPECT_NEAR(sum / k, cube.solidAngle(j), 2e-3 * cube.solidAngle(j)) << j;
  }
}

}  // namespace
}  // namespace prt::haar
