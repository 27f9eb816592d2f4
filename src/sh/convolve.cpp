// Zonal convolution with the clamped cosine (irradiance) and Ramamoorthi–Hanrahan's quadratic
// form. R. Ramamoorthi, P. Hanrahan, "An Efficient Representation for Irradiance Environment
// Maps", SIGGRAPH 2001; "On the relationship between radiance and irradiance", JOSA A 18 (2001).
#include "prt/sh/convolve.hpp"

#include <cmath>
#include <string>

#include "prt/core/error.hpp"

namespace prt::sh {

// Funk–Hecke: Λ_l = 2π ∫_{-1}^{1} max(t, 0) P_l(t) dt. For the clamped cosine, Λ_0 = π,
// Λ_1 = 2π/3, Λ_l = 0 for odd l > 1, and for even l ≥ 2
//   Λ_l = 2π (−1)^{l/2−1} / ((l+2)(l−1)) · C_l,   C_l = l! / (2^l ((l/2)!)²) = binom(l, l/2) / 2^l,
// with C_{l+2} = C_l (l+1)/(l+2) (no factorial overflow at any l).
std::vector<double> clampedCosineKernel(int bands) {
  checkBands(bands);
  std::vector<double> k(bands, 0.0);
  k[0] = kPi;
  if (bands > 1) k[1] = 2 * kPi / 3;
  double c = 0.5;  // C_2 = 2 / 4
  for (int l = 2; l < bands; l += 2) {
    const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
    k[l] = 2 * kPi * sign / ((l + 2.0) * (l - 1.0)) * c;
    c *= (l + 1.0) / (l + 2.0);
  }
  return k;
}

namespace {
template <typename V>
void scaleBands(int bands, V* c, std::span<const double> scale) {
  if (static_cast<int>(scale.size()) < bands)
    throw Error("zonal kernel has " + std::to_string(scale.size()) + " bands, function has " +
                std::to_string(bands));
  for (int l = 0; l < bands; ++l)
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) c[i] *= float(scale[l]);
}
}  // namespace

void convolveZonal(RgbSh& f, std::span<const double> scale) {
  scaleBands(f.bands, f.c.data(), scale);
}
void convolveZonal(ShCoeffs& f, std::span<const double> scale) {
  scaleBands(f.bands, f.c.data(), scale);
}

RgbSh irradiance(const RgbSh& radiance) {
  RgbSh e = radiance;
  convolveZonal(e, clampedCosineKernel(radiance.bands));
  return e;
}

// RH 2001 eq. 12, E(n) = nᵀ M n, n = (x, y, z, 1):
//   M = | c1 L22   c1 L2-2  c1 L21  c2 L11 |
//       | c1 L2-2 −c1 L22   c1 L2-1 c2 L1-1 |
//       | c1 L21   c1 L2-1  c3 L20  c2 L10 |
//       | c2 L11   c2 L1-1  c2 L10  c4 L00 − c5 L20 |
// with c1 = Λ2·k22, c2 = Λ1·k1/2, c3 = 3 Λ2 k20, c4 = Λ0 k00, c5 = Λ2 k20 (k00 = 1/sqrt(4π),
// k1 = sqrt(3/4π), k20 = sqrt(5/16π), k22 = sqrt(15/16π)); numerically 0.429043, 0.511664,
// 0.743125, 0.886227, 0.247708. RH's basis has no Condon–Shortley phase, so their L11, L1-1, L21,
// L2-1 are minus ours: those four enter with a minus sign here.
Rgb irradianceQuadratic(const RgbSh& radiance3, const Vec3f& n) {
  if (radiance3.bands < 3)
    throw Error("irradianceQuadratic needs 3 bands, got " + std::to_string(radiance3.bands));
  const double k00 = 1 / std::sqrt(4 * kPi), k1 = std::sqrt(3 / (4 * kPi));
  const double k20 = std::sqrt(5 / (16 * kPi)), k22 = std::sqrt(15 / (16 * kPi));
  const double l0 = kPi, l1 = 2 * kPi / 3, l2 = kPi / 4;
  const double c1 = l2 * k22, c2 = l1 * k1 / 2, c3 = 3 * l2 * k20, c4 = l0 * k00, c5 = l2 * k20;
  const double x = n.x, y = n.y, z = n.z;
  Rgb out;
  for (int ch = 0; ch < 3; ++ch) {
    auto L = [&](int l, int m) { return double(radiance3.c[index(l, m)][ch]); };
    const double L00 = L(0, 0), L1m1 = -L(1, -1), L10 = L(1, 0), L11 = -L(1, 1);
    const double L2m2 = L(2, -2), L2m1 = -L(2, -1), L20 = L(2, 0), L21 = -L(2, 1), L22 = L(2, 2);
    const double e = c1 * L22 * (x * x - y * y) + c3 * L20 * z * z + c4 * L00 - c5 * L20 +
                     2 * c1 * (L2m2 * x * y + L21 * x * z + L2m1 * y * z) +
                     2 * c2 * (L11 * x + L1m1 * y + L10 * z);
    out[ch] = float(e);
  }
  return out;
}

const char* toString(Window window) {
  switch (window) {
    case Window::Hanning:
      return "hanning";
    case Window::Lanczos:
      return "lanczos";
    case Window::Dering:
      return "dering";
    case Window::None:
      break;
  }
  return "none";
}

Window parseWindow(const std::string& name) {
  for (Window w : {Window::None, Window::Hanning, Window::Lanczos, Window::Dering})
    if (name == toString(w)) return w;
  throw Error("window must be none, hanning, lanczos or dering, got '" + name + "'");
}

DeringResult applyWindow(RgbSh& f, Window window, double width) {
  DeringResult r;
  switch (window) {
    case Window::None:
      r.window.assign(static_cast<std::size_t>(f.bands), 1.0);
      break;
    case Window::Hanning:
      r.window = hanningWindow(f.bands, width);
      convolveZonal(f, r.window);
      break;
    case Window::Lanczos:
      r.window = lanczosWindow(f.bands, width);
      convolveZonal(f, r.window);
      break;
    case Window::Dering:
      if (width != 0) throw Error("the dering window picks its own width");
      r = dering(f);
      break;
  }
  return r;
}

}  // namespace prt::sh
