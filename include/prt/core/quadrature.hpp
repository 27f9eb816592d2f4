#pragma once
// The one-dimensional quadratures and recurrences the SH code builds on, once:
//  - Gauss–Legendre rules: n nodes x_i in (−1, 1), the roots of P_n, and weights
//    w_i = 2 / ((1 − x_i²) P_n'(x_i)²), exact for polynomials of degree ≤ 2n − 1 (Σ w_i = 2).
//    Used for the SH projection's sphere rule (sh::gaussLegendreSphere), the glossy bake's
//    hemisphere products, and the equal-area layout's edge integrals.
//  - The Legendre polynomials by Bonnet's recurrence (l+1) P_{l+1} = (2l+1) t P_l − l P_{l−1}.

#include <vector>

namespace prt {

/// Nodes (descending, Tricomi's order) and weights of an n-point rule on [lo, hi].
struct QuadratureRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

/// The n-point Gauss–Legendre rule on [−1, 1] (n in 1..4096; prt::Error otherwise), by Newton's
/// method on P_n from Tricomi's initial guess cos(π (i + 3/4) / (n + 1/2)), to double precision.
QuadratureRule gaussLegendre(int n);
/// The same rule mapped affinely onto [lo, hi] (weights scaled by (hi − lo) / 2).
QuadratureRule gaussLegendre(int n, double lo, double hi);

/// P_0(t) .. P_{n−1}(t) into p[0..n) (nothing for n ≤ 0).
inline void legendrePolynomials(int n, double t, double* p) {
  if (n > 0) p[0] = 1.0;
  if (n > 1) p[1] = t;
  for (int l = 1; l + 1 < n; ++l) p[l + 1] = ((2 * l + 1) * t * p[l] - l * p[l - 1]) / (l + 1);
}

}  // namespace prt
