// The base-colour texture in the bake file (issue 18): written as material 0's baseColorTexture
// on TEXCOORD_0 — one PNG in the binary chunk — and read back bit for bit; what a glTF viewer
// sees of it, read through tinygltf alone; files without one as before; and every way a file can
// lie about it refused with one line.

#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>

#include "common/error_text.hpp"
#include "common/random_data.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/load.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/mesh_file.hpp"

namespace prt {
namespace {

using testing::errorOf;

/// A quad with texture UVs and a 3 × 2 texture whose codes are all distinct, one shadowed
/// vector transfer.
BakeFile texturedBake() {
  BakeFile b;
  Mesh& m = b.mesh;
  m.source = "quad";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  m.normals.assign(4, Vec3f{0, 1, 0});
  m.albedo = {{0.5f, 0.25f, 1}, {1, 1, 1}, {0.125f, 0.5f, 0.75f}, {1, 0, 0.5f}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}};
  m.parts = {{"quad", 0, 4, 0, 2}};
  BaseColourTexture t;
  t.name = "wood.png";
  t.image.width = 3;
  t.image.height = 2;
  for (int i = 0; i < 18; ++i) t.image.rgb.push_back(std::uint8_t(7 + 13 * i));
  m.baseColour = t;
  BakedTransfer tr;
  tr.recipe.mode = TransferMode::Shadowed;
  tr.transfer = testdata::randomField(TransferLayout::Vector, 3, 1, 4, 5);
  b.transfers.push_back(std::move(tr));
  return b;
}

std::span<const unsigned char> asBytes(const std::string& s) {
  return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

nlohmann::json jsonOf(const std::string& glb) {
  std::uint32_t len;
  std::memcpy(&len, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.substr(20, len));
}

/// `glb` with its JSON chunk replaced by `doc` (the binary chunk kept).
std::string withJson(const std::string& glb, const nlohmann::json& doc) {
  std::string json = doc.dump();
  while (json.size() % 4) json.push_back(' ');
  std::string out = glb.substr(0, 12);
  const auto put = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  put(std::uint32_t(json.size()));
  put(0x4E4F534Au);
  out += json;
  std::uint32_t oldJson;
  std::memcpy(&oldJson, glb.data() + 12, 4);
  out += glb.substr(20 + oldJson);
  const std::uint32_t total = std::uint32_t(out.size());
  std::memcpy(out.data() + 8, &total, 4);
  return out;
}

TEST(BakeTexture, RoundTripsBitExactly) {
  const BakeFile b = texturedBake();
  const std::string bytes = encodeBake(b);
  const BakeFile r = decodeBake(asBytes(bytes), "t.glb");
  ASSERT_TRUE(r.mesh.baseColour.has_value());
  EXPECT_EQ(*r.mesh.baseColour, *b.mesh.baseColour);  // every code, the size and the name
  EXPECT_EQ(r.mesh.albedo, b.mesh.albedo);            // COLOR_0: the factor, untextured
  EXPECT_EQ(r.mesh.uvs, b.mesh.uvs);
  EXPECT_EQ(r.formatVersion, kBakeFormatVersion);
  EXPECT_EQ(encodeBake(r), bytes);  // and the same bytes again
  // Without a texture the file holds no image at all, as before.
  BakeFile plain = b;
  plain.mesh.baseColour.reset();
  const nlohmann::json j = jsonOf(encodeBake(plain));
  EXPECT_FALSE(j.contains("images"));
  EXPECT_FALSE(j.contains("textures"));
  EXPECT_FALSE(j["materials"][0]["pbrMetallicRoughness"].contains("baseColorTexture"));
  EXPECT_FALSE(decodeBake(asBytes(encodeBake(plain)), "p.glb").mesh.baseColour.has_value());
}

// What any glTF viewer reads: material 0's baseColorTexture on TEXCOORD_0, a sampler of linear
// filtering and repeat wrapping, and an embedded PNG that decodes (tinygltf's own stb_image
// here, not our reader) to the mesh's codes; COLOR_0 then multiplies it, as glTF defines.
TEST(BakeTexture, GltfViewersSeeTheTexture) {
  const BakeFile b = texturedBake();
  const std::string bytes = encodeBake(b);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, asBytes(bytes).data(),
                                          unsigned(bytes.size())))
      << err;
  ASSERT_EQ(model.materials.size(), 1u);
  const auto& bt = model.materials[0].pbrMetallicRoughness.baseColorTexture;
  ASSERT_EQ(bt.index, 0);
  EXPECT_EQ(bt.texCoord, 0);
  ASSERT_EQ(model.textures.size(), 1u);
  ASSERT_EQ(model.samplers.size(), 1u);
  EXPECT_EQ(model.samplers[0].wrapS, TINYGLTF_TEXTURE_WRAP_REPEAT);
  EXPECT_EQ(model.samplers[0].wrapT, TINYGLTF_TEXTURE_WRAP_REPEAT);
  EXPECT_EQ(model.samplers[0].magFilter, TINYGLTF_TEXTURE_FILTER_LINEAR);
  const tinygltf::Image& im = model.images[std::size_t(model.textures[0].source)];
  EXPECT_EQ(im.mimeType, "image/png");
  ASSERT_EQ(im.width, 3);
  ASSERT_EQ(im.height, 2);
  ASSERT_GE(im.component, 3);
  for (int i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(im.image[std::size_t(i * im.component + c)],
                b.mesh.baseColour->image.rgb[3 * i + c]);
  const auto& prim = model.meshes[0].primitives[0];
  EXPECT_EQ(prim.material, 0);
  EXPECT_TRUE(prim.attributes.count("TEXCOORD_0"));
  EXPECT_TRUE(prim.attributes.count("COLOR_0"));
}

TEST(BakeTexture, PlainMeshFilesKeepItToo) {
  // prt unwrap's .glb goes through the same writer; the mesh loader reads the texture back.
  const BakeFile b = texturedBake();
  const std::string glb = encodeMeshGlb(b.mesh);
  const nlohmann::json j = jsonOf(glb);
  ASSERT_TRUE(j.contains("images"));
  EXPECT_EQ(j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
  LoadReport report;
  const Mesh m = loadMeshBytes("quad.glb", asBytes(glb), &report);
  ASSERT_TRUE(m.baseColour.has_value());
  EXPECT_EQ(m.baseColour->image, b.mesh.baseColour->image);
  EXPECT_EQ(m.albedo, b.mesh.albedo);
  EXPECT_TRUE(report.warnings.empty());
}

TEST(BakeTexture, LiesAboutTheTextureAreRefusedInOneLine) {
  const BakeFile b = texturedBake();
  const std::string bytes = encodeBake(b);
  const nlohmann::json doc = jsonOf(bytes);
  const auto refused = [&](const std::function<void(nlohmann::json&)>& edit,
                           const std::string& mention) {
    nlohmann::json d = doc;
    edit(d);
    const std::string e = errorOf([&] { decodeBake(asBytes(withJson(bytes, d)), "t.glb"); });
    EXPECT_NE(e.find("t.glb: "), std::string::npos) << e;
    EXPECT_NE(e.find(mention), std::string::npos) << "expected '" << mention << "' in: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  refused([](nlohmann::json& d) { d["images"].push_back(d["images"][0]); }, "other than one");
  refused([](nlohmann::json& d) { d["images"][0]["mimeType"] = "image/jpeg"; }, "embedded PNG");
  refused([](nlohmann::json& d) { d["images"][0]["uri"] = "/etc/hostname"; }, "external image");
  refused([](nlohmann::json& d) { d["images"][0]["bufferView"] = 999; }, "bufferView 999");
  refused(
      [](nlohmann::json& d) {
        d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
      },
      "baseColorTexture");
  refused(
      [](nlohmann::json& d) {
        d["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture");
      },
      "other than one");
  // The PNG's bytes cut short: its view now ends inside the image data.
  refused(
      [](nlohmann::json& d) {
        const int view = d["images"][0]["bufferView"];
        d["bufferViews"][std::size_t(view)]["byteLength"] = 40;
      },
      "base colour texture");
  // A texture without the texture set it is read at.
  BakeFile noUvs = b;
  noUvs.mesh.uvs.clear();
  EXPECT_NE(errorOf([&] { encodeBake(noUvs); }).find("no texture UV per vertex"),
            std::string::npos);
}

}  // namespace
}  // namespace prt
