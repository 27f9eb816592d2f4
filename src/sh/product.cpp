// Real Gaunt coefficients C_ijk = ∫ Y_i Y_j Y_k dω and SH products.
// Ng, Ramamoorthi & Hanrahan, "Triple Product Wavelet Integrals for All-Frequency Relighting",
// SIGGRAPH 2004; Sloan, "Stupid SH Tricks" (GDC 2008), products.
#include "prt/sh/product.hpp"

#include <array>
#include <cmath>
#include <cstdlib>
#include <string>

#include "prt/core/error.hpp"
#include "prt/sh/project.hpp"

namespace prt::sh {

namespace {
constexpr int kMaxProductBands = 16;

// Selection rules for real Gaunt coefficients (necessary conditions for C_ijk ≠ 0):
//  * |l_i − l_j| ≤ l_k ≤ l_i + l_j and l_i + l_j + l_k even (parity under ω → −ω);
//  * |m_k| ∈ {|m_i| + |m_j|, ||m_i| − |m_j||} (products of cos/sin of mφ);
//  * an even number of the three m are negative (sin-type: odd under φ → −φ).
bool mayBeNonZero(int li, int mi, int lj, int mj, int lk, int mk) {
  if (lk < std::abs(li - lj) || lk > li + lj || (li + lj + lk) % 2) return false;
  const int a = std::abs(mi), b = std::abs(mj), c = std::abs(mk);
  if (c != a + b && c != std::abs(a - b)) return false;
  return ((mi < 0) + (mj < 0) + (mk < 0)) % 2 == 0;
}
}  // namespace

// The integrand Y_i Y_j Y_k has degree ≤ 3(B−1), so Gauss–Legendre with n ≥ (3B−2)/2 rings is
// exact. Candidates passing the selection rules are integrated; zeros are dropped (|C| < 1e-10).
TripleProduct::TripleProduct(int bands) : bands_(bands) {
  checkBands(bands);
  if (bands > kMaxProductBands)
    throw Error("TripleProduct supports bands 1.." + std::to_string(kMaxProductBands) + ", got " +
                std::to_string(bands));
  struct Candidate {
    int i, j, k;
  };
  std::vector<Candidate> cand;
  for (int li = 0; li < bands; ++li)
    for (int mi = -li; mi <= li; ++mi)
      for (int lj = 0; lj < bands; ++lj)
        for (int mj = -lj; mj <= lj; ++mj)
          for (int lk = 0; lk < bands; ++lk)
            for (int mk = -lk; mk <= lk; ++mk)
              if (mayBeNonZero(li, mi, lj, mj, lk, mk))
                cand.push_back({index(li, mi), index(lj, mj), index(lk, mk)});
  const SphereQuadrature q = gaussLegendreSphere((3 * bands) / 2 + 1);
  std::vector<double> sum(cand.size(), 0.0);
  std::array<double, kMaxProductBands * kMaxProductBands> y;
  for (std::size_t p = 0; p < q.dirs.size(); ++p) {
    eval(bands, q.dirs[p], y.data());
    const double w = q.weights[p];
    for (std::size_t c = 0; c < cand.size(); ++c)
      sum[c] += w * y[cand[c].i] * y[cand[c].j] * y[cand[c].k];
  }
  for (std::size_t c = 0; c < cand.size(); ++c)
    if (std::fabs(sum[c]) > 1e-10)
      entries_.push_back({static_cast<std::uint16_t>(cand[c].i),
                          static_cast<std::uint16_t>(cand[c].j),
                          static_cast<std::uint16_t>(cand[c].k), float(sum[c])});
}

void TripleProduct::multiply(const float* a, const float* b, float* out) const {
  std::array<double, kMaxProductBands * kMaxProductBands> acc{};
  for (const Entry& e : entries_) acc[e.k] += double(e.c) * a[e.i] * b[e.j];
  for (int k = 0; k < bands_ * bands_; ++k) out[k] = float(acc[k]);
}

RgbSh TripleProduct::multiply(const RgbSh& a, const ShCoeffs& b) const {
  if (a.bands != bands_ || b.bands != bands_)
    throw Error("TripleProduct: " + std::to_string(bands_) + "-band product given " +
                std::to_string(a.bands) + "- and " + std::to_string(b.bands) + "-band inputs");
  std::array<Rgbd, kMaxProductBands * kMaxProductBands> acc{};
  for (const Entry& e : entries_) acc[e.k] += Rgbd(a.c[e.i]) * (double(e.c) * b.c[e.j]);
  RgbSh out(bands_);
  for (int k = 0; k < bands_ * bands_; ++k) out.c[k] = Rgb(acc[k]);
  return out;
}

}  // namespace prt::sh
