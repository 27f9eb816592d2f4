#include "prt/core/vec.hpp"

namespace prt {

Mat3d rotationAxisAngle(const Vec3d& axisIn, double angle) {
  const Vec3d a = normalize(axisIn);
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  Mat3d r;
  r.m = {{{t * a.x * a.x + c, t * a.x * a.y - s * a.z, t * a.x * a.z + s * a.y},
          {t * a.x * a.y + s * a.z, t * a.y * a.y + c, t * a.y * a.z - s * a.x},
          {t * a.x * a.z - s * a.y, t * a.y * a.z + s * a.x, t * a.z * a.z + c}}};
  return r;
}

Mat3d rotationEulerXYZ(double degX, double degY, double degZ) {
  constexpr double d2r = kPi / 180.0;
  return rotationAxisAngle({0, 0, 1}, degZ * d2r) * rotationAxisAngle({0, 1, 0}, degY * d2r) *
         rotationAxisAngle({1, 0, 0}, degX * d2r);
}

}  // namespace prt
