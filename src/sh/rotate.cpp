// SH rotation matrices by the recurrence of Ivanic & Ruedenberg, J. Phys. Chem. 100 (1996)
// 6342–6347, with the errata of J. Phys. Chem. A 102 (1998) 9099–9100.
//
// Let M^l be band l's matrix in IR's real basis Ỹ_lm (no Condon–Shortley phase). With
// R_ij = M^1_ij (i, j in -1..1; band 1 is ∝ (y, z, x)), IR build M^l from M^{l-1}:
//   M^l_mn = u U + v V + w W, with denominators den = (l+n)(l−n) for |n| < l, 2l(2l−1) at |n| = l:
//   u = sqrt((l+m)(l−m)/den),  v = ½ sqrt((1+δ_m0)(l+|m|−1)(l+|m|)/den)(1−2δ_m0),
//   w = −½ sqrt((l−|m|−1)(l−|m|)/den)(1−δ_m0),
//   U = P(0, m, n)
//   V = P(1,1,n) + P(−1,−1,n)                                           m = 0
//       P(1, m−1, n) sqrt(1+δ_m1) − P(−1, −m+1, n)(1−δ_m1)              m > 0
//       P(1, m+1, n)(1−δ_m,−1) + P(−1, −m−1, n) sqrt(1+δ_m,−1)          m < 0
//   W = P(1, m+1, n) + P(−1, −m−1, n)   (m > 0),   P(1, m−1, n) − P(−1, −m+1, n)   (m < 0)
//   P(i, a, n) = R_i0 M^{l−1}_an                                          |n| < l
//                R_i1 M^{l−1}_{a,l−1} − R_i,−1 M^{l−1}_{a,−l+1}           n = l
//                R_i1 M^{l−1}_{a,−l+1} + R_i,−1 M^{l−1}_{a,l−1}           n = −l
// For |n| < l, each row m of M^l is a combination of at most five rows of M^{l−1} (scalars
// independent of n) times 1/sqrt((l+n)(l−n)): the build runs as short vector loops over n, with
// the n-independent factors of u, v, w in a constexpr table.
//
// Our basis is Y_lm = (−1)^m Ỹ_lm, so our block is M_mn = (−1)^{m+n} M^l_mn. Band 1 follows from
// g(ω) = f(R⁻¹ω): with Ỹ_1 ∝ T ω, T = rows (e_y, e_z, e_x), M^1 = T R Tᵀ.
#include "prt/sh/rotate.hpp"

#include <cmath>
#include <string>

#include "prt/core/error.hpp"
#include "prt/sh/sh_fixed.hpp"

namespace prt::sh {

namespace {

using detail::constSqrt;

// Up to five terms (coef, i, a): row m of M^l (interior part) = Σ coef · R_i0 · row a of M^{l−1},
// before the 1/sqrt(den) column factor.
struct Term {
  double coef = 0;
  int i = 0, a = 0;
};
struct RowTerms {
  Term t[5];
  int count = 0;
};
struct RotTables {
  RowTerms rows[kMaxBands][2 * kMaxBands - 1];            // [l][m + l]
  double invInterior[kMaxBands][2 * kMaxBands - 1] = {};  // 1/sqrt((l+n)(l−n)), [l][n + l]
  double invEdge[kMaxBands] = {};                         // 1/sqrt(2l(2l−1))
};

constexpr RotTables makeRotTables() {
  RotTables t;
  for (int l = 2; l < kMaxBands; ++l) {
    t.invEdge[l] = 1.0 / constSqrt(2.0 * l * (2.0 * l - 1));
    for (int n = -l + 1; n < l; ++n)
      t.invInterior[l][n + l] = 1.0 / constSqrt(double(l + n) * (l - n));
    for (int m = -l; m <= l; ++m) {
      RowTerms& r = t.rows[l][m + l];
      auto add = [&](double c, int i, int a) {
        if (c != 0) r.t[r.count++] = Term{c, i, a};
      };
      const int am = m < 0 ? -m : m;
      const double d = m == 0 ? 1 : 0;
      const double u = constSqrt(double(l + m) * (l - m));
      const double v = 0.5 * constSqrt((1 + d) * (l + am - 1.0) * (l + am)) * (1 - 2 * d);
      const double w = -0.5 * constSqrt((l - am - 1.0) * (l - am)) * (1 - d);
      add(u, 0, m);
      if (m == 0) {
        add(v, 1, 1);
        add(v, -1, -1);
      } else if (m > 0) {
        add(v * (m == 1 ? constSqrt(2.0) : 1.0), 1, m - 1);
        add(-v * (m == 1 ? 0.0 : 1.0), -1, -m + 1);
        add(w, 1, m + 1);
        add(w, -1, -m - 1);
      } else {
        add(v * (m == -1 ? 0.0 : 1.0), 1, m + 1);
        add(v * (m == -1 ? constSqrt(2.0) : 1.0), -1, -m - 1);
        add(w, 1, m - 1);
        add(-w, -1, -m + 1);
      }
    }
  }
  return t;
}

constexpr RotTables kRot = makeRotTables();

}  // namespace

Rotation::Rotation(int bands, const Mat3d& r)
    : bands_(bands),
      blocks_(static_cast<std::size_t>(blockOffset(bands))),
      blocksF_(static_cast<std::size_t>(blockOffset(bands))) {
  checkBands(bands);
  set(r);
}

double Rotation::at(int l, int m, int n) const {
  PRT_CHECK(l >= 0 && l < bands_ && m >= -l && m <= l && n >= -l && n <= l, "SH rotation index");
  return blocks_[blockOffset(l) + (m + l) * (2 * l + 1) + (n + l)];
}

void Rotation::set(const Mat3d& r) {
  double* blk = blocks_.data();
  blk[0] = 1;
  if (bands_ > 1) {
    // M^1 = T R Tᵀ in IR's basis (y, z, x): M^1_ij = R[t(i)][t(j)], t(−1) = 1, t(0) = 2, t(1) = 0.
    const int t[3] = {1, 2, 0};
    double* m1 = blk + blockOffset(1);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m1[i * 3 + j] = r.m[t[i]][t[j]];
  }
  // R_ij with i, j in −1..1.
  const double* m1 = blk + blockOffset(1);
  auto R = [m1](int i, int j) { return m1[(i + 1) * 3 + (j + 1)]; };
  for (int l = 2; l < bands_; ++l) {
    const double* prev = blk + blockOffset(l - 1);
    double* cur = blk + blockOffset(l);
    const int w = 2 * l + 1, wp = 2 * l - 1;
    const double* inv = kRot.invInterior[l];
    for (int m = -l; m <= l; ++m) {
      const RowTerms& rt = kRot.rows[l][m + l];
      double* row = cur + (m + l) * w;
      double edgeHi = 0, edgeLo = 0;
      for (int n = 0; n < w; ++n) row[n] = 0;
      for (int k = 0; k < rt.count; ++k) {
        const Term& tm = rt.t[k];
        const double* pr = prev + (tm.a + l - 1) * wp;  // row a of M^{l−1}, columns −l+1..l−1
        const double s = tm.coef * R(tm.i, 0);
        for (int n = 0; n < wp; ++n) row[n + 1] += s * pr[n];
        edgeHi += tm.coef * (R(tm.i, 1) * pr[wp - 1] - R(tm.i, -1) * pr[0]);
        edgeLo += tm.coef * (R(tm.i, 1) * pr[0] + R(tm.i, -1) * pr[wp - 1]);
      }
      for (int n = 1; n < w - 1; ++n) row[n] *= inv[n];
      row[0] = edgeLo * kRot.invEdge[l];
      row[w - 1] = edgeHi * kRot.invEdge[l];
    }
  }
  // To our Condon–Shortley basis: M_mn = (−1)^{m+n} M^l_mn, i.e. negate where m + n is odd
  // (l ± m has the parity of m, so (m + l) + (n + l) is odd exactly when m + n is).
  for (int l = 1; l < bands_; ++l) {
    double* b = blk + blockOffset(l);
    const int w = 2 * l + 1;
    for (int i = 0; i < w; ++i)
      for (int j = (i + 1) & 1; j < w; j += 2) b[i * w + j] = -b[i * w + j];
  }
  for (std::size_t k = 0; k < blocks_.size(); ++k) blocksF_[k] = float(blocks_[k]);
}

namespace {
template <typename M, typename V>
void applyBlocks(int bands, const M* blocks, const V* in, V* out) {
  out[0] = in[0] * blocks[0];
  for (int l = 1; l < bands; ++l) {
    const M* b = blocks + l * (4 * l * l - 1) / 3;
    const int w = 2 * l + 1, o = l * l;
    for (int i = 0; i < w; ++i) {
      V acc = in[o] * b[i * w];
      for (int j = 1; j < w; ++j) acc += in[o + j] * b[i * w + j];
      out[o + i] = acc;
    }
  }
}
}  // namespace

// Applying band l: out_l = M_l in_l. Undoing the parity flip of set() here would cost nothing
// either way, so the stored blocks are already in our basis.
void Rotation::apply(const float* in, float* out) const {
  applyBlocks(bands_, blocksF_.data(), in, out);
}
void Rotation::apply(const double* in, double* out) const {
  applyBlocks(bands_, blocks_.data(), in, out);
}
void Rotation::apply(const Rgb* in, Rgb* out) const {
  applyBlocks(bands_, blocksF_.data(), in, out);
}

RgbSh Rotation::apply(const RgbSh& in) const {
  if (in.bands != bands_)
    throw Error("cannot rotate " + std::to_string(in.bands) + "-band SH with a " +
                std::to_string(bands_) + "-band rotation");
  RgbSh out(bands_);
  apply(in.c.data(), out.c.data());
  return out;
}

// Rotation about +Z by α: g(φ) = f(φ − α), so per band and m > 0, with (a, b) = (f_{l,m},
// f_{l,−m}):
//   g_{l,m} = a cos mα − b sin mα,   g_{l,−m} = a sin mα + b cos mα.
// cos mα, sin mα by the angle-addition recurrence from one cos/sin.
template <typename V>
static void rotateZImpl(int bands, double angle, const V* in, V* out) {
  checkBands(bands);
  const double c1 = std::cos(angle), s1 = std::sin(angle);
  double cm[kMaxBands], sm[kMaxBands];
  cm[0] = 1;
  sm[0] = 0;
  for (int m = 1; m < bands; ++m) {
    cm[m] = cm[m - 1] * c1 - sm[m - 1] * s1;
    sm[m] = sm[m - 1] * c1 + cm[m - 1] * s1;
  }
  for (int l = 0; l < bands; ++l) {
    const int o = l * (l + 1);
    out[o] = in[o];
    for (int m = 1; m <= l; ++m) {
      const float c = float(cm[m]), s = float(sm[m]);
      const V a = in[o + m], b = in[o - m];
      out[o + m] = a * c - b * s;
      out[o - m] = a * s + b * c;
    }
  }
}

void rotateZ(int bands, double angle, const float* in, float* out) {
  rotateZImpl(bands, angle, in, out);
}
void rotateZ(int bands, double angle, const Rgb* in, Rgb* out) {
  rotateZImpl(bands, angle, in, out);
}

}  // namespace prt::sh
