#pragma once
// The product of two SH functions projected back to B bands:
//   (f g)_k = Σ_ij f_i g_j C_ijk,   C_ijk = ∫ Y_i Y_j Y_k dω   (real Gaunt coefficients).
// The tensor is sparse (selection rules: l_k ≤ l_i + l_j, parity, |m| rules); we compute it once
// per band count by exact quadrature and keep the non-zeros.
// Reference: Ng, Ramamoorthi & Hanrahan, "Triple Product Wavelet Integrals", SIGGRAPH 2004;
// Sloan, "Stupid SH Tricks" §products.

#include <cstdint>
#include <vector>

#include "prt/sh/sh.hpp"

namespace prt::sh {

class TripleProduct {
 public:
  explicit TripleProduct(int bands);
  int bands() const { return bands_; }
  std::size_t nonZeros() const { return entries_.size(); }
  /// out = projection of (a·b) onto `bands` bands. a, b, out hold B² values.
  void multiply(const float* a, const float* b, float* out) const;
  RgbSh multiply(const RgbSh& a, const ShCoeffs& b) const;

 private:
  struct Entry {
    std::uint16_t i, j, k;
    float c;
  };
  int bands_;
  std::vector<Entry> entries_;
};

}  // namespace prt::sh
