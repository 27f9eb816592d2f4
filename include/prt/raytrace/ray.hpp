#pragma once
// The ray and hit types of ray queries (occluder.hpp), apart from the ray tracer, so that code
// that only makes rays (a camera) includes no tracer.

#include <cstdint>

#include "prt/core/vec.hpp"

namespace prt {

struct Ray {
  Vec3f origin;
  Vec3f dir;  ///< unit
  float tnear = 0;
  float tfar = 3.4e38f;
};

struct Hit {
  bool hit = false;
  std::uint32_t triangle = 0;  ///< index into Mesh::triangles
  float u = 0, v = 0;          ///< barycentrics: p = (1-u-v) p0 + u p1 + v p2
  float t = 0;
};

}  // namespace prt
