#include "prt/geometry/mesh.hpp"

namespace prt {

Bounds computeBounds(const Mesh& mesh) {
  Bounds b;
  if (mesh.positions.empty()) return b;
  b.lo = b.hi = mesh.positions[0];
  for (const Vec3f& p : mesh.positions) {
    b.lo = min(b.lo, p);
    b.hi = max(b.hi, p);
  }
  return b;
}

}  // namespace prt
