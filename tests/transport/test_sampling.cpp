// Tests of the low-discrepancy and direction sampling in prt/core/sampling.hpp: the (0,m,2)-net
// property of Sobol' points before and after Owen scrambling, uniformity of the scramble, and
// the moments of the direction mappings against their analytic values.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "prt/core/sampling.hpp"

namespace prt {
namespace {

// Every elementary interval [a 2^-j, (a+1) 2^-j) x [b 2^-(m-j), (b+1) 2^-(m-j)) holds exactly
// one of the 2^m points (fractions as 32-bit fixed point).
bool isZeroMTwoNet(const std::vector<std::uint32_t>& xs, const std::vector<std::uint32_t>& ys,
                   int m) {
  const std::size_t n = std::size_t(1) << m;
  for (int j = 0; j <= m; ++j) {
    std::vector<int> cells(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t cx = j == 0 ? 0 : xs[i] >> (32 - j);
      const std::uint32_t cy = m - j == 0 ? 0 : ys[i] >> (32 - (m - j));
      if (++cells[(std::size_t(cx) << (m - j)) | cy] > 1) return false;
    }
  }
  return true;
}

TEST(Sobol, FirstPointsAreTheKnownSequence) {
  // Dimension 0 is the van der Corput sequence; dimension 1 (x + 1), in natural (not Gray-code)
  // order, starts 0, 1/2, 3/4, 1/4, 5/8.
  const double x[] = {0, 0.5, 0.25, 0.75, 0.125};
  const double y[] = {0, 0.5, 0.75, 0.25, 0.625};
  for (std::uint32_t i = 0; i < 5; ++i) {
    EXPECT_EQ(sobol0(i) * 0x1p-32, x[i]) << i;
    EXPECT_EQ(sobol1(i) * 0x1p-32, y[i]) << i;
  }
}

TEST(Sobol, PrefixesAreZeroMTwoNetsBeforeAndAfterScrambling) {
  for (int m = 1; m <= 12; ++m) {
    const std::uint32_t n = 1u << m;
    std::vector<std::uint32_t> xs(n), ys(n), sx(n), sy(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      xs[i] = sobol0(i);
      ys[i] = sobol1(i);
      sx[i] = owenScramble(xs[i], 0x1234567u + m);
      sy[i] = owenScramble(ys[i], 0x89abcdefu * m);
    }
    EXPECT_TRUE(isZeroMTwoNet(xs, ys, m)) << "unscrambled, m = " << m;
    EXPECT_TRUE(isZeroMTwoNet(sx, sy, m)) << "scrambled, m = " << m;
    EXPECT_NE(sx, xs);
  }
}

TEST(Sobol, NotANetWithoutTheSecondDimensionMatrix) {
  // Sanity check of the checker itself: van der Corput in both dimensions is not a net.
  std::vector<std::uint32_t> xs(64);
  for (std::uint32_t i = 0; i < 64; ++i) xs[i] = sobol0(i);
  EXPECT_FALSE(isZeroMTwoNet(xs, xs, 6));
}

TEST(Sobol, TableMatchesDirectEvaluation) {
  const OwenSobol2D table(300);
  for (std::uint32_t i = 0; i < 300; ++i) {
    const Point2 a = table.point(i, 17u * i + 3, 99u);
    const Point2 b = scrambledSobol(i, 17u * i + 3, 99u);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_GE(a.x, 0.0f);
    EXPECT_LT(a.x, 1.0f);
  }
}

TEST(Sobol, CosineBatchIsBitIdenticalToScalarPath) {
  const OwenSobol2D table(200);
  float x[64], y[64], z[64];
  for (std::uint32_t first : {0u, 64u, 136u}) {
    const std::uint32_t count = first == 136 ? 64 : 37;
    table.cosineBatch(first, count, 0xabcdefu, 0x13572468u, x, y, z);
    for (std::uint32_t j = 0; j < count; ++j) {
      const Point2 u = table.point(first + j, 0xabcdefu, 0x13572468u);
      const Vec3f d = cosineHemisphere(u.x, u.y);
      ASSERT_EQ(d.x, x[j]) << first + j;
      ASSERT_EQ(d.y, y[j]) << first + j;
      ASSERT_EQ(d.z, z[j]) << first + j;
    }
  }
}

TEST(Owen, ScrambledPointIsUniformOverSeeds) {
  // Owen scrambling makes each point uniform on [0,1): chi-square over 16 bins for point 5,
  // 16000 seeds; 15 degrees of freedom, p = 0.001 critical value 37.7.
  const int bins = 16, seeds = 16000;
  std::vector<int> hx(bins, 0), hy(bins, 0);
  for (int s = 0; s < seeds; ++s) {
    const std::uint64_t key = deriveSeed(42, s);
    const Point2 p = scrambledSobol(5, std::uint32_t(key), std::uint32_t(key >> 32));
    ++hx[int(p.x * bins)];
    ++hy[int(p.y * bins)];
  }
  double cx = 0, cy = 0;
  const double expected = double(seeds) / bins;
  for (int b = 0; b < bins; ++b) {
    cx += (hx[b] - expected) * (hx[b] - expected) / expected;
    cy += (hy[b] - expected) * (hy[b] - expected) / expected;
  }
  EXPECT_LT(cx, 37.7);
  EXPECT_LT(cy, 37.7);
}

TEST(Directions, SinCos2PiMatchesLibm) {
  double worst = 0;
  for (int i = 0; i < (1 << 20); ++i) {
    const float u = float(i) * 0x1p-20f;
    float s, c;
    sinCos2Pi(u, s, c);
    worst =
        std::max({worst, std::abs(s - std::sin(2 * kPi * u)), std::abs(c - std::cos(2 * kPi * u))});
  }
  EXPECT_LT(worst, 4e-7);
  float s, c;
  sinCos2Pi(0.25f, s, c);
  EXPECT_NEAR(s, 1.0f, 1e-7f);
  EXPECT_NEAR(c, 0.0f, 1e-7f);
}

TEST(Directions, CosineHemisphereMomentsMatchAnalytic) {
  // Under pdf cos θ/π: E[cos θ] = 2/3, E[cos² θ] = 1/2, E[x] = E[y] = 0, all unit length.
  Pcg32 rng(7);
  const int n = 200000;
  double c1 = 0, c2 = 0, sx = 0, sy = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3f d = cosineHemisphere(rng.uniform(), rng.uniform());
    ASSERT_NEAR(length(d), 1.0f, 1e-6f);
    ASSERT_GE(d.z, 0.0f);
    c1 += d.z;
    c2 += d.z * d.z;
    sx += d.x;
    sy += d.y;
  }
  // Standard deviations of the means: sqrt(Var/n) with Var(cos) = 1/2 - 4/9, Var(x) = 1/4.
  const double se1 = std::sqrt((0.5 - 4.0 / 9.0) / n), seX = std::sqrt(0.25 / n);
  EXPECT_NEAR(c1 / n, 2.0 / 3.0, 5 * se1);
  EXPECT_NEAR(c2 / n, 0.5, 5 * std::sqrt((1.0 / 3.0 - 0.25) / n));
  EXPECT_NEAR(sx / n, 0.0, 5 * seX);
  EXPECT_NEAR(sy / n, 0.0, 5 * seX);
}

TEST(Directions, UniformSphereMomentsMatchAnalytic) {
  // Uniform on the sphere: E[z] = 0, E[z²] = 1/3, P(z > 0) = 1/2.
  Pcg32 rng(11);
  const int n = 200000;
  double z1 = 0, z2 = 0, up = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3f d = uniformSphere(rng.uniform(), rng.uniform());
    ASSERT_NEAR(length(d), 1.0f, 1e-6f);
    z1 += d.z;
    z2 += d.z * d.z;
    up += d.z > 0;
  }
  EXPECT_NEAR(z1 / n, 0.0, 5 * std::sqrt(1.0 / 3.0 / n));
  EXPECT_NEAR(z2 / n, 1.0 / 3.0, 5 * std::sqrt((0.2 - 1.0 / 9.0) / n));
  EXPECT_NEAR(up / n, 0.5, 5 * std::sqrt(0.25 / n));
}

TEST(Seeds, DerivedSeedsDifferAndAreStable) {
  EXPECT_NE(deriveSeed(1, 0), deriveSeed(1, 1));
  EXPECT_NE(deriveSeed(1, 0), deriveSeed(2, 0));
  EXPECT_EQ(deriveSeed(5, 9), deriveSeed(5, 9));
  EXPECT_EQ(reverseBits(1u), 0x80000000u);
  EXPECT_EQ(reverseBits(reverseBits(0x12345678u)), 0x12345678u);
}

}  // namespace
}  // namespace prt
