// SH rotation: M(R) = Z(α) Jᵀ Z(β) J Z(γ) (Kautz, Sloan & Snyder, EGWR 2002), with J tabulated
// once by the Ivanic–Ruedenberg recurrence, which is also the dense reference below.
//
// Why this method (profiled, see docs/perf/sh.md): building the dense per-band matrices by the
// recurrence costs ~5 terms per entry (≈12.8k instructions at B = 6, 3/4 of build + apply), and
// applying the dense blocks to RGB costs as much again. The zyz route makes `set` O(B) with no
// trigonometric calls, and `apply` costs two half-sparse J products plus three Z products
// (2×2 per ±m pair), about the price of one dense apply.
//
// ---- Dense reference ----
// The recurrence of Ivanic & Ruedenberg, J. Phys. Chem. 100 (1996)
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

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

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

void detail::rotationBlocksReference(int bands, const Mat3d& r, double* blocks) {
  checkBands(bands);
  double* blk = blocks;
  blk[0] = 1;
  if (bands > 1) {
    // M^1 = T R Tᵀ in IR's basis (y, z, x): M^1_ij = R[t(i)][t(j)], t(−1) = 1, t(0) = 2, t(1) = 0.
    const int t[3] = {1, 2, 0};
    double* m1 = blk + detail::rotationBlockOffset(1);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m1[i * 3 + j] = r.m[t[i]][t[j]];
  }
  // R_ij with i, j in −1..1.
  const double* m1 = blk + detail::rotationBlockOffset(1);
  auto R = [m1](int i, int j) { return m1[(i + 1) * 3 + (j + 1)]; };
  for (int l = 2; l < bands; ++l) {
    const double* prev = blk + detail::rotationBlockOffset(l - 1);
    double* cur = blk + detail::rotationBlockOffset(l);
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
  for (int l = 1; l < bands; ++l) {
    double* b = blk + detail::rotationBlockOffset(l);
    const int w = 2 * l + 1;
    for (int i = 0; i < w; ++i)
      for (int j = (i + 1) & 1; j < w; j += 2) b[i * w + j] = -b[i * w + j];
  }
}

// ---- Fast path: zxzxz ----
//
// Euler angles without trigonometry. For R = Rz(α) Ry(β) Rz(γ), the unit quaternion is
//   q = (w, x, y, z) = (cos(β/2) cos σ, −sin(β/2) sin δ, sin(β/2) cos δ, cos(β/2) sin σ),
// σ = (α+γ)/2, δ = (α−γ)/2 (Hamilton product qz(α) qy(β) qz(γ)). So e^{iσ} = (w + iz)/|(w, z)|,
// e^{iδ} = (y − ix)/|(x, y)|, e^{iα} = e^{iσ}e^{iδ}, e^{iγ} = e^{iσ}e^{−iδ},
// cos β = w² + z² − x² − y², sin β = 2|(w, z)||(x, y)| ≥ 0. Near β = 0 the direction of (x, y),
// hence δ, is ill-conditioned (error ε/sin(β/2)), but M depends on δ only through terms carrying
// sin(β/2)^|m−n| (|m − n| ≥ 1), so the result stays exact to round-off; likewise σ near β = π.
// At exactly β = 0 (or π) the undefined angle is set to 0. q comes from R by Shepperd's method
// (largest of 1 + tr, 1 + 2R_ii − tr under the square root), which is accurate for every R.
//
// Z(θ) = M(Rz(θ)), from g(φ) = f(φ − θ): for k > 0, (a, b) = (f_{l,k}, f_{l,−k}) →
//   (a cos kθ − b sin kθ, a sin kθ + b cos kθ).
// J = M(Rx(90°)), since Ry(β) = Rx(−90°) Rz(β) Rx(90°) (both fix +y and send +x to (cos β, 0,
// −sin β)), and M(Rx(−90°)) = Jᵀ as M is orthogonal.
//
// Parity classes. The reflection x → −x (φ → π − φ) commutes with rotations about x and maps
// Y_lm → (−1)^m Y_lm for m ≥ 0, −(−1)^m Y_lm for m < 0. So J never mixes the classes
// P = {m ≥ 0 even, m < 0 odd} (l + 1 functions) and N = {m > 0 odd, m < 0 even} (l functions):
// J is two dense blocks, half the entries of a full matrix. Slot k = 0..l of P holds
// m = mP(k), |m| = k; slot k = 1..l of N holds mN(k) = −mP(k) (slot 0 of N is unused, zero).
// The ±k partners that Z mixes share a slot, and with s̃_k = (−1)^k sin kθ, Z acts slot-wise:
//   P' = cos kθ · P − s̃_k N,   N' = cos kθ · N + s̃_k P
// (k even: P holds +k, N holds −k; k odd: P holds −k, so the sine's sign flips).
// apply gathers a band into (P, N), runs Z(γ), J, Z(β), Jᵀ, Z(α) on the class vectors, and
// scatters back. Single channel (float, double): class vectors padded to a multiple of 4 slots
// with zeros, J's class blocks column-major with that padding, so each column update and each Z
// step is whole SIMD vectors. RGB: one (r, g, b, 0) vector per slot and J_ij pre-broadcast, so
// the three channels ride in one SIMD register with no transposes. Explicit GCC/Clang vector
// types (SSE2 on x86-64 baseline) because the auto-vectoriser turned the SoA loops into shuffle
// storms. Bands 2..15 are compile-time specialised (fixed trip counts, unrolled); bands 16..31
// run the same code with runtime sizes. Band 0 is the identity and band 1 is applied directly as
// the 3×3 block.

namespace {

constexpr int pad4(int n) {
  return (n + 3) & ~3;
}
constexpr int mP(int k) {
  return (k & 1) ? -k : k;
}
constexpr int mN(int k) {
  return (k & 1) ? k : -k;
}

// J tables: dense (natural order, rotationBlockOffset layout, double) for `at`, and per band l
// four column-major pad4(l+1) × (l+1) matrices [J_P, J_N, J_Pᵀ, J_Nᵀ] in double and float.
using F4 = float __attribute__((vector_size(16)));

struct JTables {
  std::vector<double> dense;
  std::vector<double> d;
  std::vector<float> f;
  int offset[kMaxBands] = {};
  // RGB path: per band l, J_P, J_N, J_Pᵀ, J_Nᵀ row-major ((l+1)², l², (l+1)², l² entries), each
  // entry broadcast to all four lanes, starting at rgbOffset[l].
  std::vector<F4> rgb;
  int rgbOffset[kMaxBands] = {};
};

JTables makeJTables() {
  JTables t;
  t.dense.resize(static_cast<std::size_t>(detail::rotationBlockOffset(kMaxBands)));
  Mat3d rx90;
  rx90.m = {{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}};
  detail::rotationBlocksReference(kMaxBands, rx90, t.dense.data());
  int total = 0;
  for (int l = 0; l < kMaxBands; ++l) {
    t.offset[l] = total;
    total += 4 * pad4(l + 1) * (l + 1);
  }
  t.d.assign(static_cast<std::size_t>(total), 0.0);
  for (int l = 2; l < kMaxBands; ++l) {
    const double* b = t.dense.data() + detail::rotationBlockOffset(l);
    const int w = 2 * l + 1, rows = pad4(l + 1), size = rows * (l + 1);
    auto J = [&](int m, int n) { return b[(m + l) * w + (n + l)]; };
    double* jp = t.d.data() + t.offset[l];
    for (int j = 0; j <= l; ++j)
      for (int i = 0; i <= l; ++i) {
        jp[j * rows + i] = J(mP(i), mP(j));
        jp[2 * size + j * rows + i] = J(mP(j), mP(i));
        if (i > 0 && j > 0) {
          jp[size + j * rows + i] = J(mN(i), mN(j));
          jp[3 * size + j * rows + i] = J(mN(j), mN(i));
        }
      }
  }
  t.f.resize(t.d.size());
  for (std::size_t k = 0; k < t.d.size(); ++k) t.f[k] = float(t.d[k]);
  int rgbTotal = 0;
  for (int l = 0; l < kMaxBands; ++l) {
    t.rgbOffset[l] = rgbTotal;
    rgbTotal += 2 * ((l + 1) * (l + 1) + l * l);
  }
  t.rgb.resize(static_cast<std::size_t>(rgbTotal));
  for (int l = 2; l < kMaxBands; ++l) {
    const double* b = t.dense.data() + detail::rotationBlockOffset(l);
    const int w = 2 * l + 1, np = (l + 1) * (l + 1), nn = l * l;
    auto J = [&](int m, int n) { return float(b[(m + l) * w + (n + l)]); };
    F4* o = t.rgb.data() + t.rgbOffset[l];
    for (int i = 0; i <= l; ++i)
      for (int j = 0; j <= l; ++j) {
        o[i * (l + 1) + j] = F4{} + J(mP(i), mP(j));
        o[np + nn + i * (l + 1) + j] = F4{} + J(mP(j), mP(i));
      }
    for (int i = 1; i <= l; ++i)
      for (int j = 1; j <= l; ++j) {
        o[np + (i - 1) * l + (j - 1)] = F4{} + J(mN(i), mN(j));
        o[2 * np + nn + (i - 1) * l + (j - 1)] = F4{} + J(mN(j), mN(i));
      }
  }
  return t;
}

const JTables& jTables() {
  static const JTables t = makeJTables();
  return t;
}

template <typename T>
const T* jClass(const JTables& t);
template <>
const double* jClass<double>(const JTables& t) {
  return t.d.data();
}
template <>
const float* jClass<float>(const JTables& t) {
  return t.f.data();
}

// Band shapes: compile-time (Fixed) or runtime (Dyn); the kernels read s.l and s.rows.
template <int L>
struct Fixed {
  static constexpr int l = L;
  static constexpr int rows = pad4(L + 1);
};
struct Dyn {
  int l, rows;
};

// Single channel: the class vectors P, N as padded arrays, processed a SIMD vector at a time
// (4 floats or 2 doubles); J's class blocks column-major, so J x is a sum of column vectors
// scaled by x_j.
template <typename T>
struct Simd;
template <>
struct Simd<float> {
  using V = float __attribute__((vector_size(16)));
};
template <>
struct Simd<double> {
  using V = double __attribute__((vector_size(16)));
};

template <typename T, typename V = typename Simd<T>::V>
[[gnu::always_inline]] inline V load(const T* a) {
  V v;
  __builtin_memcpy(&v, a, sizeof v);
  return v;
}
template <typename T, typename V>
[[gnu::always_inline]] inline void store(T* a, V v) {
  __builtin_memcpy(a, &v, sizeof v);
}

// Z(θ) on slots 0..rows−1 (padded slots are zero and stay zero).
template <typename T>
[[gnu::always_inline]] inline void zStep(int rows, const Rotation::ZFactor<T>& z, T* p, T* n) {
  constexpr int w = int(sizeof(typename Simd<T>::V) / sizeof(T));
  for (int k = 0; k < rows; k += w) {
    const auto a = load(p + k), b = load(n + k), c = load(z.c + k), sn = load(z.s + k);
    store(p + k, c * a - sn * b);
    store(n + k, c * b + sn * a);
  }
}

// y = A x for a column-major rows × cols block, columns j0..cols−1 (x's other slots are zero).
template <typename T>
[[gnu::always_inline]] inline void matVec(const T* a, int rows, int j0, int cols, const T* x,
                                          T* y) {
  using V = typename Simd<T>::V;
  constexpr int w = int(sizeof(V) / sizeof(T));
  V acc[kMaxBands / w];
  for (int v = 0; v < rows / w; ++v) acc[v] = V{};
  for (int j = j0; j < cols; ++j) {
    const T xj = x[j];
    for (int v = 0; v < rows / w; ++v) acc[v] += load(a + j * rows + v * w) * xj;
  }
  for (int v = 0; v < rows / w; ++v) store(y + v * w, acc[v]);
}

// Band l ≥ 2 of in → out (B² arrays), one channel.
template <typename T, typename S>
void rotateBand(S s, const T* jt, const Rotation::Factors<T>& fa, const T* in, T* out) {
  const int l = s.l, rows = s.rows, size = rows * (l + 1);
  alignas(16) T p[kMaxBands], n[kMaxBands], q[kMaxBands], u[kMaxBands];
  const T* x = in + l * (l + 1);
  T* y = out + l * (l + 1);
  // Gather into whole vectors built in registers (scalar stores followed by a vector load
  // would defeat store-to-load forwarding).
  using V = typename Simd<T>::V;
  constexpr int w = int(sizeof(V) / sizeof(T));
  for (int k = 0; k < rows; k += w) {
    V a, b;
    for (int i = 0; i < w; ++i) {
      a[i] = k + i <= l ? x[mP(k + i)] : T(0);
      b[i] = k + i <= l && k + i > 0 ? x[mN(k + i)] : T(0);
    }
    store(p + k, a);
    store(n + k, b);
  }
  zStep<T>(rows, fa.g, p, n);
  matVec<T>(jt, rows, 0, l + 1, p, q);
  matVec<T>(jt + size, rows, 1, l + 1, n, u);
  zStep<T>(rows, fa.b, q, u);
  matVec<T>(jt + 2 * size, rows, 0, l + 1, q, p);
  matVec<T>(jt + 3 * size, rows, 1, l + 1, u, n);
  zStep<T>(rows, fa.a, p, n);
  for (int k = 0; k <= l; ++k) y[mP(k)] = p[k];
  for (int k = 1; k <= l; ++k) y[mN(k)] = n[k];
}

// RGB: one vector (r, g, b, 0) per slot, so J is applied entry by entry with J_ij broadcast
// (pre-broadcast in the table): no transposes, no padding of the class vectors.
[[gnu::always_inline]] inline F4 loadRgb(const Rgb& v) {
  return F4{v.x, v.y, v.z, 0.0f};
}
[[gnu::always_inline]] inline void storeRgb(Rgb& v, F4 a) {
  v.x = a[0], v.y = a[1], v.z = a[2];
}
template <typename S>
[[gnu::always_inline]] inline void zStepRgb(S s, const Rotation::ZFactor4& z, F4* p, F4* n) {
  for (int k = 1; k <= s.l; ++k) {
    F4 c, sn;
    __builtin_memcpy(&c, z.c[k], sizeof c);
    __builtin_memcpy(&sn, z.s[k], sizeof sn);
    const F4 a = p[k], b = n[k];
    p[k] = a * c - b * sn;
    n[k] = b * c + a * sn;
  }
}
// y[i0 + i] = Σ_j a[i][j] x[i0 + j], i, j < dim (row-major broadcast entries).
template <int I0>
[[gnu::always_inline]] inline void matVecRgb(int dim, const F4* a, const F4* x, F4* y) {
  for (int i = 0; i < dim; ++i) {
    F4 acc = a[i * dim] * x[I0];
    for (int j = 1; j < dim; ++j) acc += a[i * dim + j] * x[I0 + j];
    y[I0 + i] = acc;
  }
}
template <typename S>
void rotateBandRgb(S s, const F4* jt, const Rotation::ZFactor4* z, const Rgb* in, Rgb* out) {
  const int l = s.l, np = (l + 1) * (l + 1), nn = l * l;
  F4 p[kMaxBands], n[kMaxBands], q[kMaxBands], u[kMaxBands];
  const Rgb* x = in + l * (l + 1);
  Rgb* y = out + l * (l + 1);
  p[0] = loadRgb(x[0]);
  for (int k = 1; k <= l; ++k) p[k] = loadRgb(x[mP(k)]), n[k] = loadRgb(x[mN(k)]);
  zStepRgb(s, z[2], p, n);
  matVecRgb<0>(l + 1, jt, p, q);
  matVecRgb<1>(l, jt + np, n, u);
  zStepRgb(s, z[1], q, u);
  matVecRgb<0>(l + 1, jt + np + nn, q, p);
  matVecRgb<1>(l, jt + 2 * np + nn, u, n);
  zStepRgb(s, z[0], p, n);
  storeRgb(y[0], p[0]);
  for (int k = 1; k <= l; ++k) storeRgb(y[mP(k)], p[k]), storeRgb(y[mN(k)], n[k]);
}

// Bands 0 and 1.
template <typename T, typename V>
inline void lowBands(int bands, const Rotation::Factors<T>& fa, const V* in, V* out) {
  out[0] = in[0];
  if (bands < 2) return;
  const T* m = fa.m1;
  for (int i = 0; i < 3; ++i)
    out[1 + i] = in[1] * m[3 * i] + in[2] * m[3 * i + 1] + in[3] * m[3 * i + 2];
}

template <typename T, int C, typename V, int B>
void applyFixed(const Rotation::Factors<T>& fa, const Rotation::ZFactor4* z, const V* in, V* out) {
  const JTables& t = jTables();
  const T* jt = jClass<T>(t);
  lowBands(B, fa, in, out);
  [&]<int... L>(std::integer_sequence<int, L...>) {
    if constexpr (C == 3)
      (rotateBandRgb(Fixed<L + 2>{}, t.rgb.data() + t.rgbOffset[L + 2], z, in, out), ...);
    else
      (rotateBand<T>(Fixed<L + 2>{}, jt + t.offset[L + 2], fa, in, out), ...);
  }
  (std::make_integer_sequence<int, (B > 2 ? B - 2 : 0)>{});
}

template <typename T, int C, typename V, int... B>
constexpr auto makeApplyTable(std::integer_sequence<int, B...>) {
  return std::array{&applyFixed<T, C, V, B + 1>...};
}

template <typename T, int C, typename V>
void applyAll(int bands, const Rotation::Factors<T>& fa, const Rotation::ZFactor4* z, const V* in,
              V* out) {
  static constexpr auto table =
      makeApplyTable<T, C, V>(std::make_integer_sequence<int, kFixedBands>{});
  table[std::size_t(std::min(bands, kFixedBands) - 1)](fa, z, in, out);
  if (bands <= kFixedBands) return;
  const JTables& t = jTables();
  for (int l = kFixedBands; l < bands; ++l) {
    if constexpr (C == 3)
      rotateBandRgb(Dyn{l, pad4(l + 1)}, t.rgb.data() + t.rgbOffset[l], z, in, out);
    else
      rotateBand<T>(Dyn{l, pad4(l + 1)}, jClass<T>(t) + t.offset[l], fa, in, out);
  }
}

// Z factors for k < bands, three angles at once: cos kθ and (−1)^k sin kθ, in double, float and
// float × 4 lanes. Even and odd k run as separate angle-addition chains stepping by 2θ (six
// independent chains, so the multiply–add latency overlaps). Entries past `bands` (at most one,
// written by the last odd step) and those never written keep finite values (zero from
// construction); they only ever multiply zero slots.
struct ZOut {
  Rotation::ZFactor<double>& d;
  Rotation::ZFactor<float>& f;
  Rotation::ZFactor4& r;
};
[[gnu::always_inline]] inline void zPut(const ZOut& o, int k, double c, double s) {
  o.d.c[k] = c, o.d.s[k] = s;
  const float cf = float(c), sf = float(s);
  o.f.c[k] = cf, o.f.s[k] = sf;
  const F4 cv = {cf, cf, cf, cf}, sv = {sf, sf, sf, sf};
  __builtin_memcpy(o.r.c[k], &cv, sizeof cv);
  __builtin_memcpy(o.r.s[k], &sv, sizeof sv);
}
void zFactors(int bands, const double (&c1)[3], const double (&s1)[3], const ZOut (&out)[3]) {
  double c2[3], s2[3], ce[3], se[3], co[3], so[3];
  for (int i = 0; i < 3; ++i) {
    c2[i] = c1[i] * c1[i] - s1[i] * s1[i], s2[i] = 2 * s1[i] * c1[i];
    ce[i] = 1, se[i] = 0, co[i] = c1[i], so[i] = s1[i];
  }
  for (int k = 0; k < bands; k += 2) {
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) {
      zPut(out[i], k, ce[i], se[i]);
      zPut(out[i], k + 1, co[i], -so[i]);
      double t = ce[i] * c2[i] - se[i] * s2[i];
      se[i] = se[i] * c2[i] + ce[i] * s2[i], ce[i] = t;
      t = co[i] * c2[i] - so[i] * s2[i];
      so[i] = so[i] * c2[i] + co[i] * s2[i], co[i] = t;
    }
  }
}

}  // namespace

Rotation::Rotation(int bands, const Mat3d& r) : bands_(bands), d_{}, f_{}, rgb_{} {
  checkBands(bands);
  jTables();  // tabulate J once per process, outside the hot paths
  set(r);
}

void Rotation::set(const Mat3d& r) {
  const auto& a = r.m;
  // Band 1: in our basis band 1 is ∝ (−y, z, −x), so M1_ij = s_i s_j R[t_i][t_j] with
  // t = (1, 2, 0), s = (−1, 1, −1).
  {
    const int t[3] = {1, 2, 0};
    const double sg[3] = {-1, 1, -1};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        d_.m1[3 * i + j] = sg[i] * sg[j] * a[t[i]][t[j]];
        f_.m1[3 * i + j] = float(d_.m1[3 * i + j]);
      }
  }
  if (bands_ < 3) return;
  // Shepperd: quaternion (w, x, y, z) from the largest of 4w², 4x², 4y², 4z².
  const double tr = a[0][0] + a[1][1] + a[2][2];
  double w, x, y, z;
  if (tr >= a[0][0] && tr >= a[1][1] && tr >= a[2][2]) {
    const double s = 2 * std::sqrt(1 + tr);
    w = 0.25 * s, x = (a[2][1] - a[1][2]) / s, y = (a[0][2] - a[2][0]) / s,
    z = (a[1][0] - a[0][1]) / s;
  } else if (a[0][0] >= a[1][1] && a[0][0] >= a[2][2]) {
    const double s = 2 * std::sqrt(1 + a[0][0] - a[1][1] - a[2][2]);
    w = (a[2][1] - a[1][2]) / s, x = 0.25 * s, y = (a[0][1] + a[1][0]) / s,
    z = (a[0][2] + a[2][0]) / s;
  } else if (a[1][1] >= a[2][2]) {
    const double s = 2 * std::sqrt(1 + a[1][1] - a[0][0] - a[2][2]);
    w = (a[0][2] - a[2][0]) / s, x = (a[0][1] + a[1][0]) / s, y = 0.25 * s,
    z = (a[1][2] + a[2][1]) / s;
  } else {
    const double s = 2 * std::sqrt(1 + a[2][2] - a[0][0] - a[1][1]);
    w = (a[1][0] - a[0][1]) / s, x = (a[0][2] + a[2][0]) / s, y = (a[1][2] + a[2][1]) / s,
    z = 0.25 * s;
  }
  const double cc = w * w + z * z, ss = x * x + y * y, n2 = cc + ss;
  const double hc = std::sqrt(cc), hs = std::sqrt(ss);
  const double sigC = hc > 0 ? w / hc : 1, sigS = hc > 0 ? z / hc : 0;   // e^{iσ}
  const double delC = hs > 0 ? y / hs : 1, delS = hs > 0 ? -x / hs : 0;  // e^{iδ}
  // α = σ + δ, β, γ = σ − δ.
  const double c1[3] = {sigC * delC - sigS * delS, (cc - ss) / n2, sigC * delC + sigS * delS};
  const double s1[3] = {sigS * delC + sigC * delS, 2 * hc * hs / n2, sigS * delC - sigC * delS};
  const ZOut out[3] = {{d_.a, f_.a, rgb_[0]}, {d_.b, f_.b, rgb_[1]}, {d_.g, f_.g, rgb_[2]}};
  zFactors(bands_, c1, s1, out);
}

// (Z(α) Jᵀ Z(β) J Z(γ))_mn in O(l): column n of Z(γ) has cos kγ at row n and sgn(n) sin kγ at
// row −n (k = |n|); row m of Z(α) has cos kα at column m and −sgn(m) sin kα at column −m.
double Rotation::at(int l, int m, int n) const {
  PRT_CHECK(l >= 0 && l < bands_ && m >= -l && m <= l && n >= -l && n <= l, "SH rotation index");
  if (l == 0) return 1;
  if (l == 1) return d_.m1[3 * (m + 1) + (n + 1)];
  const int w = 2 * l + 1;
  const double* b = jTables().dense.data() + detail::rotationBlockOffset(l);
  auto J = [&](int i, int j) { return b[(i + l) * w + (j + l)]; };
  auto sinK = [](const ZFactor<double>& z, int k) { return (k & 1) ? -z.s[k] : z.s[k]; };
  auto sgn = [](int v) { return double((v > 0) - (v < 0)); };
  const int kn = n < 0 ? -n : n, km = m < 0 ? -m : m;
  const double cn = d_.g.c[kn], sn = sgn(n) * sinK(d_.g, kn);
  double u[2 * kMaxBands - 1];
  for (int i = -l; i <= l; ++i) u[i + l] = J(i, n) * cn + J(i, -n) * sn;  // J Z(γ) e_n
  double tm = 0, tmm = 0;  // (Jᵀ Z(β) u) at rows m and −m
  for (int i = -l; i <= l; ++i) {
    const int k = i < 0 ? -i : i;
    const double wi = d_.b.c[k] * u[i + l] - sgn(i) * sinK(d_.b, k) * u[-i + l];
    tm += J(i, m) * wi;
    tmm += J(i, -m) * wi;
  }
  return d_.a.c[km] * tm - sgn(m) * sinK(d_.a, km) * tmm;
}

void Rotation::apply(const float* in, float* out) const {
  applyAll<float, 1>(bands_, f_, nullptr, in, out);
}
void Rotation::apply(const double* in, double* out) const {
  applyAll<double, 1>(bands_, d_, nullptr, in, out);
}
void Rotation::apply(const Rgb* in, Rgb* out) const {
  applyAll<float, 3>(bands_, f_, rgb_, in, out);
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
