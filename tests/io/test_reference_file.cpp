// Reference files (io/reference_file.hpp): per vertex and per texel they read back what was
// written, and a per-texel file is held to its lightmap (rows named "texels", each below W·H).

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/error_text.hpp"
#include "prt/io/reference_file.hpp"

namespace prt {
namespace {

io::ReferenceFile sample(bool texels) {
  io::ReferenceFile r;
  r.bakeFile = "b.glb";
  r.meshVertices = 4;
  r.meshFingerprint = "0123456789abcdef";
  r.lightSource = "builtin:sky";
  r.environmentFingerprint = "fedcba9876543210";
  r.mode = "shadowed";
  r.material = "lambert";
  r.samples = 8;
  r.mis = "power";
  if (texels) {
    r.lightmapWidth = 8;
    r.lightmapHeight = 2;
    r.lightmapUvFingerprint = "00112233445566aa";
    r.vertices = {1, 9, 15};  // past the 4 vertices: texels
  } else {
    r.vertices = {0, 3};
  }
  r.radiance.assign(r.vertices.size(), Rgb(0.25f, 0.5f, 0.125f));
  r.stdError.assign(r.vertices.size(), Rgb(0.01f));
  return r;
}

TEST(ReferenceFile, PerVertexAndPerTexelReadBackWhatWasWritten) {
  const auto dir = std::filesystem::temp_directory_path() / "prt-test-reference-file";
  std::filesystem::create_directories(dir);
  for (const bool texels : {false, true}) {
    const io::ReferenceFile r = sample(texels);
    const std::string path = (dir / (texels ? "t.json" : "v.json")).string();
    io::writeReferenceJson(path, r);
    const io::ReferenceFile back = io::readReferenceJson(path);
    EXPECT_EQ(back.texels(), texels);
    EXPECT_EQ(back.lightmapWidth, r.lightmapWidth);
    EXPECT_EQ(back.lightmapHeight, r.lightmapHeight);
    EXPECT_EQ(back.lightmapUvFingerprint, r.lightmapUvFingerprint);
    EXPECT_EQ(back.rowCount(), texels ? 16u : 4u);
    EXPECT_EQ(back.vertices, r.vertices);
    ASSERT_EQ(back.radiance.size(), r.radiance.size());
    EXPECT_EQ(back.radiance[0].y, 0.5f);
  }
  std::filesystem::remove_all(dir);
}

TEST(ReferenceFile, APerTexelFileIsHeldToItsLightmap) {
  const auto parse = [](const std::string& text) {
    return testing::errorOf([&] { io::parseReferenceJson(text, "r.json"); });
  };
  const std::string head =
      R"({"format": "prtkit-reference", "formatVersion": 1,
          "bake": {"file": "b.glb", "vertices": 4, "fingerprint": "x",
                   "lightmap": {"width": 8, "height": 2, "uvFingerprint": "y"}},
          "light": {"source": "s", "fingerprint": "f", "rotation": [1,0,0,0,1,0,0,0,1]},
          "mode": "shadowed", "bounces": 0, "material": "lambert", "samples": 8, "seed": 0,
          "mis": "power", "rays": 0, )";
  const std::string one = R"("radiance": [[1, 1, 1]], "stdError": [[0, 0, 0]]})";
  EXPECT_EQ(parse(head + R"("texels": [15], )" + one), "");
  EXPECT_NE(parse(head + R"("vertices": [1], )" + one).find("missing \"texels\""),
            std::string::npos);
  EXPECT_NE(parse(head + R"("texels": [16], )" + one)
                .find("texel entry 0 is not a texel index "
                      "below 16"),
            std::string::npos);
  std::string zero = head;
  zero.replace(zero.find("\"width\": 8"), 10, "\"width\": 0");
  EXPECT_NE(parse(zero + R"("texels": [1], )" + one).find("at least 1 x 1"), std::string::npos);
}

}  // namespace
}  // namespace prt
