// Windowing SH against ringing (the Gibbs phenomenon of truncated expansions), and de-ringing.
// Sloan, "Stupid Spherical Harmonics (SH) Tricks", GDC 2008 §windowing; Sloan, "Deringing
// Spherical Harmonics", SIGGRAPH Asia 2017 Technical Briefs (window chosen to make the
// reconstruction non-negative).
#include "prt/sh/convolve.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "prt/core/error.hpp"
#include "prt/sh/project.hpp"

namespace prt::sh {

namespace {
double widthOr(int bands, double width) {
  checkBands(bands);
  if (width < 0) throw Error("window width must be >= 0, got " + std::to_string(width));
  return width > 0 ? width : bands;
}
}  // namespace

std::vector<double> hanningWindow(int bands, double width) {
  const double w = widthOr(bands, width);
  std::vector<double> out(bands);
  for (int l = 0; l < bands; ++l) out[l] = l < w ? 0.5 * (1 + std::cos(kPi * l / w)) : 0.0;
  return out;
}

std::vector<double> lanczosWindow(int bands, double width) {
  const double w = widthOr(bands, width);
  std::vector<double> out(bands);
  for (int l = 0; l < bands; ++l) {
    const double x = kPi * l / w;
    out[l] = l == 0 ? 1.0 : (l < w ? std::sin(x) / x : 0.0);
  }
  return out;
}

namespace {
// The dense grid used for minima: Gauss–Legendre with n = max(48, 8B) rings (2n² points), about
// 4 nodes per half-wavelength of the highest band, so the grid minimum is close to the true one.
SphereQuadrature minimumGrid(int bands) {
  return gaussLegendreSphere(std::max(48, 8 * bands));
}

// Minimum and maximum over the grid and channels of the reconstruction of f windowed by w.
std::pair<double, double> extremes(const RgbSh& f, const std::vector<double>& w,
                                   const SphereQuadrature& grid) {
  const int n = f.bands * f.bands;
  std::vector<Rgbd> c(n);
  for (int l = 0; l < f.bands; ++l)
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) c[i] = Rgbd(f.c[i]) * w[l];
  std::vector<double> y(n);
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec3d& d : grid.dirs) {
    eval(f.bands, d, y.data());
    Rgbd v(0.0);
    for (int i = 0; i < n; ++i) v += c[i] * y[i];
    lo = std::min({lo, v.x, v.y, v.z});
    hi = std::max({hi, v.x, v.y, v.z});
  }
  return {lo, hi};
}
}  // namespace

double minimumValue(const RgbSh& f) {
  checkBands(f.bands);
  return extremes(f, std::vector<double>(f.bands, 1.0), minimumGrid(f.bands)).first;
}

// Bisection on the Hanning width W in [1, B]: W = B is the mildest window considered,
// W ≤ 1 keeps only the mean (non-negative whenever f's mean is). Non-negativity is taken as
// monotone in W (wider windows ring more), which holds for the lobes and caps we met; the result
// is verified on the grid in any case and reported.
DeringResult dering(RgbSh& f) {
  checkBands(f.bands);
  const SphereQuadrature grid = minimumGrid(f.bands);
  DeringResult r;
  r.minBefore = extremes(f, std::vector<double>(f.bands, 1.0), grid).first;
  // A grid minimum of exactly 0 can hide slightly negative values between nodes, so the search asks
  // for a margin of kMargin × the maximum on the grid.
  constexpr double kMargin = 1e-3;
  auto ok = [&](double width) {
    const auto [lo, hi] = extremes(f, hanningWindow(f.bands, width), grid);
    return lo >= kMargin * hi;
  };
  double good = 1, bad = f.bands;
  if (r.minBefore >= 0) {  // nothing to do
    r.window.assign(f.bands, 1.0);
    r.minAfter = r.minBefore;
    return r;
  }
  if (ok(bad)) {
    good = bad;
  } else {
    for (int it = 0; it < 30 && bad - good > 1e-3; ++it) {
      const double mid = 0.5 * (good + bad);
      (ok(mid) ? good : bad) = mid;
    }
  }
  r.window = hanningWindow(f.bands, good);
  convolveZonal(f, r.window);
  r.minAfter = extremes(f, std::vector<double>(f.bands, 1.0), grid).first;
  return r;
}

}  // namespace prt::sh
