// PLY (ASCII, binary little/big endian, gzip) and OFF loading: every encoding of the same
// tetrahedron loads to the same mesh; colours are sRGB-decoded; malformed files give one line.

#include <gtest/gtest.h>
#include <zlib.h>

#include <bit>
#include <cstring>

#include "fixtures.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/load.hpp"
#include "prt/image/color.hpp"
#include "support/hardening.hpp"

namespace prt {
namespace {

using test::TempDir;

const Vec3f kP[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::uint8_t kRgb[4][3] = {{255, 0, 0}, {0, 128, 0}, {0, 0, 64}, {10, 200, 30}};
// Outward-facing (counter-clockwise seen from outside) faces of the tetrahedron.
const std::uint32_t kF[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

std::string header(const char* format, int faces = 4) {
  return std::string("ply\nformat ") + format +
         " 1.0\ncomment test\nelement vertex 4\nproperty float x\nproperty float y\nproperty "
         "float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face " +
         std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string asciiPly() {
  std::string s = header("ascii");
  for (int v = 0; v < 4; ++v)
    s += std::to_string(kP[v].x) + " " + std::to_string(kP[v].y) + " " + std::to_string(kP[v].z) +
         " " + std::to_string(kRgb[v][0]) + " " + std::to_string(kRgb[v][1]) + " " +
         std::to_string(kRgb[v][2]) + "\n";
  for (auto& f : kF)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
         "\n";
  return s;
}

template <typename T>
void put(std::string& s, T x, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  if (big == (std::endian::native == std::endian::little)) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string binaryPly(bool big) {
  std::string s = header(big ? "binary_big_endian" : "binary_little_endian");
  for (int v = 0; v < 4; ++v) {
    for (int k = 0; k < 3; ++k) put(s, kP[v][k], big);
    for (int k = 0; k < 3; ++k) put(s, kRgb[v][k], big);
  }
  for (auto& f : kF) {
    put(s, std::uint8_t(3), big);
    for (auto i : f) put(s, std::int32_t(i), big);
  }
  return s;
}

using test::gzipOf;

void expectTetrahedron(const Mesh& m, bool colours) {
  ASSERT_EQ(m.vertexCount(), 4u);
  ASSERT_EQ(m.triangleCount(), 4u);
  for (int v = 0; v < 4; ++v) EXPECT_EQ(m.positions[v], kP[v]);
  for (int f = 0; f < 4; ++f)
    EXPECT_EQ(m.triangles[f], (std::array<std::uint32_t, 3>{kF[f][0], kF[f][1], kF[f][2]}));
  ASSERT_EQ(m.hasAlbedo(), colours);
  if (colours) {
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(m.albedo[v][k], image::srgb8ToLinear(kRgb[v][k]));
  }
  // Computed normals point away from the centroid.
  const Vec3f c{0.25f, 0.25f, 0.25f};
  for (int v = 0; v < 4; ++v) EXPECT_GT(dot(m.normals[v], m.positions[v] - c), 0.0f) << v;
}

TEST(PlyLoader, AllEncodingsGiveTheSameMesh) {
  TempDir dir;
  expectTetrahedron(loadMesh(dir.write("a.ply", asciiPly())), true);
  expectTetrahedron(loadMesh(dir.write("le.ply", binaryPly(false))), true);
  expectTetrahedron(loadMesh(dir.write("be.ply", binaryPly(true))), true);
  expectTetrahedron(loadMesh(dir.write("le.ply.gz", gzipOf(binaryPly(false)))), true);
  expectTetrahedron(loadMesh(dir.write("a.PLY.GZ", gzipOf(asciiPly()))), true);
}

TEST(PlyLoader, NormalsAndExtraElementsAndQuads) {
  TempDir dir;
  const std::string s =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty "
      "double z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty list uchar "
      "uchar junk\nelement face 1\nproperty uchar flags\nproperty list uchar uint vertex_indices\n"
      "element edge 1\nproperty int a\nproperty int b\nend_header\n"
      "0 0 0 0 0 2 2 7 7\n1 0 0 0 0 2 0\n1 1 0 0 0 2 0\n0 1 0 0 0 2 1 9\n5 4 0 1 2 3\n0 1\n";
  LoadReport r;
  const Mesh m = loadMesh(dir.write("q.ply", s), &r);
  ASSERT_EQ(m.triangleCount(), 2u);
  EXPECT_EQ(r.polygonsTriangulated, 1u);
  EXPECT_EQ(r.computedNormals, 0u);
  for (const Vec3f& n : m.normals) EXPECT_EQ(n, (Vec3f{0, 0, 1}));  // normalised file normals
}

std::string errorOf(const std::string& path) {
  return test::errorOf([&] { loadMesh(path); });
}

TEST(PlyLoader, MalformedFilesGiveOneLineErrors) {
  TempDir dir;
  const std::string bin = binaryPly(false);
  const std::string cut = dir.write("cut.ply", bin.substr(0, bin.size() - 5));
  EXPECT_NE(errorOf(cut).find("truncated"), std::string::npos) << errorOf(cut);
  std::string lying = binaryPly(false);
  lying.replace(lying.find("vertex 4"), 8, "vertex 400000000");
  const std::string lie = dir.write("lie.ply", lying);
  EXPECT_NE(errorOf(lie).find("claims 400000000 records"), std::string::npos) << errorOf(lie);
  std::string badIndex = asciiPly();
  badIndex.replace(badIndex.rfind("3 1 2 3"), 7, "3 1 2 9");
  const std::string bi = dir.write("bi.ply", badIndex);
  EXPECT_EQ(errorOf(bi), bi + ": face 3 references vertex 9 (mesh has 4)");
  const std::string noEnd = dir.write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n");
  EXPECT_NE(errorOf(noEnd).find("end_header"), std::string::npos);
  const std::string badType = dir.write(
      "type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n1\n");
  EXPECT_NE(errorOf(badType).find("header line 4"), std::string::npos) << errorOf(badType);
  const std::string cloud = dir.write(
      "cloud.ply",
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float "
      "z\nend_header\n0 0 0\n1 1 1\n");
  EXPECT_NE(errorOf(cloud).find("has no faces"), std::string::npos);
  std::string nan = asciiPly();
  nan.replace(nan.find("1.000000 0.000000 0.000000"), 8, "nan     ");
  const std::string np = dir.write("nan.ply", nan);
  EXPECT_NE(errorOf(np).find("vertex 1 has a non-finite coordinate"), std::string::npos)
      << errorOf(np);
  const std::string gz = dir.write("bad.ply.gz", gzipOf(asciiPly()).substr(0, 40));
  EXPECT_NE(errorOf(gz).find("gzip"), std::string::npos) << errorOf(gz);
  for (const auto& p : {cut, lie, bi, noEnd, badType, cloud, np, gz})
    EXPECT_EQ(errorOf(p).find('\n'), std::string::npos);
}

TEST(OffLoader, CubeOfQuadsHasTriangulationIndependentNormals) {
  TempDir dir;
  // A unit cube of 6 quads. After fan triangulation each corner lies in one or two triangles of
  // each face; angle weighting (Thürmer & Wüthrich) still gives the symmetric corner normal
  // (±1, ±1, ±1)/√3, which area- or count-weighting would not.
  const std::string off = R"(OFF
# cube
8 6 12
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
4 0 3 2 1
4 4 5 6 7
4 0 1 5 4
4 2 3 7 6
4 0 4 7 3
4 1 2 6 5
)";
  LoadReport r;
  const Mesh m = loadMesh(dir.write("cube.off", off), &r);
  ASSERT_EQ(m.triangleCount(), 12u);
  EXPECT_EQ(r.polygonsTriangulated, 6u);
  for (std::size_t v = 0; v < 8; ++v) {
    const Vec3f expect = normalize(m.positions[v] * 2.0f - Vec3f(1.0f));
    EXPECT_NEAR(length(m.normals[v] - expect), 0.0f, 1e-6f) << v;
  }
}

TEST(OffLoader, ColoursAndErrors) {
  TempDir dir;
  const Mesh c = loadMesh(dir.write(
      "c.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 128 0 255\n0 1 0 0 0 64 255\n3 0 1 2\n"));
  ASSERT_TRUE(c.hasAlbedo());
  EXPECT_FLOAT_EQ(c.albedo[1].y, image::srgb8ToLinear(128));
  const std::string bi = dir.write("bi.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
  EXPECT_EQ(errorOf(bi), bi + ": face 0 references vertex 5 (mesh has 3)");
  const std::string tr = dir.write("tr.off", "OFF\n3000000 1 0\n0 0 0\n1 0 0\n");
  EXPECT_NE(errorOf(tr).find("do not fit the file size"), std::string::npos) << errorOf(tr);
  const std::string tr2 = dir.write("tr2.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1");
  EXPECT_NE(errorOf(tr2).find("unexpected end of file"), std::string::npos) << errorOf(tr2);
  const std::string hd = dir.write("hd.off", "PLY\n");
  EXPECT_NE(errorOf(hd).find("not an OFF file"), std::string::npos);
  const std::string word = dir.write("w.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n");
  EXPECT_NE(errorOf(word).find("line 4"), std::string::npos) << errorOf(word);
}

}  // namespace
}  // namespace prt
