// OBJ loading: the GAMES202 vertex order, no welding of differing normals/UVs, materials and
// textures to albedo, and one-line errors.

#include <gtest/gtest.h>

#include "fixtures.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/load.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"
#include "support/hardening.hpp"

namespace prt {
namespace {

using test::TempDir;

const char* kOrderObj = R"(# vertex order fixture
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
vt 0 0
vt 1 0
vt 1 1
vn 0 0 1
vn 0 0 -1
f 3/3/1 1/1/1 2/2/1
f 1/1/1 3/3/1 4/2/1 5/1/2
f 1/1/2 2/2/1 3/3/1
f -5/-3/-2 -4/-2/-1 -1/-1/-1
)";

TEST(ObjLoader, VertexOrderIsFirstAppearanceOfIndexTriples) {
  TempDir dir;
  LoadReport report;
  const Mesh m = loadMesh(dir.write("order.obj", kOrderObj), &report);
  // Triples (position, uv, normal), 0-based, in order of first appearance:
  //   face 1: (2,2,0)->0 (0,0,0)->1 (1,1,0)->2
  //   face 2: (0,0,0)=1 (2,2,0)=0 (3,1,0)->3 (4,0,1)->4      quad -> (1,0,3) (1,3,4)
  //   face 3: (0,0,1)->5 (same position as vertex 1, other normal: not welded) (1,1,0)=2 (2,2,0)=0
  //   face 4: negative indices (0,0,0)=1 (1,1,1)->6 (4,2,1)->7
  const std::vector<int> pos = {2, 0, 1, 3, 4, 0, 1, 4};
  const std::vector<int> uv = {2, 0, 1, 1, 0, 0, 1, 2};
  const std::vector<int> nrm = {0, 0, 0, 0, 1, 1, 1, 1};
  const Vec3f P[5] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}};
  const Vec2f T[3] = {{0, 0}, {1, 0}, {1, 1}};
  const Vec3f N[2] = {{0, 0, 1}, {0, 0, -1}};
  ASSERT_EQ(m.vertexCount(), pos.size());
  ASSERT_EQ(m.uvs.size(), pos.size());
  for (std::size_t v = 0; v < pos.size(); ++v) {
    EXPECT_EQ(m.positions[v], P[pos[v]]) << v;
    EXPECT_EQ(m.uvs[v].x, T[uv[v]].x) << v;
    EXPECT_EQ(m.uvs[v].y, T[uv[v]].y) << v;
    EXPECT_EQ(m.normals[v], N[nrm[v]]) << v;
  }
  const std::vector<std::array<std::uint32_t, 3>> tris = {
      {0, 1, 2}, {1, 0, 3}, {1, 3, 4}, {5, 2, 0}, {1, 6, 7}};
  EXPECT_EQ(m.triangles, tris);
  EXPECT_EQ(report.polygonsTriangulated, 1u);
  EXPECT_EQ(report.computedNormals, 0u);
  EXPECT_FALSE(m.hasAlbedo());  // no materials
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].name, "order");
  EXPECT_EQ(m.parts[0].triangleCount, 5u);
}

TEST(ObjLoader, MaterialsAndTexturesGiveLinearAlbedo) {
  TempDir dir;
  // A 2x2 texture whose texels are exact sRGB codes: top-left 200, top-right 50, bottom-left
  // 128, bottom-right 10 (grey), written through the image module.
  image::Image tex(2, 2);
  const int codes[2][2] = {{200, 50}, {128, 10}};  // [row][col], row 0 = top
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) tex.at(x, y) = Rgb(image::srgb8ToLinear(std::uint8_t(codes[y][x])));
  image::WriteOptions wo;
  wo.toneMap = image::ToneMap::Clamp;
  image::writeImage(dir.file("tex.png"), tex, wo);
  dir.write("m.mtl",
            "newmtl red\nKd 0.5 0.25 0.125\nnewmtl textured\nKd 0.5 1 1\nmap_Kd tex.png\n");
  dir.write("m.obj", R"(mtllib m.mtl
v 0 0 0
v 1 0 0
v 0 1 0
v 1 1 0
vt 0.25 0.75
vt 0.75 0.75
vt 0.25 0.25
vt 0.75 0.25
usemtl red
f 1/1 2/2 3/3
usemtl textured
f 2/2 4/4 3/3
f 4/4 2/1 3/3
)");
  const Mesh m = loadMesh(dir.file("m.obj"));
  ASSERT_TRUE(m.hasAlbedo());
  ASSERT_EQ(m.vertexCount(), 5u);  // (2,2) (4,4) and (2,1) are distinct triples
  const auto lin = [](int code) { return image::srgb8ToLinear(std::uint8_t(code)); };
  // Vertices 0-2 first appear in the red face: Kd only.
  for (int v = 0; v < 3; ++v) EXPECT_EQ(m.albedo[v], (Rgb{0.5f, 0.25f, 0.125f})) << v;
  // Vertex 3 (position 4, uv (0.75, 0.25): bottom-right texel, OBJ v points up).
  const Rgb e3 = Rgb{0.5f, 1, 1} * lin(10);
  // Vertex 4 (position 2, uv (0.25, 0.75): top-left texel).
  const Rgb e4 = Rgb{0.5f, 1, 1} * lin(200);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(m.albedo[3][k], e3[k], 2e-3f);
    EXPECT_NEAR(m.albedo[4][k], e4[k], 2e-3f);
  }
  // The decode is sRGB, not linear: 200/255 would be 0.784, sRGB-decoded it is 0.578.
  EXPECT_LT(m.albedo[4].y, 0.7f);
}

TEST(ObjLoader, ComputesNormalsWhenAbsent) {
  TempDir dir;
  // Two triangles of the plane z = 2 wound counter-clockwise seen from +z.
  const Mesh m = loadMesh(dir.write("p.obj", "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\nf 1 2 3 4\n"));
  ASSERT_EQ(m.normals.size(), 4u);
  for (const Vec3f& n : m.normals) EXPECT_EQ(n, (Vec3f{0, 0, 1}));
}

std::string errorOf(const std::string& path) {
  return test::errorOf([&] { loadMesh(path); });
}

TEST(ObjLoader, BadFilesGiveOneLineErrors) {
  TempDir dir;
  const std::string past = dir.write("past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
  EXPECT_EQ(errorOf(past), past + ": face 2 references vertex 9 (mesh has 3)");
  const std::string nan = dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(errorOf(nan), nan + ": line 2: vertex coordinate 'nan' is not a finite number");
  const std::string pts = dir.write("pts.obj", "v 0 0 0\nv 1 0 0\n");
  EXPECT_NE(errorOf(pts).find("has no faces"), std::string::npos);
  const std::string empty = dir.write("empty.obj", "");
  EXPECT_EQ(errorOf(empty), empty + ": has no vertices");
  const std::string flat = dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n");
  EXPECT_EQ(errorOf(flat), flat + ": all 2 triangles have zero area");
  const std::string missing = dir.file("missing.obj");
  EXPECT_NE(errorOf(missing).find(missing + ": "), std::string::npos);
  const std::string unknown = dir.write("mesh.stl", "solid");
  EXPECT_NE(errorOf(unknown).find("unknown extension .stl"), std::string::npos);
  for (const std::string& e : {errorOf(past), errorOf(nan), errorOf(missing)})
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(ObjLoader, DegenerateTrianglesAreSkippedAndCounted) {
  TempDir dir;
  LoadReport r;
  const Mesh m = loadMesh(
      dir.write("d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 3 3 1\n"), &r);
  EXPECT_EQ(m.triangleCount(), 1u);
  EXPECT_EQ(r.degenerateTriangles, 2u);
  EXPECT_EQ(r.unusedVertices, 1u);  // vertex 4 is only on a degenerate triangle
  EXPECT_FALSE(r.warnings.empty());
  EXPECT_EQ(m.parts.at(0).triangleCount, 1u);
}

}  // namespace
}  // namespace prt
