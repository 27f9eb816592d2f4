#include "prt/core/quadrature.hpp"

#include <cmath>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/vec.hpp"

namespace prt {

QuadratureRule gaussLegendre(int n) {
  if (n < 1 || n > 4096)
    throw Error("quadrature order must be in 1..4096, got " + std::to_string(n));
  QuadratureRule q;
  q.nodes.resize(n);
  q.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = x;  // P_{k−1}, P_k; after the loop P_{n−1}, P_n
      for (int k = 2; k <= n; ++k) {
        const double pk = ((2.0 * k - 1) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pk;
      }
      const double pn = n == 1 ? x : p1, pm = n == 1 ? 1 : p0;
      dp = n * (x * pn - pm) / (x * x - 1);  // P_n'
      const double dx = pn / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-16) break;
    }
    q.nodes[i] = x;
    q.weights[i] = 2.0 / ((1 - x * x) * dp * dp);
  }
  return q;
}

QuadratureRule gaussLegendre(int n, double lo, double hi) {
  QuadratureRule q = gaussLegendre(n);
  const double half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
  for (int i = 0; i < n; ++i) {
    q.nodes[i] = mid + half * q.nodes[i];
    q.weights[i] *= half;
  }
  return q;
}

}  // namespace prt
