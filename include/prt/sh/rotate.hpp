#pragma once
// SH rotation. Rotating a function f by a rotation R gives g(ω) = f(R⁻¹ ω): a lobe pointing
// along d moves to R d. Each band l transforms by its own (2l+1)×(2l+1) orthogonal matrix M_l(R),
// and M is a representation: M(R₁R₂) = M(R₁) M(R₂).
//
// Method ("zxzxz", Kautz, Sloan & Snyder, "Fast, Arbitrary BRDF Shading for Low-Frequency
// Lighting Using Spherical Harmonics", EGWR 2002, §4): write R with zyz Euler angles,
// R = Rz(α) Ry(β) Rz(γ), and Ry(β) = Rx(−90°) Rz(β) Rx(90°), so
//     M(R) = Z(α) Jᵀ Z(β) J Z(γ),   J = M(Rx(90°)) (fixed), Z(θ) = M(Rz(θ)) (2×2 per ±m pair).
// `set` only extracts cos/sin of kα, kβ, kγ from R (no trigonometric calls, see rotate.cpp);
// `apply` runs the five factors band by band. J is tabulated once per process by the
// Ivanic–Ruedenberg recurrence (J. Phys. Chem. 100 (1996), errata J. Phys. Chem. A 102 (1998)),
// which is also kept as the independent dense reference `detail::rotationBlocksReference`.

#include "prt/sh/sh.hpp"

namespace prt::sh {

class Rotation {
 public:
  /// Rotation for `bands` bands (1..32). Never allocates.
  Rotation(int bands, const Mat3d& r);
  explicit Rotation(int bands) : Rotation(bands, Mat3d::identity()) {}

  /// Re-targets to a new rotation: O(B) work, no allocation, no trigonometric calls.
  void set(const Mat3d& r);

  int bands() const { return bands_; }
  /// Element (m, n) of band l's matrix, m, n in -l..l (O(l) work; for inspection and tests).
  double at(int l, int m, int n) const;

  /// out = rotated in; in and out hold B² values and must not alias. No allocation.
  /// The double path is exact to double round-off; float and RGB run in float.
  void apply(const float* in, float* out) const;
  void apply(const double* in, double* out) const;
  void apply(const Rgb* in, Rgb* out) const;
  RgbSh apply(const RgbSh& in) const;

  /// cos kθ and σ_k sin kθ (σ_k = (−1)^k) for k = 0..31: the Z(θ) factor in the parity-class
  /// order used by apply (see rotate.cpp).
  template <typename T>
  struct ZFactor {
    alignas(16) T c[kMaxBands];
    alignas(16) T s[kMaxBands];
  };
  template <typename T>
  struct Factors {
    ZFactor<T> a, b, g;  // α, β, γ
    T m1[9];             // band 1 block, row-major (applied directly)
  };
  /// The float Z factors broadcast to four lanes for the RGB path.
  struct ZFactor4 {
    alignas(16) float c[kMaxBands][4];
    alignas(16) float s[kMaxBands][4];
  };

 private:
  int bands_;
  Factors<double> d_;
  Factors<float> f_;
  ZFactor4 rgb_[3];  // α, β, γ
};

/// Fast rotation about +Z by `angle` radians (each band mixes only m and -m).
void rotateZ(int bands, double angle, const float* in, float* out);
void rotateZ(int bands, double angle, const Rgb* in, Rgb* out);

namespace detail {
/// Offset of band l's (2l+1)×(2l+1) row-major block in a dense block array:
/// Σ_{k<l} (2k+1)² = l(4l²−1)/3.
constexpr int rotationBlockOffset(int l) {
  return l * (4 * l * l - 1) / 3;
}
/// Dense reference: all B bands' matrices M_l(r) (our basis) by the Ivanic–Ruedenberg
/// recurrence, written to blocks[rotationBlockOffset(l) + (m+l)(2l+1) + (n+l)]; `blocks` holds
/// rotationBlockOffset(bands) values. Independent of Rotation's method; used to tabulate J, in
/// tests, and as the benchmark baseline.
void rotationBlocksReference(int bands, const Mat3d& r, double* blocks);
}  // namespace detail

}  // namespace prt::sh
