// Tests of the Embree occluder: no self-intersection with rayOffset (and that a zero offset does
// self-intersect, so the check can fail), rays that must hit do, hits are consistent with their
// barycentrics and t, the batched query equals the single-ray query, errors are prt::Error.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"

namespace prt {
namespace {

/// Uniform direction in the hemisphere around unit n.
Vec3f hemisphere(const Vec3f& n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float z = u(rng), phi = 2.0f * kPif * u(rng);
  const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
  Vec3f t, b;
  orthonormalBasis(n, t, b);
  return normalize(t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + n * z);
}

/// Rays leaving random interior points of random triangles into the hemisphere of the
/// triangle's geometric normal, offset by scale * rayOffset(p). Returns how many are occluded.
/// On a convex closed surface or a plane none may hit anything.
int selfHits(const Mesh& mesh, const Occluder& occ, float scale, int rays, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::uniform_int_distribution<std::size_t> pick(0, mesh.triangles.size() - 1);
  int hits = 0;
  for (int k = 0; k < rays; ++k) {
    const auto& tri = mesh.triangles[pick(rng)];
    const Vec3f p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]],
                p2 = mesh.positions[tri[2]];
    float b1 = u(rng), b2 = u(rng);
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const Vec3f p = p0 * (1 - b1 - b2) + p1 * b1 + p2 * b2;
    const Vec3f ng = normalize(cross(p1 - p0, p2 - p0));
    Ray r;
    r.origin = p + ng * (scale * occ.rayOffset(p));
    r.dir = hemisphere(ng, rng);
    hits += occ.occluded(r) ? 1 : 0;
  }
  return hits;
}

Mesh transformed(Mesh m, float scale, Vec3f shift) {
  // A rotation that is not axis-aligned, so coordinates are not exactly representable.
  const Mat3f rot = rotationEulerXYZ(23.0, -41.0, 67.0).cast<float>();
  for (auto& p : m.positions) p = rot * p * scale + shift;
  for (auto& n : m.normals) n = normalize(rot * n);
  return m;
}

TEST(EmbreeOccluder, SphereDoesNotShadowItself) {
  for (const auto& [scale, shift] : {std::pair{1.0f, Vec3f{0.0f}}, std::pair{0.01f, Vec3f{0.0f}},
                                     std::pair{3.0f, Vec3f{1000.0f, -500.0f, 250.0f}}}) {
    const Mesh m = transformed(builtinScene("builtin:sphere?subdiv=5"), scale, shift);
    const auto occ = makeEmbreeOccluder(m);
    EXPECT_EQ(selfHits(m, *occ, 1.0f, 40000, 1), 0) << "scale " << scale << " shift " << shift.x;
  }
}

TEST(EmbreeOccluder, ZeroOffsetDoesSelfIntersect) {
  // The counter-check: without the offset, rays from interpolated points do re-hit their own
  // triangle, so the test above measures something.
  const Mesh m = transformed(builtinScene("builtin:sphere?subdiv=5"), 3.0f, {1000, -500, 250});
  const auto occ = makeEmbreeOccluder(m);
  EXPECT_GT(selfHits(m, *occ, 0.0f, 40000, 2), 100);
}

TEST(EmbreeOccluder, PlaneDoesNotShadowItself) {
  // The plane of sphere-plane alone (part 0), tilted and moved off the origin.
  Mesh scene = builtinScene("builtin:sphere-plane?grid=64");
  Mesh plane;
  const MeshPart& part = scene.parts.at(0);
  ASSERT_EQ(part.name, "plane");
  plane.positions.assign(scene.positions.begin() + part.firstVertex,
                         scene.positions.begin() + part.firstVertex + part.vertexCount);
  plane.triangles.assign(scene.triangles.begin() + part.firstTriangle,
                         scene.triangles.begin() + part.firstTriangle + part.triangleCount);
  plane = transformed(plane, 7.0f, {3.3f, 51.7f, -12.9f});
  const auto occ = makeEmbreeOccluder(plane);
  EXPECT_EQ(selfHits(plane, *occ, 1.0f, 40000, 3), 0);
  // From the vertices too (where neighbouring triangles meet).
  std::mt19937 rng(4);
  const Vec3f n = normalize(
      cross(plane.positions[plane.triangles[0][1]] - plane.positions[plane.triangles[0][0]],
            plane.positions[plane.triangles[0][2]] - plane.positions[plane.triangles[0][0]]));
  int hits = 0;
  for (const Vec3f& p : plane.positions)
    for (int k = 0; k < 8; ++k) {
      Ray r{p + n * occ->rayOffset(p), hemisphere(n, rng)};
      hits += occ->occluded(r);
    }
  EXPECT_EQ(hits, 0);
}

TEST(EmbreeOccluder, RaysUpFromPlaneHitSphere) {
  const float r = 0.5f, h = 1.0f;
  const Mesh m = builtinScene("builtin:sphere-plane?r=0.5&h=1");
  const auto occ = makeEmbreeOccluder(m);
  const MeshPart& sphere = m.parts.at(1);
  ASSERT_EQ(sphere.name, "sphere");
  // The icosphere's facets lie inside the sphere by at most the sagitta of its longest edge.
  const float sag = r * 0.01f;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int inside = 0, outside = 0;
  for (int k = 0; k < 4000; ++k) {
    const float x = u(rng), z = u(rng);
    const float d = std::sqrt(x * x + z * z);
    const Vec3f o{x, 0.0f, z};
    Ray ray{o + Vec3f{0, 1, 0} * occ->rayOffset(o), {0, 1, 0}};
    const Hit hit = occ->intersect(ray);
    if (d < 0.95f * r) {
      ++inside;
      ASSERT_TRUE(hit.hit) << x << " " << z;
      EXPECT_TRUE(occ->occluded(ray));
      ASSERT_GE(hit.triangle, sphere.firstTriangle);
      ASSERT_LT(hit.triangle, sphere.firstTriangle + sphere.triangleCount);
      // Analytic: the lower cap of the sphere at distance d from the axis.
      const float tExact = h - std::sqrt(r * r - d * d) - ray.origin.y;
      EXPECT_NEAR(hit.t, tExact, sag / std::sqrt(1 - (d / r) * (d / r)));
      // The barycentric interpolation of the hit triangle's vertices gives the hit point.
      const auto& tri = m.triangles[hit.triangle];
      const Vec3f p = m.positions[tri[0]] * (1 - hit.u - hit.v) + m.positions[tri[1]] * hit.u +
                      m.positions[tri[2]] * hit.v;
      const Vec3f q = ray.origin + ray.dir * hit.t;
      EXPECT_NEAR(length(p - q), 0.0f, 1e-5f);
      // A ray stopped short of the sphere is not occluded.
      Ray shortRay = ray;
      shortRay.tfar = hit.t * 0.99f;
      EXPECT_FALSE(occ->occluded(shortRay));
    } else if (d > 1.05f * r) {
      ++outside;
      EXPECT_FALSE(hit.hit);
      EXPECT_FALSE(occ->occluded(ray));
    }
  }
  EXPECT_GT(inside, 100);
  EXPECT_GT(outside, 100);
}

TEST(EmbreeOccluder, BatchedAndThreadedEqualSingle) {
  const Mesh m = builtinScene("builtin:cornell?grid=16");
  const auto occ = makeEmbreeOccluder(m);
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Ray> rays(10007);
  for (auto& r : rays) {
    const std::size_t v =
        std::min<std::size_t>(m.vertexCount() - 1, std::size_t(u(rng) * m.vertexCount()));
    r.origin = m.positions[v] + m.normals[v] * occ->rayOffset(m.positions[v]);
    r.dir = hemisphere(m.normals[v], rng);
    if (u(rng) < 0.3f) r.tfar = u(rng) * 0.5f;
  }
  std::vector<std::uint8_t> batched(rays.size()), threaded(rays.size());
  occ->occluded(rays, batched);
  parallelFor(rays.size(), 64, [&](std::size_t b, std::size_t e) {
    occ->occluded(std::span<const Ray>(rays).subspan(b, e - b),
                  std::span(threaded).subspan(b, e - b));
  });
  int occludedCount = 0;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const bool single = occ->occluded(rays[k]);
    ASSERT_EQ(batched[k], single ? 1 : 0) << k;
    ASSERT_EQ(threaded[k], batched[k]) << k;
    occludedCount += single;
  }
  // Inside an open box both outcomes must occur.
  EXPECT_GT(occludedCount, 1000);
  EXPECT_LT(occludedCount, int(rays.size()) - 1000);
  EXPECT_GT(occ->memoryBytes(), m.triangleCount() * 12);

  // Closest hits in streams (rtcIntersect1M) are the single-ray query's, field for field.
  std::vector<Hit> hits(rays.size());
  occ->intersect(rays, hits);
  int hitCount = 0;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const Hit single = occ->intersect(rays[k]);
    ASSERT_EQ(hits[k].hit, single.hit) << k;
    hitCount += single.hit;
    if (!single.hit) continue;
    ASSERT_EQ(hits[k].triangle, single.triangle) << k;
    ASSERT_EQ(hits[k].t, single.t) << k;
    ASSERT_EQ(hits[k].u, single.u) << k;
    ASSERT_EQ(hits[k].v, single.v) << k;
  }
  EXPECT_EQ(hitCount, occludedCount);  // every ray that is blocked has a closest hit
}

TEST(EmbreeOccluder, BadMeshesThrow) {
  Mesh empty;
  empty.source = "empty.obj";
  try {
    makeEmbreeOccluder(empty);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty.obj"), std::string::npos);
  }
  Mesh bad;
  bad.source = "bad.ply";
  bad.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  bad.triangles = {{0, 1, 3}};
  EXPECT_THROW(makeEmbreeOccluder(bad), Error);
  bad.triangles = {{0, 1, 2}};
  bad.positions[1].x = std::nanf("");
  EXPECT_THROW(makeEmbreeOccluder(bad), Error);
  bad.positions[1].x = 1;
  EXPECT_NO_THROW(makeEmbreeOccluder(bad));
}

}  // namespace
}  // namespace prt
