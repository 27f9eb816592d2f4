#include "prt/geometry/mesh.hpp"

#include "prt/core/hash.hpp"

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

std::string meshFingerprint(const Mesh& mesh) {
  Fnv1a h;
  h.addAll(mesh.positions);
  h.addAll(mesh.normals);
  h.addAll(mesh.triangles);
  h.addAll(mesh.albedo);
  return h.hex();
}

}  // namespace prt
