// Builtin scenes and scene merging: valid meshes (unit normals, indices in range, no zero-area
// triangles, parts covering everything), the documented geometry and parameters, closed and
// outward-facing spheres, inward-facing Cornell walls, and angle-weighted normals on a sphere.

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "fixtures.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/normals.hpp"
#include "prt/geometry/texel_sampling.hpp"

namespace prt {
namespace {

void expectValid(const Mesh& m) {
  ASSERT_GT(m.triangleCount(), 0u);
  ASSERT_EQ(m.normals.size(), m.vertexCount());
  ASSERT_EQ(m.albedo.size(), m.vertexCount());
  EXPECT_LE(m.vertexCount(), 50000u);
  for (const Vec3f& n : m.normals) ASSERT_NEAR(length(n), 1.0f, 1e-5f);
  for (const auto& t : m.triangles) {
    for (auto i : t) ASSERT_LT(i, m.vertexCount());
    ASSERT_FALSE(isDegenerateTriangle(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
    // Counter-clockwise = front: the face normal agrees with the vertex normals.
    const Vec3f fn =
        cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    for (auto i : t) ASSERT_GT(dot(fn, m.normals[i]), 0.0f);
  }
  std::uint32_t v = 0, t = 0;
  for (const MeshPart& p : m.parts) {
    EXPECT_EQ(p.firstVertex, v);
    EXPECT_EQ(p.firstTriangle, t);
    v += p.vertexCount;
    t += p.triangleCount;
    for (std::uint32_t k = p.firstTriangle; k < p.firstTriangle + p.triangleCount; ++k)
      for (auto i : m.triangles[k])
        ASSERT_TRUE(i >= p.firstVertex && i < p.firstVertex + p.vertexCount);
  }
  EXPECT_EQ(v, m.vertexCount());
  EXPECT_EQ(t, m.triangleCount());
}

TEST(Builtin, AllScenesAreValid) {
  for (const std::string& name : builtinSceneNames()) {
    SCOPED_TRACE(name);
    const Mesh m = builtinScene("builtin:" + name);
    expectValid(m);
    EXPECT_EQ(m.source, "builtin:" + name);
    // loadMesh accepts the same name.
    EXPECT_EQ(loadMesh("builtin:" + name).triangleCount(), m.triangleCount());
  }
}

TEST(Builtin, SphereIsClosedAndOnTheSphere) {
  const Mesh m = builtinScene("sphere?subdiv=4&r=2");
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  // Closed and consistently oriented: every directed edge once, its reverse once.
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u);
  }
  EXPECT_EQ(m.vertexCount(), 10u * 256u + 2u);  // 10·4^s + 2
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    EXPECT_NEAR(length(m.positions[v]), 2.0f, 1e-5f);
    EXPECT_NEAR(length(m.normals[v] - m.positions[v] / 2.0f), 0.0f, 1e-5f);
  }
}

TEST(Builtin, SpherePlaneFollowsItsParameters) {
  const Mesh m = builtinScene("builtin:sphere-plane?r=0.25&h=2&size=3&grid=10");
  ASSERT_EQ(m.parts.size(), 2u);
  const MeshPart& plane = m.parts[0];
  const MeshPart& sphere = m.parts[1];
  EXPECT_EQ(plane.name, "plane");
  EXPECT_EQ(plane.triangleCount, 200u);
  float lo = 1e9f, hi = -1e9f;
  for (std::uint32_t v = sphere.firstVertex; v < sphere.firstVertex + sphere.vertexCount; ++v) {
    lo = std::min(lo, m.positions[v].y);
    hi = std::max(hi, m.positions[v].y);
  }
  EXPECT_NEAR(lo, 1.75f, 1e-5f);
  EXPECT_NEAR(hi, 2.25f, 1e-5f);
  for (std::uint32_t v = plane.firstVertex; v < plane.firstVertex + plane.vertexCount; ++v) {
    EXPECT_EQ(m.positions[v].y, 0.0f);
    EXPECT_LE(std::fabs(m.positions[v].x), 3.0f);
    EXPECT_EQ(m.normals[v], (Vec3f{0, 1, 0}));
  }
}

TEST(Builtin, PlaneFollowsItsParameters) {
  const Mesh m = builtinScene("builtin:plane?y=-0.5&size=2&grid=4&albedo=0.3");
  expectValid(m);
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.triangleCount(), 32u);
  EXPECT_EQ(m.vertexCount(), 25u);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    EXPECT_EQ(m.positions[v].y, -0.5f);
    EXPECT_LE(std::fabs(m.positions[v].z), 2.0f);
    EXPECT_EQ(m.normals[v], (Vec3f{0, 1, 0}));
    EXPECT_EQ(m.albedo[v], Rgb(0.3f));
  }
  EXPECT_THROW(builtinScene("builtin:plane?size=0"), Error);
}

TEST(Builtin, CornellWallsFaceInwardAndAreColoured) {
  const Mesh m = builtinScene("cornell");
  std::map<std::string, MeshPart> parts;
  for (const auto& p : m.parts) parts[p.name] = p;
  ASSERT_EQ(parts.count("left-wall"), 1u);
  ASSERT_EQ(parts.count("right-wall"), 1u);
  const Vec3f centre{0, 1, 0};
  for (const char* w : {"floor", "ceiling", "back-wall", "left-wall", "right-wall"}) {
    const MeshPart& p = parts.at(w);
    for (std::uint32_t v = p.firstVertex; v < p.firstVertex + p.vertexCount; ++v)
      ASSERT_GT(dot(m.normals[v], centre - m.positions[v]), 0.0f) << w;
  }
  const Rgb left = m.albedo[parts["left-wall"].firstVertex];
  const Rgb right = m.albedo[parts["right-wall"].firstVertex];
  EXPECT_GT(left.x, 5 * left.y);    // red
  EXPECT_GT(right.y, 2 * right.x);  // green
}

TEST(Builtin, BadNamesAndParametersThrow) {
  EXPECT_THROW(builtinScene("builtin:teapot"), Error);
  EXPECT_THROW(builtinScene("builtin:sphere?radius=2"), Error);
  EXPECT_THROW(builtinScene("builtin:sphere?r=abc"), Error);
  EXPECT_THROW(builtinScene("builtin:sphere?subdiv=2.5"), Error);
  EXPECT_THROW(builtinScene("builtin:sphere-plane?r=1&h=0.5"), Error);
  try {
    builtinScene("builtin:nope");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("builtin:nope: unknown builtin scene"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("sphere-plane"), std::string::npos);  // lists the names
  }
}

TEST(Normals, AngleWeightedNormalsOfASphereConvergeToRadial) {
  const auto worstError = [](int subdiv) {
    Mesh m = builtinScene("sphere?subdiv=" + std::to_string(subdiv));
    m.normals.clear();
    computeVertexNormals(m);
    double worst = 0;
    for (std::size_t v = 0; v < m.vertexCount(); ++v)
      worst = std::max(worst, double(length(m.normals[v] - normalize(m.positions[v]))));
    return worst;
  };
  const double e3 = worstError(3), e4 = worstError(4);
  EXPECT_GT(e4, 0.0);  // computed, not copied
  EXPECT_LT(e4, 0.01);
  // Halving the edges at least halves the error: O(h) on the icosphere's irregular (valence 5
  // and 6) neighbourhoods, as for any vertex-normal estimate on irregular meshes (Meek & Walton
  // 2000), O(h^2) only on regular ones.
  EXPECT_GT(e3 / e4, 1.8);
}

TEST(Scene, MergesFilesAndBuiltinsIntoParts) {
  test::TempDir dir;
  const std::string obj = dir.write("tri.obj", "v 0 5 0\nv 1 5 0\nv 0 6 0\nf 1 2 3\n");
  LoadReport r;
  const Mesh s = loadScene({"builtin:sphere?subdiv=1", obj}, &r);
  const Mesh sphere = builtinScene("sphere?subdiv=1");
  ASSERT_EQ(s.parts.size(), 2u);
  EXPECT_EQ(s.parts[1].name, "tri");
  EXPECT_EQ(s.parts[1].firstVertex, sphere.vertexCount());
  EXPECT_EQ(s.parts[1].firstTriangle, sphere.triangleCount());
  EXPECT_EQ(s.vertexCount(), sphere.vertexCount() + 3);
  EXPECT_EQ(s.triangles.back(),
            (std::array<std::uint32_t, 3>{std::uint32_t(sphere.vertexCount()),
                                          std::uint32_t(sphere.vertexCount() + 1),
                                          std::uint32_t(sphere.vertexCount() + 2)}));
  // The OBJ has no material: its vertices get the default albedo next to the sphere's.
  ASSERT_EQ(s.albedo.size(), s.vertexCount());
  EXPECT_EQ(s.albedo.back(), Rgb(kDefaultAlbedo));
  EXPECT_EQ(s.source, "builtin:sphere?subdiv=1+" + obj);
  expectValid(s);
  EXPECT_THROW(loadScene({}), Error);
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

// The builtin scenes' lightmap UVs (issue 18): the plane and the Cornell box have one chart per
// grid (a wall, a block's face) packed into [0, 1]² at one texel density, valid lightmaps at
// any resolution from 64² (no texel centre in two charts); the sphere scenes have none (the
// icosphere shares its vertices: no seams).
TEST(BuiltinScenes, PlaneAndCornellHaveLightmapUvsAtOneDensity) {
  for (const char* name : {"builtin:plane?grid=8", "builtin:cornell?grid=10", "builtin:cornell"}) {
    SCOPED_TRACE(name);
    const Mesh m = builtinScene(name);
    ASSERT_EQ(m.lightmapUvs.size(), m.vertexCount());
    EXPECT_TRUE(m.uvs.empty());
    for (int res : {64, 256, 512}) EXPECT_NO_THROW(checkLightmapUvs(m, m.lightmapUvs, res, res, "lightmap"));
    // Texel density: UV area over world area, the same for every triangle.
    double lo = 1e30, hi = 0, uvArea = 0;
    for (const auto& t : m.triangles) {
      const Vec2f a = m.lightmapUvs[t[0]], b = m.lightmapUvs[t[1]], c = m.lightmapUvs[t[2]];
      const double uv = 0.5 * std::abs(double(b.x - a.x) * (c.y - a.y) - double(b.y - a.y) * (c.x - a.x));
      const double world = 0.5 * length(Vec3d(cross(m.positions[t[1]] - m.positions[t[0]],
                                                    m.positions[t[2]] - m.positions[t[0]])));
      lo = std::min(lo, uv / world);
      hi = std::max(hi, uv / world);
      uvArea += uv;
    }
    EXPECT_LT(hi / lo, 1.001) << "texel density varies";
    EXPECT_GT(uvArea, 0.35) << "the charts use too little of the lightmap";
  }
  EXPECT_TRUE(builtinScene("builtin:sphere?subdiv=1").lightmapUvs.empty());
  EXPECT_TRUE(builtinScene("builtin:sphere-plane?grid=4&subdiv=1").lightmapUvs.empty());
}

}  // namespace
}  // namespace prt
