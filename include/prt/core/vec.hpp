#pragma once
// Small value types for 3-vectors, RGB colours and 3x3 matrices. Float for storage and hot loops,
// double where accumulation needs it (quadrature, references).

#include <array>
#include <cmath>
#include <cstddef>

namespace prt {

template <typename T>
struct Vec3 {
  T x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3(T s) : x(s), y(s), z(s) {}
  template <typename U>
  constexpr explicit Vec3(const Vec3<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}

  constexpr T& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr T operator[](std::size_t i) const { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator*(const Vec3& o) const { return {x * o.x, y * o.y, z * o.z}; }
  constexpr Vec3 operator/(const Vec3& o) const { return {x / o.x, y / o.y, z / o.z}; }
  constexpr Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(T s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(const Vec3& o) {
    x *= o.x;
    y *= o.y;
    z *= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(T s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  constexpr Vec3& operator/=(T s) {
    x /= s;
    y /= s;
    z /= s;
    return *this;
  }
  constexpr bool operator==(const Vec3&) const = default;
};

template <typename T>
constexpr Vec3<T> operator*(T s, const Vec3<T>& v) {
  return v * s;
}
template <typename T>
constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
inline T length(const Vec3<T>& v) {
  return std::sqrt(dot(v, v));
}
template <typename T>
inline Vec3<T> normalize(const Vec3<T>& v) {
  return v / length(v);
}
template <typename T>
constexpr Vec3<T> min(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
template <typename T>
constexpr Vec3<T> max(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
template <typename T>
inline bool isFinite(const Vec3<T>& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;
/// Linear, scene-referred RGB.
using Rgb = Vec3<float>;
using Rgbd = Vec3<double>;

struct Vec2f {
  float x = 0, y = 0;
  constexpr bool operator==(const Vec2f&) const = default;
};

/// Row-major 3x3 matrix; m[r][c]. Rotations act on column vectors: v' = M v.
template <typename T>
struct Mat3 {
  std::array<std::array<T, 3>, 3> m{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

  static constexpr Mat3 identity() { return Mat3{}; }
  constexpr bool operator==(const Mat3&) const = default;
  constexpr Vec3<T> operator*(const Vec3<T>& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  constexpr Mat3 operator*(const Mat3& o) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
    return r;
  }
  constexpr Mat3 transposed() const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = m[j][i];
    return r;
  }
  template <typename U>
  constexpr Mat3<U> cast() const {
    Mat3<U> r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = U(m[i][j]);
    return r;
  }
};
using Mat3f = Mat3<float>;
using Mat3d = Mat3<double>;

/// Rotation by `angle` radians about the unit `axis` (right-handed, counter-clockwise looking
/// down the axis toward the origin).
Mat3d rotationAxisAngle(const Vec3d& axis, double angle);
/// Rotation from Euler angles in degrees, applied in the order: about X, then Y, then Z
/// (R = Rz * Ry * Rx).
Mat3d rotationEulerXYZ(double degX, double degY, double degZ);

/// An orthonormal frame (t, b, n) with n given; right-handed: cross(t, b) = n.
/// Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
template <typename T>
inline void orthonormalBasis(const Vec3<T>& n, Vec3<T>& t, Vec3<T>& b) {
  const T sign = std::copysign(T(1), n.z);
  const T a = T(-1) / (sign + n.z);
  const T c = n.x * n.y * a;
  t = {T(1) + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr float kPif = 3.14159265358979323846f;

}  // namespace prt
