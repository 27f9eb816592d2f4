#pragma once
// Zonal convolution, windowing against ringing.
//
// Convolving f with a kernel h symmetric about +Z (zonal) scales band l uniformly
// (Funk–Hecke): (h ⋆ f)_lm = Λ_l f_lm with Λ_l = 2π ∫ h(cos θ) P_l(cos θ) dcos θ.
// For the clamped cosine max(cos θ, 0) (irradiance E(n) = ∫ L(ω) max(n·ω,0) dω):
//   Λ_0 = π, Λ_1 = 2π/3, Λ_l = 0 for odd l > 1, and for even l
//   Λ_l = 2π (-1)^(l/2 - 1) / ((l+2)(l-1)) · l! / (2^l ((l/2)!)²)
// (Ramamoorthi & Hanrahan, "An Efficient Representation for Irradiance Environment Maps",
// SIGGRAPH 2001; "On the relationship between radiance and irradiance", JOSA A 2001).

#include <span>
#include <string>
#include <vector>

#include "prt/sh/sh.hpp"

namespace prt::sh {

/// Λ_l of the clamped cosine for l = 0..bands-1 (double, closed form above).
std::vector<double> clampedCosineKernel(int bands);
/// Multiplies band l of f by scale[l].
void convolveZonal(RgbSh& f, std::span<const double> scale);
void convolveZonal(ShCoeffs& f, std::span<const double> scale);
/// Irradiance SH from radiance SH: E_lm = Λ_l L_lm.
RgbSh irradiance(const RgbSh& radiance);

/// Irradiance at normal n from 3-band radiance by Ramamoorthi–Hanrahan's quadratic form
/// E(n) = nᵀ M n with n = (x, y, z, 1) (their eq. 12, in our sign convention).
Rgb irradianceQuadratic(const RgbSh& radiance3, const Vec3f& n);

/// Windows: per-band factors w_l in [0, 1] for l = 0..bands-1.
enum class Window { None, Hanning, Lanczos, Dering };
/// Hanning: w_l = (1 + cos(π l / W)) / 2 for l < W, with W = bands by default.
std::vector<double> hanningWindow(int bands, double width = 0);
/// Lanczos σ-factors: w_l = sinc(π l / W), W = bands by default.
std::vector<double> lanczosWindow(int bands, double width = 0);

/// Result of de-ringing: the window applied and the minimum reconstructed value (over a dense
/// sphere sampling, per channel minimum) before and after.
struct DeringResult {
  std::vector<double> window;
  double minBefore = 0;
  double minAfter = 0;
};
/// Finds the least-smoothing Hanning-type window (largest width) for which the reconstruction is
/// non-negative wherever the unwindowed function's band-limited mean allows it; applies it.
DeringResult dering(RgbSh& f);
/// Minimum over channels and over a dense quadrature grid of the reconstruction of f.
double minimumValue(const RgbSh& f);

/// "none" | "hanning" | "lanczos" | "dering".
const char* toString(Window window);
/// Parses a window's name; throws prt::Error("window must be none, hanning, lanczos or dering,
/// got 'X'") otherwise (a front end prefixes its option's name).
Window parseWindow(const std::string& name);
/// Applies `window` to f — the one rule prt light, prt validate and the Python module window a
/// light by: Hanning and Lanczos of width `width` (0: f's band count), de-ringing picking its own
/// (`width` must be 0). Returns the per-band factors applied (1 without a window), and for
/// de-ringing its minimum before and after.
DeringResult applyWindow(RgbSh& f, Window window, double width = 0);

}  // namespace prt::sh
