// SH products through the real Gaunt tensor.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "prt/core/error.hpp"
#include "prt/sh/product.hpp"
#include "prt/sh/project.hpp"

using namespace prt;
using namespace prt::sh;

TEST(ShProduct, ConstantScales) {
  const int bands = 6;
  const TripleProduct tp(bands);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<float> f(bands * bands), k(bands * bands, 0.0f), out(bands * bands);
  for (float& v : f) v = u(rng);
  // g = 2.5 everywhere: g_00 = 2.5 sqrt(4π); f·g = 2.5 f.
  k[0] = float(2.5 * std::sqrt(4 * kPi));
  tp.multiply(f.data(), k.data(), out.data());
  for (int i = 0; i < bands * bands; ++i) EXPECT_NEAR(out[i], 2.5f * f[i], 1e-5) << i;
}

// Bands a + bands b − 1 ≤ B: the product is band-limited to B, so the Gaunt route must equal
// the projection of the pointwise product.
TEST(ShProduct, MatchesPointwiseProductProjection) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto [ba, bb, B] :
       {std::array<int, 3>{2, 2, 3}, {3, 3, 5}, {4, 3, 6}, {5, 5, 9}, {8, 8, 16}}) {
    std::vector<float> a(B * B, 0.0f), b(B * B, 0.0f), out(B * B);
    for (int i = 0; i < ba * ba; ++i) a[i] = float(u(rng));
    for (int i = 0; i < bb * bb; ++i) b[i] = float(u(rng));
    const TripleProduct tp(B);
    tp.multiply(a.data(), b.data(), out.data());
    auto value = [&](const std::vector<float>& c, const Vec3d& d) {
      std::vector<double> y(B * B);
      evalReference(B, d, y.data());
      double s = 0;
      for (int i = 0; i < B * B; ++i) s += c[i] * y[i];
      return s;
    };
    const ShCoeffs p = projectFunction(
        B, [&](const Vec3d& d) { return value(a, d) * value(b, d); }, B + 2);
    for (int i = 0; i < B * B; ++i) EXPECT_NEAR(out[i], p.c[i], 2e-5) << "B=" << B << " i=" << i;
    // The RGB path agrees with the scalar one.
    RgbSh ar(B);
    ShCoeffs bs(B);
    for (int i = 0; i < B * B; ++i) ar.c[i] = Rgb(a[i], -a[i], 0), bs.c[i] = b[i];
    const RgbSh o = tp.multiply(ar, bs);
    for (int i = 0; i < B * B; ++i) EXPECT_NEAR(o.c[i].y, -out[i], 1e-5);
  }
}

TEST(ShProduct, SparseAndChecked) {
  const TripleProduct tp(4);
  EXPECT_GT(tp.nonZeros(), 0u);
  EXPECT_LT(tp.nonZeros(), std::size_t(16 * 16 * 16) / 4);
  EXPECT_THROW(TripleProduct(17), Error);
  EXPECT_THROW(tp.multiply(RgbSh(3), ShCoeffs(4)), Error);
}
