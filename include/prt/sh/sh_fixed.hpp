#pragma once
// Compile-time specialised SH evaluation (header-only, so hot loops elsewhere can inline it).
//
// Sloan, "Efficient Spherical Harmonic Evaluation", JCGT 2(2), 2013: no trigonometry and no
// square root per direction. With z = cos θ and (x + i y)^m = sin^m θ (cos mφ + i sin mφ),
//   Y_l,+m = N_l^m · Re (x + i y)^m,   Y_l,-m = N_l^m · Im (x + i y)^m,   Y_l0 = N_l^0,
// where N_l^m(z) = sqrt(2) K_lm P_l^m(z) / sin^m θ (K_l0 without the sqrt 2) is a polynomial in z
// obeying the normalised associated-Legendre recurrence
//   N_m^m     = c_m                               (a constant, sign (-1)^m: Condon–Shortley)
//   N_{m+1}^m = sqrt(2m+3) z N_m^m
//   N_l^m     = a_lm z N_{l-1}^m + b_lm N_{l-2}^m,  a_lm = sqrt((4l²-1)/(l²-m²)),
//               b_lm = -sqrt(((l-1)²-m²)(2l+1) / ((2l-3)(l²-m²))),
// with c_0 = 1/sqrt(4π), c_1 = -sqrt(3/(4π)), c_m = -c_{m-1} sqrt((2m+1)/(2m)).
// (Re, Im)(x + i y)^m come from (x + i y)^{m-1} by one complex multiplication.
// All factors live in constexpr tables; evalFixed<B> is unrolled completely for a constant B, so
// the cost is ~3 flops per coefficient with no branches and grows smoothly with B.
//
// Accuracy: the normalised recurrence is stable (every intermediate is O(1) on the unit sphere);
// the float path stays within 1e-6 of the double reference relative to the band's largest value
// (tests/sh/test_eval.cpp).

#include <utility>

#include "prt/sh/sh.hpp"

namespace prt::sh::detail {

constexpr double constSqrt(double v) {
  if (v <= 0) return 0;
  double r = v > 1 ? v : 1;
  for (int i = 0; i < 100; ++i) {
    const double next = 0.5 * (r + v / r);
    if (next == r) break;
    r = next;
  }
  return r;
}

struct PolyTables {
  double a[kMaxBands][kMaxBands] = {};  ///< a[l][m]
  double b[kMaxBands][kMaxBands] = {};  ///< b[l][m]
  double diag[kMaxBands] = {};          ///< c_m = N_m^m
  double sub[kMaxBands] = {};           ///< sqrt(2m+3)
};

constexpr PolyTables makePolyTables() {
  PolyTables t;
  t.diag[0] = 1.0 / constSqrt(4.0 * 3.14159265358979323846);
  t.diag[1] = -constSqrt(3.0 / (4.0 * 3.14159265358979323846));
  for (int m = 2; m < kMaxBands; ++m)
    t.diag[m] = -t.diag[m - 1] * constSqrt((2.0 * m + 1) / (2.0 * m));
  for (int m = 0; m < kMaxBands; ++m) {
    t.sub[m] = constSqrt(2.0 * m + 3);
    for (int l = m + 2; l < kMaxBands; ++l) {
      const double l2m2 = double(l) * l - double(m) * m;
      t.a[l][m] = constSqrt((4.0 * l * l - 1) / l2m2);
      t.b[l][m] = -constSqrt(((l - 1.0) * (l - 1.0) - double(m) * m) * (2.0 * l + 1) /
                             ((2.0 * l - 3) * l2m2));
    }
  }
  return t;
}

inline constexpr PolyTables kPoly = makePolyTables();

// T goes by const reference through every function here (free for float and double once
// inlined): with a SIMD lane type T (relight/cpca_matrix_kernels.cpp's eight floats) a caller
// compiled for AVX2 and a copy of these templates compiled for the baseline disagree on how a
// 32-byte value is passed (GCC's -Wpsabi note), which corrupts the arguments wherever the
// compiler chooses not to inline (seen in the sanitizer build).

// Column m = M of the triangle: N_l^M for l = M..B-1, multiplied by (c, s) = (x + i y)^M.
template <int B, int M, typename T, typename O>
inline void evalColumn(const T& z, const T& c, const T& s, O* out) {
  T p2 = T(kPoly.diag[M]);
  auto store = [&](int l, const T& p) {
    if constexpr (M == 0) {
      out[l * (l + 1)] = O(p);
    } else {
      out[l * (l + 1) + M] = O(p * c);
      out[l * (l + 1) - M] = O(p * s);
    }
  };
  store(M, p2);
  if constexpr (M + 1 < B) {
    T p1 = T(kPoly.sub[M]) * z * p2;
    store(M + 1, p1);
#pragma GCC unroll 32
    for (int l = M + 2; l < B; ++l) {
      const T p = T(kPoly.a[l][M]) * z * p1 + T(kPoly.b[l][M]) * p2;
      store(l, p);
      p2 = p1;
      p1 = p;
    }
  }
}

template <int B, typename T, typename O, int... M>
inline void evalColumns(const T& x, const T& y, const T& z, O* out,
                        std::integer_sequence<int, M...>) {
  T c = T(1), s = T(0);
  // Left-to-right comma fold: column M, then advance (c, s) to (x + i y)^{M+1}.
  ((evalColumn<B, M>(z, c, s, out),
    [&] {
      const T cn = x * c - y * s;
      s = x * s + y * c;
      c = cn;
    }()),
   ...);
}

}  // namespace prt::sh::detail

namespace prt::sh {

/// All B² values at unit direction (x, y, z), for a compile-time band count B (1..kMaxBands),
/// computed in T's precision.
template <int B, typename T>
inline void evalFixed(const T& x, const T& y, const T& z, T* out) {
  static_assert(B >= 1 && B <= kMaxBands);
  detail::evalColumns<B>(x, y, z, out, std::make_integer_sequence<int, B>{});
}

/// The float path: all B² values as float for a float direction, to 1e-6 of the band's largest
/// value. A float unit vector is only unit to ~1e-7 (|d|² = 1 + δ), and the polynomial recurrence
/// amplifies δ by up to ~l²/2 (4e-6 at l = 15), so the direction is renormalised by one Newton
/// step for 1/|d| in double, s = (3 − |d|²)/2 (error O(δ²), no sqrt), and the recurrence runs in
/// double (scalar double costs what scalar float does) with results rounded to float once.
/// Also absorbs small denormalisation such as interpolated normals (|δ| ≲ 1e-3 keeps 1e-6).
template <int B>
inline void evalFixed(const Vec3f& d, float* out) {
  static_assert(B >= 1 && B <= kMaxBands);
  const double x = d.x, y = d.y, z = d.z;
  const double s = 1.5 - 0.5 * (x * x + y * y + z * z);
  detail::evalColumns<B>(x * s, y * s, z * s, out, std::make_integer_sequence<int, B>{});
}

}  // namespace prt::sh

namespace prt::sh {

/// The one band-count dispatch: returns f.template operator()<B>() for the compile-time
/// B == bands when 1 <= bands <= MaxB, else fallback(). (Each kernel states its MaxB: the band
/// counts worth a specialised copy; MaxB <= kMaxBands.)
template <int MaxB, typename F, typename G>
decltype(auto) dispatchBands(int bands, F&& f, G&& fallback) {
  static_assert(MaxB >= 1 && MaxB <= kMaxBands);
  if constexpr (MaxB == 1) {
    if (bands == 1) return f.template operator()<1>();
    return fallback();
  } else {
    if (bands == MaxB) return f.template operator()<MaxB>();
    return dispatchBands<MaxB - 1>(bands, std::forward<F>(f), std::forward<G>(fallback));
  }
}

}  // namespace prt::sh
