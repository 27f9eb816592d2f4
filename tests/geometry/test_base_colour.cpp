// The base-colour texture (issue 18): glTF's baseColorTexture (a file beside the .gltf, or an
// image embedded in a .glb) and OBJ's map_Kd are kept as Mesh::baseColour — the file's sRGB
// codes, row 0 at v = 0 — with the albedo holding the factor alone (baseColorFactor, Kd); the
// lookup (sRGB decode, bilinear, repeat); what is sampled at the vertices instead (textures that
// differ between parts, scenes of several files); and a missing or corrupt texture: one warning
// naming it, the mesh loaded without it. Every file is written here, into a scratch folder.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>

#include "fixtures.hpp"
#include "prt/geometry/base_colour.hpp"
#include "prt/geometry/load.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"

namespace prt {
namespace {

using test::TempDir;

/// 2 × 2 codes, every texel and channel distinct: (x, y) row-major from the top row.
image::Srgb8Image twoByTwo() {
  image::Srgb8Image img;
  img.width = img.height = 2;
  img.rgb = {200, 10, 20, /**/ 30, 220, 40, /**/ 50, 60, 230, /**/ 128, 129, 130};
  return img;
}

Rgb linear(const image::Srgb8Image& img, int x, int y) {
  return {image::srgb8ToLinear(img.code(x, y, 0)), image::srgb8ToLinear(img.code(x, y, 1)),
          image::srgb8ToLinear(img.code(x, y, 2))};
}

std::string png(const image::Srgb8Image& img) {
  return image::encodePng(img, "test");
}

// A unit quad in y = 0 facing +Y: positions, normals, TEXCOORD_0 spanning [0, 1]², uint32 indices.
std::string quadData() {
  std::string b;
  const auto f = [&](float x) { b.append(reinterpret_cast<const char*>(&x), 4); };
  const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  for (const auto& q : p) f(q[0]), f(q[1]), f(q[2]);
  for (int v = 0; v < 4; ++v) f(0), f(1), f(0);
  const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const auto& q : uv) f(q[0]), f(q[1]);
  const std::uint32_t idx[6] = {0, 2, 1, 0, 3, 2};
  b.append(reinterpret_cast<const char*>(idx), 24);
  return b;  // 48 + 48 + 32 + 24 = 152 bytes
}

/// A glTF of the quad whose material has baseColorFactor (0.5, 0.25, 1) and `texture` (the JSON
/// of "images", or "" for none), its buffer `bufferUri` (or the GLB's BIN chunk when empty) with
/// `extraViews` appended to its bufferViews.
std::string quadJson(const std::string& bufferUri, std::size_t bytes, const std::string& images,
                     const std::string& extraViews = "") {
  const std::string uri = bufferUri.empty() ? "" : "\"uri\": \"" + bufferUri + "\", ";
  const std::string material =
      images.empty()
          ? R"({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1]}})"
          : R"({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1], "baseColorTexture": {"index": 0}}})";
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"name": "quad", "mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
 "materials": [)" +
         material + "]," + (images.empty() ? "" : images + R"(, "textures": [{"source": 0}],)") +
         R"( "buffers": [{)" + uri + "\"byteLength\": " + std::to_string(bytes) + R"(}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 128}, {"buffer": 0, "byteOffset": 128, "byteLength": 24})" +
         extraViews + R"(],
 "accessors": [
   {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 0, 1]},
   {"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},
   {"bufferView": 0, "byteOffset": 96, "componentType": 5126, "count": 4, "type": "VEC2"},
   {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}]})";
}

std::string glb(const std::string& j, const std::string& bin) {
  std::string js = j, b = bin;
  while (js.size() % 4) js += ' ';
  while (b.size() % 4) b += '\0';
  std::string out;
  const auto u32 = [&](std::uint32_t x) { out.append(reinterpret_cast<const char*>(&x), 4); };
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(std::uint32_t(12 + 8 + js.size() + 8 + b.size()));
  u32(std::uint32_t(js.size()));
  u32(0x4E4F534A);  // JSON
  out += js;
  u32(std::uint32_t(b.size()));
  u32(0x004E4942);  // BIN
  out += b;
  return out;
}

bool mentions(const LoadReport& r, const std::string& a, const std::string& b) {
  for (const std::string& w : r.warnings)
    if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
  return false;
}

void expectKeptTexture(const Mesh& m, const image::Srgb8Image& file) {
  ASSERT_TRUE(m.baseColour.has_value());
  EXPECT_EQ(m.baseColour->image, file);  // the file's codes, as they are (glTF: no flip)
  // The albedo is the factor alone: the texture multiplies per pixel, not at the vertices.
  ASSERT_EQ(m.albedo.size(), 4u);
  for (const Rgb& a : m.albedo) EXPECT_EQ(a, (Rgb{0.5f, 0.25f, 1.0f}));
  ASSERT_EQ(m.uvs.size(), 4u);
  // At texel centres the lookup is the texel, sRGB-decoded: (0, 0) is the image's top left.
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      EXPECT_EQ(sampleBaseColour(*m.baseColour, {(x + 0.5f) / 2, (y + 0.5f) / 2}),
                linear(file, x, y))
          << x << "," << y;
  // The decode is sRGB, not code / 255: code 200 is 0.578 linear, not 0.784.
  EXPECT_NEAR(sampleBaseColour(*m.baseColour, {0.25f, 0.25f}).x, 0.578f, 1e-3f);
}

TEST(BaseColourTexture, GltfKeepsAnImageBesideTheFile) {
  TempDir dir;
  const std::string data = quadData();
  dir.write("quad.bin", data);
  dir.write("tex.png", png(twoByTwo()));
  LoadReport report;
  const Mesh m = loadMesh(dir.write("quad.gltf", quadJson("quad.bin", data.size(),
                                                          R"("images": [{"uri": "tex.png"}])")),
                          &report);
  expectKeptTexture(m, twoByTwo());
  EXPECT_TRUE(report.warnings.empty()) << report.warnings[0];
}

TEST(BaseColourTexture, GltfKeepsAnImageEmbeddedInTheGlb) {
  TempDir dir;
  std::string data = quadData();
  const std::string image = png(twoByTwo());
  const std::string view =
      R"(, {"buffer": 0, "byteOffset": 152, "byteLength": )" + std::to_string(image.size()) + "}";
  data += image;
  const std::string json =
      quadJson("", data.size(), R"("images": [{"bufferView": 2, "mimeType": "image/png"}])", view);
  LoadReport report;
  const Mesh m = loadMesh(dir.write("quad.glb", glb(json, data)), &report);
  expectKeptTexture(m, twoByTwo());
  EXPECT_TRUE(report.warnings.empty()) << report.warnings[0];
  // The same bytes from memory: nothing outside them is needed.
  const std::string bytes = glb(json, data);
  const Mesh fromMemory = loadMeshBytes(
      "quad.glb", std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()));
  ASSERT_TRUE(fromMemory.baseColour.has_value());
  EXPECT_EQ(fromMemory.baseColour->image, twoByTwo());
}

TEST(BaseColourTexture, GltfWithoutItsImageWarnsAndLoadsWithoutIt) {
  TempDir dir;
  const std::string data = quadData();
  dir.write("quad.bin", data);
  // Missing, then corrupt (a PNG signature and nothing after), then a header declaring
  // 100000 x 100000 texels (refused before anything is allocated for them).
  std::string huge = png(twoByTwo());
  const std::uint32_t side = 0xA0860100u;  // 100000, big-endian
  std::memcpy(huge.data() + 16, &side, 4);
  std::memcpy(huge.data() + 20, &side, 4);
  dir.write("corrupt.png", std::string("\x89PNG\r\n\x1a\n", 8) + "garbage");
  dir.write("huge.png", huge);
  for (const std::string name : {"missing.png", "corrupt.png", "huge.png"}) {
    SCOPED_TRACE(name);
    LoadReport report;
    const Mesh m = loadMesh(
        dir.write("quad.gltf",
                  quadJson("quad.bin", data.size(), R"("images": [{"uri": ")" + name + "\"}]")),
        &report);
    EXPECT_FALSE(m.baseColour.has_value());
    ASSERT_EQ(m.albedo.size(), 4u);
    EXPECT_EQ(m.albedo[0], (Rgb{0.5f, 0.25f, 1.0f}));  // the factor alone, texture or not
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_TRUE(mentions(report, name, "base colour texture not used")) << report.warnings[0];
    EXPECT_EQ(report.warnings[0].find('\n'), std::string::npos);
  }
}

// An OBJ plane of two quads whose faces use `left` and `right` materials.
std::string twoQuadObj(const std::string& left, const std::string& right) {
  return "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 2 0 0\nv 2 0 1\n"
         "vt 0.25 0.25\nvt 0.75 0.25\nvt 0.75 0.75\nvt 0.25 0.75\nvn 0 1 0\n"
         "usemtl " +
         left + "\nf 1/1/1 4/4/1 3/3/1 2/2/1\nusemtl " + right + "\nf 2/2/1 3/3/1 6/3/1 5/2/1\n";
}

TEST(BaseColourTexture, ObjKeepsMapKdStoredBottomRowFirst) {
  TempDir dir;
  dir.write("tex.png", png(twoByTwo()));
  dir.write("m.mtl",
            "newmtl a\nKd 0.5 0.25 1\nmap_Kd tex.png\nnewmtl b\nKd 0.5 0.25 1\n"
            "map_Kd tex.png\n");
  LoadReport report;
  const Mesh m = loadMesh(dir.write("m.obj", twoQuadObj("a", "b")), &report);
  EXPECT_TRUE(report.warnings.empty()) << report.warnings[0];
  ASSERT_TRUE(m.baseColour.has_value());  // two materials, one file: one texture
  for (const Rgb& a : m.albedo) EXPECT_EQ(a, (Rgb{0.5f, 0.25f, 1.0f}));
  // OBJ's v runs up the image: the stored row 0 is the file's bottom row, so the lookup at
  // v = 0.75 finds the file's top row, as an OBJ viewer shows it.
  const image::Srgb8Image file = twoByTwo();
  for (int x = 0; x < 2; ++x) {
    EXPECT_EQ(sampleBaseColour(*m.baseColour, {(x + 0.5f) / 2, 0.75f}), linear(file, x, 0));
    EXPECT_EQ(sampleBaseColour(*m.baseColour, {(x + 0.5f) / 2, 0.25f}), linear(file, x, 1));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(m.baseColour->image.code(x, 1, c), file.code(x, 0, c));
  }
}

TEST(BaseColourTexture, PartsWithDifferentTexturesAreSampledAtTheVertices) {
  TempDir dir;
  dir.write("tex.png", png(twoByTwo()));
  dir.write("m.mtl", "newmtl a\nKd 1 1 1\nmap_Kd tex.png\nnewmtl plain\nKd 0.5 0.5 0.5\n");
  LoadReport report;
  const Mesh m = loadMesh(dir.write("m.obj", twoQuadObj("a", "plain")), &report);
  EXPECT_FALSE(m.baseColour.has_value());
  EXPECT_TRUE(mentions(report, "m.obj", "sampled at the vertices")) << report.warnings.size();
  // Vertex 0 (uv (0.25, 0.25): the file's bottom-left texel) takes the texture into its albedo.
  EXPECT_EQ(m.albedo[0], linear(twoByTwo(), 0, 1));
}

TEST(BaseColourTexture, MissingOrCorruptMapKdWarnsOnce) {
  TempDir dir;
  dir.write("bad.png", std::string("\x89PNG\r\n\x1a\n", 8) + "garbage");
  for (const std::string name : {"gone.png", "bad.png"}) {
    SCOPED_TRACE(name);
    dir.write("m.mtl", "newmtl a\nKd 0.5 0.25 1\nmap_Kd " + name + "\n");
    LoadReport report;
    const Mesh m = loadMesh(dir.write("m.obj", twoQuadObj("a", "a")), &report);
    EXPECT_FALSE(m.baseColour.has_value());
    EXPECT_EQ(m.albedo[0], (Rgb{0.5f, 0.25f, 1.0f}));
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_TRUE(mentions(report, dir.file(name), "texture not used")) << report.warnings[0];
  }
}

TEST(BaseColourTexture, ScenesOfSeveralFilesFoldTexturesIntoTheAlbedo) {
  TempDir dir;
  dir.write("tex.png", png(twoByTwo()));
  dir.write("m.mtl", "newmtl a\nKd 1 0.5 1\nmap_Kd tex.png\n");
  const std::string obj = dir.write("m.obj", twoQuadObj("a", "a"));
  const Mesh one = loadMesh(obj);
  ASSERT_TRUE(one.baseColour.has_value());
  const Mesh scene = loadScene({obj, obj});
  EXPECT_FALSE(scene.baseColour.has_value());
  const std::vector<Rgb> expected = albedoAtVertices(one);
  ASSERT_EQ(scene.albedo.size(), 2 * expected.size());
  for (std::size_t v = 0; v < scene.albedo.size(); ++v)
    EXPECT_EQ(scene.albedo[v], expected[v % expected.size()]) << v;
  EXPECT_EQ(expected[0], Rgb(1, 0.5f, 1) * linear(twoByTwo(), 0, 1));
}

TEST(BaseColourTexture, LookupIsBilinearWithRepeatWrapping) {
  BaseColourTexture t{twoByTwo(), "t"};
  const image::Srgb8Image& im = t.image;
  // Halfway between the two texels of the top row, and across the wrap: u = 0 lies halfway
  // between the last column and the first.
  const Rgb mid = (linear(im, 0, 0) + linear(im, 1, 0)) * 0.5f;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(sampleBaseColour(t, {0.5f, 0.25f})[c], mid[c], 1e-6f);
    EXPECT_NEAR(sampleBaseColour(t, {0.0f, 0.25f})[c], mid[c], 1e-6f);
    EXPECT_NEAR(sampleBaseColour(t, {3.0f, -0.75f})[c], mid[c], 1e-6f);  // whole periods away
  }
  EXPECT_EQ(sampleBaseColour(t, {0.25f, 1.25f}), linear(im, 0, 0));
  EXPECT_EQ(sampleBaseColour(t, {NAN, 0.5f}), Rgb(1.0f));
}

}  // namespace
}  // namespace prt
