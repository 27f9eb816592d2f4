#include "prt/envmap/analytic.hpp"

#include <cmath>

#include "prt/core/quadrature.hpp"

namespace prt::envmap {

std::vector<double> capLegendreIntegrals(int bands, double halfAngle) {
  const double x = std::cos(halfAngle);
  // P_0..P_bands at x; ∫_x^1 P_l = (P_{l−1} − P_{l+1}) / (2l + 1).
  std::vector<double> p(static_cast<std::size_t>(bands) + 1);
  legendrePolynomials(bands + 1, x, p.data());
  std::vector<double> out(bands);
  out[0] = 1 - x;
  for (int l = 1; l < bands; ++l) out[l] = (p[l - 1] - p[l + 1]) / (2 * l + 1);
  return out;
}

sh::RgbSh constantSh(int bands, const Rgb& radiance) {
  sh::checkBands(bands);
  sh::RgbSh out(bands);
  out.c[0] = radiance * static_cast<float>(std::sqrt(4 * kPi));
  return out;
}

sh::RgbSh directionalSh(int bands, const Vec3f& direction, const Rgb& power) {
  sh::checkBands(bands);
  std::vector<double> y(static_cast<std::size_t>(bands) * bands);
  sh::eval(bands, normalize(Vec3d(direction)), y.data());
  sh::RgbSh out(bands);
  for (std::size_t i = 0; i < y.size(); ++i) out.c[i] = power * static_cast<float>(y[i]);
  return out;
}

sh::RgbSh capSh(int bands, const Cap& cap) {
  sh::checkBands(bands);
  const std::vector<double> integ = capLegendreIntegrals(bands, cap.halfAngle);
  std::vector<double> y(static_cast<std::size_t>(bands) * bands);
  sh::eval(bands, normalize(Vec3d(cap.direction)), y.data());
  sh::RgbSh out(bands);
  for (int l = 0; l < bands; ++l)
    for (int m = -l; m <= l; ++m) {
      const int i = sh::index(l, m);
      out.c[i] = cap.radiance * static_cast<float>(2 * kPi * integ[l] * y[i]);
    }
  return out;
}

}  // namespace prt::envmap
