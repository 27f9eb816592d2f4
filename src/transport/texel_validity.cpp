#include "prt/transport/texel_validity.hpp"

#include <array>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"

namespace prt {

namespace {

/// kValidityProbeRays cosine-distributed directions about +Z: a Fibonacci spiral over the disc
/// lifted to the hemisphere (Malley's method), r = √((i + ½)/N), φ = i · the golden angle.
std::array<Vec3f, kValidityProbeRays> probeDirections() {
  std::array<Vec3f, kValidityProbeRays> d{};
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kValidityProbeRays; ++i) {
    const double r2 = (i + 0.5) / kValidityProbeRays, r = std::sqrt(r2), phi = golden * i;
    d[i] = Vec3f(Vec3d(r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - r2)));
  }
  return d;
}

}  // namespace

std::vector<std::uint8_t> insideGeometry(const Mesh& mesh, const Occluder& occluder,
                                         std::span<const Vec3f> positions,
                                         std::span<const Vec3f> normals) {
  PRT_CHECK(positions.size() == normals.size(), "one normal per point");
  static const std::array<Vec3f, kValidityProbeRays> local = probeDirections();
  std::vector<std::uint8_t> inside(positions.size(), 0);
  parallelFor(positions.size(), 64, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Vec3f n = normals[i];
      Vec3f t, bt;
      orthonormalBasis(n, t, bt);
      const Vec3f origin = positions[i] + n * occluder.rayOffset(positions[i]);
      int back = 0;
      for (const Vec3f& l : local) {
        Ray ray;
        ray.origin = origin;
        ray.dir = t * l.x + bt * l.y + n * l.z;
        const Hit h = occluder.intersect(ray);
        if (!h.hit) continue;
        const auto& tri = mesh.triangles[h.triangle];
        const Vec3f p0 = mesh.positions[tri[0]];
        const Vec3f g = cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
        back += dot(g, ray.dir) > 0.0f;
      }
      inside[i] = back * 2 > kValidityProbeRays;
    }
  });
  return inside;
}

}  // namespace prt
