#include "prt/render/probe_object.hpp"

#include <algorithm>

namespace prt::render {

Bounds probeGridBounds(const ProbeGrid& grid) {
  return {grid.origin, grid.position(grid.probes() - 1)};
}

Vec3f defaultObjectPosition(const ProbeGrid& grid) {
  return probeGridBounds(grid).centre();
}

float defaultObjectSize(const ProbeGrid& grid) {
  const Bounds b = probeGridBounds(grid);
  const Vec3f extent = b.hi - b.lo + grid.spacing;
  return 0.2f * std::max({extent.x, extent.y, extent.z});
}

Mesh placeObject(Mesh object, const Vec3f& at, float size) {
  const Bounds b = computeBounds(object);
  const Vec3f extent = b.hi - b.lo;
  const float largest = std::max({extent.x, extent.y, extent.z});
  const float scale = largest > 0 ? size / largest : 1.0f;
  for (Vec3f& p : object.positions) p = (p - b.centre()) * scale + at;
  return object;
}

}  // namespace prt::render
