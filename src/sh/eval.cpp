// SH evaluation: the fast polynomial path (Sloan, JCGT 2013; tables and recurrence in
// prt/sh/sh_fixed.hpp) dispatched over the band count, and the trigonometric reference.
#include "prt/sh/sh.hpp"

#include <array>
#include <cmath>
#include <cstdlib>
#include <string>
#include <type_traits>

#include "prt/core/error.hpp"
#include "prt/sh/sh_fixed.hpp"

namespace prt::sh {

void checkBands(int bands) {
  if (bands < 1 || bands > kMaxBands)
    throw Error("bands must be in 1.." + std::to_string(kMaxBands) + ", got " +
                std::to_string(bands));
}

namespace {

template <typename T>
using EvalFn = void (*)(T, T, T, T*);

template <int B>
void evalFloat(float x, float y, float z, float* out) {
  evalFixed<B>(Vec3f(x, y, z), out);
}

template <int... B>
constexpr std::array<EvalFn<float>, sizeof...(B)> makeTableF(std::integer_sequence<int, B...>) {
  return {&evalFloat<B + 1>...};
}
template <int B>
void evalDouble(double x, double y, double z, double* out) {
  evalFixed<B, double>(x, y, z, out);
}

template <int... B>
constexpr std::array<EvalFn<double>, sizeof...(B)> makeTableD(std::integer_sequence<int, B...>) {
  return {&evalDouble<B + 1>...};
}

template <typename T>
constexpr auto kFixed = [] {
  if constexpr (std::is_same_v<T, float>)
    return makeTableF(std::make_integer_sequence<int, kFixedBands>{});
  else
    return makeTableD(std::make_integer_sequence<int, kFixedBands>{});
}();

// The recurrence of sh_fixed.hpp with runtime bounds (bands 17..32), in double, the direction
// renormalised as in evalFixed(const Vec3f&, float*).
template <typename O>
void evalLoop(int bands, double x, double y, double z, O* out) {
  using T = double;
  const double sc = 1.5 - 0.5 * (x * x + y * y + z * z);
  x *= sc;
  y *= sc;
  z *= sc;
  const auto& t = detail::kPoly;
  T c = 1, s = 0;
  for (int m = 0; m < bands; ++m) {
    auto store = [&](int l, T p) {
      if (m == 0) {
        out[l * (l + 1)] = O(p);
      } else {
        out[l * (l + 1) + m] = O(p * c);
        out[l * (l + 1) - m] = O(p * s);
      }
    };
    T p2 = T(t.diag[m]);
    store(m, p2);
    if (m + 1 < bands) {
      T p1 = T(t.sub[m]) * z * p2;
      store(m + 1, p1);
      for (int l = m + 2; l < bands; ++l) {
        const T p = T(t.a[l][m]) * z * p1 + T(t.b[l][m]) * p2;
        store(l, p);
        p2 = p1;
        p1 = p;
      }
    }
    const T cn = x * c - y * s;
    s = x * s + y * c;
    c = cn;
  }
}

template <typename T>
void evalAny(int bands, const Vec3<T>& d, T* out) {
  checkBands(bands);
  if (bands <= kFixedBands)
    kFixed<T>[bands - 1](d.x, d.y, d.z, out);
  else
    evalLoop(bands, d.x, d.y, d.z, out);
}

template <typename T>
void evalBatchAny(int bands, std::span<const Vec3<T>> dirs, T* out) {
  checkBands(bands);
  const std::size_t n = static_cast<std::size_t>(bands) * bands;
  if (bands <= kFixedBands) {
    const EvalFn<T> fn = kFixed<T>[bands - 1];
    for (std::size_t k = 0; k < dirs.size(); ++k) fn(dirs[k].x, dirs[k].y, dirs[k].z, out + k * n);
  } else {
    for (std::size_t k = 0; k < dirs.size(); ++k)
      evalLoop(bands, dirs[k].x, dirs[k].y, dirs[k].z, out + k * n);
  }
}

}  // namespace

void eval(int bands, const Vec3f& dir, float* out) {
  evalAny(bands, dir, out);
}
void eval(int bands, const Vec3d& dir, double* out) {
  evalAny(bands, dir, out);
}
void evalBatch(int bands, std::span<const Vec3f> dirs, float* out) {
  evalBatchAny(bands, dirs, out);
}
void evalBatch(int bands, std::span<const Vec3d> dirs, double* out) {
  evalBatchAny(bands, dirs, out);
}

void evalReference(int bands, const Vec3d& dir, double* out) {
  checkBands(bands);
  const Vec3d d = normalize(dir);
  const double theta = std::acos(std::fmin(1.0, std::fmax(-1.0, d.z)));
  const double phi = std::atan2(d.y, d.x);
  const double ct = std::cos(theta), st = std::sin(theta);
  for (int m = 0; m < bands; ++m) {
    // P_m^m = (-1)^m (2m-1)!! sin^m θ, P_{m+1}^m = (2m+1) cos θ P_m^m,
    // (l-m) P_l^m = (2l-1) cos θ P_{l-1}^m - (l+m-1) P_{l-2}^m.
    double pmm = 1;
    for (int k = 1; k <= m; ++k) pmm *= -(2.0 * k - 1) * st;
    double p2 = 0, p1 = 0;
    for (int l = m; l < bands; ++l) {
      double p;
      if (l == m)
        p = pmm;
      else if (l == m + 1)
        p = (2.0 * m + 1) * ct * p1;
      else
        p = ((2.0 * l - 1) * ct * p1 - (l + m - 1.0) * p2) / (l - m);
      p2 = p1;
      p1 = p;
      const double k = normalization(l, m);  // √2 K_lm for m > 0
      if (m == 0) {
        out[index(l, 0)] = k * p;
      } else {
        out[index(l, m)] = k * p * std::cos(m * phi);
        out[index(l, -m)] = k * p * std::sin(m * phi);
      }
    }
  }
}

double normalization(int l, int m) {
  const int am = std::abs(m);
  double ratio = 1;  // (l−|m|)! / (l+|m|)!
  for (int k = l - am + 1; k <= l + am; ++k) ratio /= k;
  const double k = std::sqrt((2.0 * l + 1) / (4.0 * kPi) * ratio);
  return m == 0 ? k : std::sqrt(2.0) * k;
}

RgbSh RgbSh::truncated(int b) const {
  checkBands(b);
  if (b > bands)
    throw Error("cannot truncate " + std::to_string(bands) + "-band SH to " + std::to_string(b) +
                " bands");
  RgbSh r(b);
  for (int i = 0; i < b * b; ++i) r.c[i] = c[i];
  return r;
}

float reconstruct(const ShCoeffs& f, const Vec3f& dir) {
  std::array<float, kMaxBands * kMaxBands> y;
  eval(f.bands, dir, y.data());
  double sum = 0;
  for (int i = 0; i < f.bands * f.bands; ++i) sum += double(f.c[i]) * y[i];
  return float(sum);
}

Rgb reconstruct(const RgbSh& f, const Vec3f& dir) {
  std::array<float, kMaxBands * kMaxBands> y;
  eval(f.bands, dir, y.data());
  Rgbd sum(0.0);
  for (int i = 0; i < f.bands * f.bands; ++i) sum += Rgbd(f.c[i]) * double(y[i]);
  return Rgb(sum);
}

}  // namespace prt::sh
