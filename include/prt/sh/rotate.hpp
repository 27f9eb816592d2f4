#pragma once
// SH rotation. Rotating a function f by a rotation R gives g(ω) = f(R⁻¹ ω): a lobe pointing
// along d moves to R d. Each band l transforms by its own (2l+1)×(2l+1) orthogonal matrix,
// built from R by the recurrence of Ivanic & Ruedenberg, "Rotation Matrices for Real Spherical
// Harmonics. Direct Determination by Recursion", J. Phys. Chem. 100 (1996), with the errata of
// J. Phys. Chem. A 102 (1998). The recurrence is run in IR's basis (real SH without the
// Condon–Shortley phase, band 1 ∝ (y, z, x)); our basis differs by (-1)^m per function, so our
// block is D M_IR D with D = diag((-1)^m) (see rotate.cpp).

#include <vector>

#include "prt/sh/sh.hpp"

namespace prt::sh {

class Rotation {
 public:
  /// Builds the per-band matrices for `bands` bands (allocates once).
  Rotation(int bands, const Mat3d& r);
  explicit Rotation(int bands) : Rotation(bands, Mat3d::identity()) {}

  /// Rebuilds the matrices for a new rotation without allocating.
  void set(const Mat3d& r);

  int bands() const { return bands_; }
  /// Element (m, n) of band l's matrix, m, n in -l..l.
  double at(int l, int m, int n) const;

  /// out = rotated in; in and out hold B² values and must not alias. No allocation.
  void apply(const float* in, float* out) const;
  void apply(const double* in, double* out) const;
  void apply(const Rgb* in, Rgb* out) const;
  RgbSh apply(const RgbSh& in) const;

 private:
  /// Offset of band l's (2l+1)×(2l+1) row-major block: Σ_{k<l} (2k+1)² = l(4l²−1)/3.
  static constexpr int blockOffset(int l) { return l * (4 * l * l - 1) / 3; }

  int bands_;
  std::vector<double> blocks_;  // all bands' blocks, row-major, at blockOffset(l)
  std::vector<float> blocksF_;  // float copy for the float paths
};

/// Fast rotation about +Z by `angle` radians (each band mixes only m and -m).
void rotateZ(int bands, double angle, const float* in, float* out);
void rotateZ(int bands, double angle, const Rgb* in, Rgb* out);

}  // namespace prt::sh
