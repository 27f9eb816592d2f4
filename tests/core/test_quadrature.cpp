// The one Gauss–Legendre rule and Legendre recurrence (core/quadrature.hpp) against the
// integrals they must reproduce exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/quadrature.hpp"

namespace prt {
namespace {

// An n-point rule integrates x^k exactly for k ≤ 2n − 1: ∫_{−1}^{1} x^k = 2/(k+1) (k even), 0.
TEST(Quadrature, GaussLegendreIsExactToDegreeTwoNMinusOne) {
  for (int n : {1, 2, 3, 8, 17, 64}) {
    const QuadratureRule q = gaussLegendre(n);
    ASSERT_EQ(q.nodes.size(), static_cast<std::size_t>(n));
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += q.weights[i] * std::pow(q.nodes[i], k);
      const double exact = k % 2 ? 0.0 : 2.0 / (k + 1);
      EXPECT_NEAR(sum, exact, 1e-13) << "n " << n << " x^" << k;
    }
    // ... and not beyond: the nodes are the roots of P_n, so P_n² (degree 2n, ∫ = 2/(2n+1))
    // integrates to 0.
    std::vector<double> p(n + 1);
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      legendrePolynomials(n + 1, q.nodes[i], p.data());
      sum += q.weights[i] * p[n] * p[n];
    }
    EXPECT_NEAR(sum, 0.0, 1e-20) << "n " << n;
  }
}

TEST(Quadrature, MappedRuleIntegratesOverItsInterval) {
  const QuadratureRule q = gaussLegendre(5, 0.0, 1.0);
  double sum = 0, cube = 0;
  for (std::size_t i = 0; i < q.nodes.size(); ++i) {
    EXPECT_GT(q.nodes[i], 0.0);
    EXPECT_LT(q.nodes[i], 1.0);
    sum += q.weights[i];
    cube += q.weights[i] * q.nodes[i] * q.nodes[i] * q.nodes[i];
  }
  EXPECT_NEAR(sum, 1.0, 1e-15);
  EXPECT_NEAR(cube, 0.25, 1e-15);
}

TEST(Quadrature, OrderOutOfRangeIsRefused) {
  EXPECT_THROW(gaussLegendre(0), Error);
  EXPECT_THROW(gaussLegendre(4097), Error);
}

// P_l against closed forms, and ∫ P_l P_m = 2/(2l+1) δ_lm with the rule above.
TEST(Quadrature, LegendrePolynomialsAreTheOrthogonalFamily) {
  for (double t : {-1.0, -0.3, 0.0, 0.5, 1.0}) {
    double p[5];
    legendrePolynomials(5, t, p);
    EXPECT_DOUBLE_EQ(p[0], 1.0);
    EXPECT_DOUBLE_EQ(p[1], t);
    EXPECT_NEAR(p[2], 0.5 * (3 * t * t - 1), 1e-15);
    EXPECT_NEAR(p[3], 0.5 * (5 * t * t * t - 3 * t), 1e-15);
    EXPECT_NEAR(p[4], (35 * std::pow(t, 4) - 30 * t * t + 3) / 8, 1e-15);
  }
  const int bands = 12;
  const QuadratureRule q = gaussLegendre(bands);
  std::vector<double> gram(bands * bands, 0.0), p(bands);
  for (int i = 0; i < bands; ++i) {
    legendrePolynomials(bands, q.nodes[i], p.data());
    for (int l = 0; l < bands; ++l)
      for (int m = 0; m < bands; ++m) gram[l * bands + m] += q.weights[i] * p[l] * p[m];
  }
  for (int l = 0; l < bands; ++l)
    for (int m = 0; m < bands; ++m)
      EXPECT_NEAR(gram[l * bands + m], l == m ? 2.0 / (2 * l + 1) : 0.0, 1e-13) << l << "," << m;
}

}  // namespace
}  // namespace prt
