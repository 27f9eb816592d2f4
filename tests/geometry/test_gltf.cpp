// glTF 2.0 loading: node hierarchy transforms (TRS and matrices) applied to positions, normals by
// the inverse transpose, base colour factor × COLOR_0 → albedo, .gltf (data URI) and .glb alike.

#include <gtest/gtest.h>

#include <cstring>

#include "fixtures.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/load.hpp"

namespace prt {
namespace {

using test::TempDir;

std::string base64(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v =
        (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8 | (unsigned char)in[i + 2];
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
  }
  if (i + 1 == in.size()) {
    const unsigned v = (unsigned char)in[i] << 16;
    out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8;
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
  }
  return out;
}

// One triangle in a tilted plane (so a non-uniform scale changes its normal).
const Vec3f kP[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
const Vec3f kN = normalize(Vec3f{0, -1, 1});
const Vec3f kC[3] = {{1, 0, 0}, {0, 1, 0}, {0.5f, 0.5f, 0.5f}};

std::string binaryData() {
  std::string b;
  const auto add = [&](const Vec3f& v) { b.append(reinterpret_cast<const char*>(&v), 12); };
  for (auto& p : kP) add(p);
  for (int k = 0; k < 3; ++k) add(kN);
  for (auto& c : kC) add(c);
  const std::uint16_t idx[4] = {0, 1, 2, 0};  // padded to 4 bytes
  b.append(reinterpret_cast<const char*>(idx), 8);
  return b;
}

std::string json(const std::string& bufferUri, std::size_t bytes) {
  const std::string uri = bufferUri.empty() ? "" : "\"uri\": \"" + bufferUri + "\", ";
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"translation": [1, 2, 3], "children": [1]},
           {"name": "tri", "rotation": [0, 0.70710678, 0, 0.70710678], "scale": [1, 2, 1], "mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "COLOR_0": 2}, "indices": 3, "material": 0}]}],
 "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1]}}],
 "buffers": [{)" +
         uri + "\"byteLength\": " + std::to_string(bytes) + R"(}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 108}, {"buffer": 0, "byteOffset": 108, "byteLength": 6}],
 "accessors": [
   {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
   {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"},
   {"bufferView": 0, "byteOffset": 72, "componentType": 5126, "count": 3, "type": "VEC3"},
   {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
}

std::string glb(const std::string& j, const std::string& bin) {
  std::string js = j;
  while (js.size() % 4) js += ' ';
  std::string b = bin;
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

void expectTransformed(const Mesh& m) {
  // World = T(1,2,3) · R_y(90°) · S(1,2,1); rotation built independently of the loader's
  // quaternion code.
  const Mat3d R = rotationAxisAngle({0, 1, 0}, kPi / 2);
  ASSERT_EQ(m.vertexCount(), 3u);
  ASSERT_EQ(m.triangleCount(), 1u);
  for (int v = 0; v < 3; ++v) {
    const Vec3d p = R * Vec3d{kP[v].x, 2.0 * kP[v].y, kP[v].z} + Vec3d{1, 2, 3};
    EXPECT_NEAR(length(Vec3d(m.positions[v]) - p), 0.0, 1e-5) << v;
    // Normals: (R S)^-T n = R S^-1 n.
    const Vec3d n = normalize(R * Vec3d{kN.x, kN.y / 2.0, kN.z});
    EXPECT_NEAR(length(Vec3d(m.normals[v]) - n), 0.0, 1e-5) << v;
    // The transformed normal is perpendicular to the transformed triangle.
    EXPECT_NEAR(dot(Vec3d(m.normals[v]), Vec3d(m.positions[1] - m.positions[0])), 0.0, 1e-5);
    EXPECT_NEAR(dot(Vec3d(m.normals[v]), Vec3d(m.positions[2] - m.positions[0])), 0.0, 1e-5);
    ASSERT_TRUE(m.hasAlbedo());
    const Rgb a = Rgb{0.5f, 0.25f, 1.0f} * kC[v];
    EXPECT_NEAR(length(m.albedo[v] - a), 0.0f, 1e-6f) << v;
  }
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].name, "tri");
}

TEST(GltfLoader, NodeTransformsNormalsAndBaseColour) {
  TempDir dir;
  const std::string bin = binaryData();
  const std::string data = "data:application/octet-stream;base64," + base64(bin);
  expectTransformed(loadMesh(dir.write("t.gltf", json(data, bin.size()))));
  expectTransformed(loadMesh(dir.write("t.glb", glb(json("", bin.size()), bin))));
}

TEST(GltfLoader, BadFilesThrow) {
  TempDir dir;
  const std::string bin = binaryData();
  const auto msg = [](const std::string& p) {
    try {
      loadMesh(p);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  // Buffer shorter than the accessors claim.
  const std::string shortBin = bin.substr(0, 60);
  const std::string s =
      dir.write("short.gltf",
                json("data:application/octet-stream;base64," + base64(shortBin), shortBin.size()));
  EXPECT_EQ(msg(s).rfind(s + ": ", 0), 0u) << msg(s);
  const std::string junk = dir.write("junk.gltf", "{ not json");
  EXPECT_EQ(msg(junk).rfind(junk + ": ", 0), 0u) << msg(junk);
  EXPECT_EQ(msg(junk).find('\n'), std::string::npos);
  const std::string none = dir.file("none.glb");
  EXPECT_EQ(msg(none).rfind(none + ": ", 0), 0u) << msg(none);
}

}  // namespace
}  // namespace prt
