#pragma once
// Real spherical harmonics: conventions and evaluation.
//
// Conventions (fixed project-wide; each is tested in tests/sh):
//  * Bands, not order: `bands = B` means degrees l = 0..B-1 and B*B coefficients.
//    (The GAMES202 course's SHOrder = 2 is bands = 3.)
//  * Real orthonormal SH with the Condon–Shortley phase, flat index i = l(l+1) + m:
//      Y00 = 0.282095, Y1,-1 = -0.488603 y, Y1,0 = 0.488603 z, Y1,1 = -0.488603 x.
//    This matches Google's spherical-harmonics library (used by the course) and D3DX.
//    With P_l^m the associated Legendre function *including* the (-1)^m phase:
//      Y_lm = sqrt(2) K_lm cos(m phi) P_l^m(cos theta)      m > 0
//      Y_l0 = K_l0 P_l^0(cos theta)
//      Y_lm = sqrt(2) K_l|m| sin(|m| phi) P_l^|m|(cos theta)  m < 0
//      K_lm = sqrt((2l+1)/(4 pi) (l-|m|)!/(l+|m|)!)
//    where (theta, phi) are the usual polar angles about +Z: z = cos theta,
//    x = sin theta cos phi, y = sin theta sin phi.
//  * SH is evaluated directly on world (x, y, z), world is right-handed with +Y up.
//  * Directions passed in are unit vectors (not checked on hot paths).
//
// References: Sloan, "Stupid Spherical Harmonics (SH) Tricks", GDC 2008; Sloan, "Efficient
// Spherical Harmonic Evaluation", JCGT 2(2), 2013 (the polynomial recurrence used here).

#include <span>
#include <vector>

#include "prt/core/band_limits.hpp"
#include "prt/core/vec.hpp"

namespace prt::sh {

/// Largest band count the library accepts anywhere (core/band_limits.hpp says why).
inline constexpr int kMaxBands = bands::kMaxLibrary;
/// Band counts 1..kFixedBands have compile-time specialised (fully unrolled) evaluation and
/// rotation; above, the same recurrences run in loops. Kernels that specialise further on the
/// band count (relighting) dispatch with sh::dispatchBands (sh_fixed.hpp).
inline constexpr int kFixedBands = 16;

constexpr int coeffCount(int bands) {
  return bands * bands;
}
constexpr int index(int l, int m) {
  return l * (l + 1) + m;
}

/// Throws prt::Error("bands must be in 1..32, got B") when out of range.
void checkBands(int bands);

/// The normalisation of the real basis function Y_lm: K_l|m| = sqrt((2l+1)/(4π) (l−|m|)!/(l+|m|)!),
/// times √2 for m ≠ 0 — the one definition (the reference evaluator and the shaders' kernels).
double normalization(int l, int m);

/// All B² values Y_i(dir) into out[0..B²) by Sloan's polynomial recurrence (see sh_fixed.hpp;
/// bands 1..16 are compile-time specialised, 17..32 use the same recurrence in a loop).
/// Float path: |eval − reference| ≤ 1e-6 · max_m |Y_lm(dir)| per band l (tested at every B).
/// `dir` must be unit length; not checked (hot path). Throws prt::Error on bands out of range.
void eval(int bands, const Vec3f& dir, float* out);
void eval(int bands, const Vec3d& dir, double* out);
/// dirs.size() rows of B² values each, row-major, into out (dispatches on B once).
void evalBatch(int bands, std::span<const Vec3f> dirs, float* out);
void evalBatch(int bands, std::span<const Vec3d> dirs, double* out);

/// Slow, simple double-precision reference: θ = acos z, φ = atan2(y, x), the unnormalised
/// associated-Legendre recurrence with the (-1)^m phase, K_lm from factorial ratios, cos/sin(mφ)
/// by std::cos/std::sin. Independent of the fast path; used by tests and as the bench baseline.
/// Normalises `dir` first.
void evalReference(int bands, const Vec3d& dir, double* out);

/// Scalar SH coefficients of one function.
struct ShCoeffs {
  int bands = 0;
  std::vector<float> c;  ///< B² coefficients
  ShCoeffs() = default;
  explicit ShCoeffs(int b) : bands(b), c(static_cast<std::size_t>(b * b), 0.0f) {}
};

/// RGB SH coefficients (lighting, RGB transfer).
struct RgbSh {
  int bands = 0;
  std::vector<Rgb> c;  ///< B² RGB coefficients
  RgbSh() = default;
  explicit RgbSh(int b) : bands(b), c(static_cast<std::size_t>(b * b), Rgb(0.0f)) {}
  /// The first `b` bands (b <= bands).
  RgbSh truncated(int b) const;
};

/// Evaluates sum_i c_i Y_i(dir).
float reconstruct(const ShCoeffs& f, const Vec3f& dir);
Rgb reconstruct(const RgbSh& f, const Vec3f& dir);

}  // namespace prt::sh
