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
      // The rule (more than half the rays hit a back face) is settled as soon as either side
      // holds a majority (issue 37: the probe was most of a quick per-texel bake). An outside
      // point — most are — settles with its first half of the rays if none hits a back face,
      // so they go as one stream; the rest, only when that did not settle it, as another. The
      // verdict is the one all the rays give.
      constexpr int kMajority = kValidityProbeRays / 2 + 1;
      constexpr int kFirst = kValidityProbeRays - kMajority + 1;  // enough to settle "outside"
      std::array<Ray, kValidityProbeRays> rays;
      std::array<Hit, kValidityProbeRays> hits;
      for (int k = 0; k < kValidityProbeRays; ++k) {
        rays[std::size_t(k)].origin = origin;
        rays[std::size_t(k)].dir = t * local[std::size_t(k)].x + bt * local[std::size_t(k)].y +
                                   n * local[std::size_t(k)].z;
      }
      int back = 0;
      const auto castRays = [&](int from, int to) {
        occluder.intersect(std::span<const Ray>(rays.data() + from, std::size_t(to - from)),
                           std::span<Hit>(hits.data() + from, std::size_t(to - from)));
        for (int k = from; k < to; ++k) {
          const Hit& h = hits[std::size_t(k)];
          if (!h.hit) continue;
          const auto& tri = mesh.triangles[h.triangle];
          const Vec3f p0 = mesh.positions[tri[0]];
          const Vec3f g = cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
          back += dot(g, rays[std::size_t(k)].dir) > 0.0f;
        }
      };
      castRays(0, kFirst);
      if (back > 0) castRays(kFirst, kValidityProbeRays);
      inside[i] = back >= kMajority;
    }
  });
  return inside;
}

std::vector<std::uint8_t> insideGeometryAllAround(const Mesh& mesh, const Occluder& occluder,
                                                  std::span<const Vec3f> positions) {
  // Inside over the hemisphere about +Z first; only the points inside there are tested about −Z
  // (most points are outside: half the rays of testing both everywhere).
  const std::vector<Vec3f> up(positions.size(), Vec3f(0.0f, 0.0f, 1.0f));
  std::vector<std::uint8_t> inside = insideGeometry(mesh, occluder, positions, up);
  std::vector<Vec3f> suspects;
  for (std::size_t i = 0; i < inside.size(); ++i)
    if (inside[i]) suspects.push_back(positions[i]);
  if (suspects.empty()) return inside;
  const std::vector<Vec3f> down(suspects.size(), Vec3f(0.0f, 0.0f, -1.0f));
  const std::vector<std::uint8_t> below = insideGeometry(mesh, occluder, suspects, down);
  std::size_t k = 0;
  for (std::uint8_t& in : inside)
    if (in) in = below[k++];
  return inside;
}

}  // namespace prt
