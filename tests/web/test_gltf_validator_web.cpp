// Every kind of bake file, and prt unwrap's plain mesh, passes the Khronos glTF validator with
// 0 errors and 0 warnings: dense
// vectors of several modes, matrices, CPCA-compressed transfer, a vertex range of a split bake,
// per-texel transfer dense and compressed.
// The only information it gives is the vendor extension it does not know
// (PRTKIT_radiance_transfer, docs/extensions/) and transfer accessors no primitive uses (they
// are read through the extension). The validator runs under node from web/node_modules; the
// test skips, saying why, without them. A broken file is checked too, so a validator that
// reports nothing fails the test.

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli/cli_harness.hpp"
#include "prt/core/json.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"

namespace prt::testing {
namespace {

class GltfValidatorWeb : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    if (std::system("command -v node > /dev/null 2>&1") != 0)
      GTEST_SKIP() << "no node here (apt-get install nodejs)";
    if (!fs::exists(std::string(PRT_SOURCE_DIR) + "/web/node_modules/gltf-validator/package.json"))
      GTEST_SKIP() << "web/node_modules/gltf-validator missing (run scripts/setup.sh)";
  }
  Json validate(const std::string& files) const {
    const std::string script =
        std::string(PRT_SOURCE_DIR) + "/tests/web/gltf_validator/validate.mjs";
    const std::string cmd = "cd '" + dir_.string() + "' && node '" + script + "' " + files +
                            " > report.json 2> node.txt";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(dir_ / "node.txt");
    return Json::parse(slurp(dir_ / "report.json"));
  }
};

TEST_F(GltfValidatorWeb, EveryBakeIsValidGltf) {
  const std::string scene = "'builtin:sphere-plane?subdiv=1'";
  for (const std::string& cmd :
       {"bake " + scene + " --mode shadowed --mode interreflected --samples 8 -o vectors.glb",
        std::string("bake builtin:cornell --mode interreflected --samples 8 -o rgb.glb"),
        "bake " + scene + " --mode shadowed --transfer matrix --bands 3 --samples 8 -o matrix.glb",
        std::string("compress matrix.glb --clusters 8 --pca 2 -o cpca.glb"),
        "bake " + scene + " --mode shadowed --samples 8 --range 0:100 -o range.glb",
        std::string("bake builtin:cornell --mode interreflected --domain texels --resolution 32 "
                    "--samples 8 -o texels.glb"),
        std::string("compress texels.glb --clusters 4 --pca 2 -o texels-cpca.glb")}) {
    const Result r = prt("-q " + cmd);
    ASSERT_EQ(r.rc, 0) << cmd << ": " << r.err;
  }
  const Json report =
      validate("vectors.glb rgb.glb matrix.glb cpca.glb range.glb texels.glb texels-cpca.glb");
  ASSERT_EQ(report.size(), 7u);
  for (const auto& [file, r] : report.items()) {
    SCOPED_TRACE(file);
    EXPECT_EQ(r["errors"], 0) << r["messages"].dump();
    EXPECT_EQ(r["warnings"], 0) << r["messages"].dump();
    bool extensionNamed = false;
    for (const Json& m : r["messages"]) {
      const std::string code = m[1];
      EXPECT_TRUE(code == "UNSUPPORTED_EXTENSION" || code == "UNUSED_OBJECT") << m.dump();
      if (code == "UNSUPPORTED_EXTENSION") {
        extensionNamed = true;
        EXPECT_EQ(m[2], "/extensionsUsed/0");
      }
    }
    EXPECT_TRUE(extensionNamed) << "the validator saw no extensionsUsed";
  }
}

TEST_F(GltfValidatorWeb, UnwrappedMeshesAreValidGltf) {
  // prt unwrap's plain glTF (no extension): with and without parts, with and without albedo.
  for (const std::string& cmd : {std::string("unwrap builtin:cornell -o cornell.glb"),
                                 std::string("unwrap 'builtin:sphere?subdiv=2' -o sphere.glb")}) {
    const Result r = prt("-q " + cmd);
    ASSERT_EQ(r.rc, 0) << cmd << ": " << r.err;
  }
  const Json report = validate("cornell.glb sphere.glb");
  ASSERT_EQ(report.size(), 2u);
  for (const auto& [file, r] : report.items()) {
    SCOPED_TRACE(file);
    EXPECT_EQ(r["errors"], 0) << r["messages"].dump();
    EXPECT_EQ(r["warnings"], 0) << r["messages"].dump();
    // Only the texture coordinates no material samples are reported, as information.
    for (const Json& m : r["messages"]) EXPECT_EQ(m[1], "UNUSED_OBJECT") << m.dump();
  }
}

TEST_F(GltfValidatorWeb, TexturedBakesAreValidGltf) {
  // An OBJ quad with a map_Kd (a 4 x 2 PNG): its bake, per vertex and per texel, and its
  // unwrapped mesh hold the texture as material 0's baseColorTexture (one embedded PNG).
  image::Srgb8Image tex;
  tex.width = 4;
  tex.height = 2;
  tex.rgb.assign(4 * 2 * 3, 0);
  for (std::size_t i = 0; i < tex.rgb.size(); ++i) tex.rgb[i] = std::uint8_t(31 * i);
  std::ofstream(dir_ / "tex.png", std::ios::binary) << image::encodePng(tex, "tex.png");
  std::ofstream(dir_ / "m.mtl") << "newmtl m\nKd 0.8 0.7 0.6\nmap_Kd tex.png\n";
  std::ofstream(dir_ / "quad.obj") << "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl m\n"
                                      "f 1/1/1 2/2/1 3/3/1 4/4/1\n";
  for (const std::string& cmd :
       {std::string("bake quad.obj --mode shadowed --samples 8 -o vertices.glb"),
        std::string("bake quad.obj --mode shadowed --samples 8 --domain texels --resolution 8 "
                    "-o texels.glb"),
        std::string("unwrap quad.obj -o unwrapped.glb")}) {
    const Result r = prt("-q " + cmd);
    ASSERT_EQ(r.rc, 0) << cmd << ": " << r.err;
  }
  const Json report = validate("vertices.glb texels.glb unwrapped.glb");
  ASSERT_EQ(report.size(), 3u);
  for (const auto& [file, r] : report.items()) {
    SCOPED_TRACE(file);
    EXPECT_EQ(r["errors"], 0) << r["messages"].dump();
    EXPECT_EQ(r["warnings"], 0) << r["messages"].dump();
    for (const Json& m : r["messages"]) {
      const std::string code = m[1];
      EXPECT_TRUE(code == "UNSUPPORTED_EXTENSION" || code == "UNUSED_OBJECT") << m.dump();
      // The texture set is sampled now: only the lightmap set may go unused.
      if (code == "UNUSED_OBJECT") {
        EXPECT_EQ(m[2].get<std::string>().find("TEXCOORD_0"), std::string::npos) << m.dump();
      }
    }
  }
}

TEST_F(GltfValidatorWeb, ABrokenFileIsReportedAsSuch) {
  ASSERT_EQ(prt("-q bake 'builtin:sphere?subdiv=1' --mode shadowed --samples 4 -o ok.glb").rc, 0);
  // The first accessor's count doubled: it reads past its buffer view.
  std::string bytes = slurp(dir_ / "ok.glb");
  const auto at = bytes.find("\"count\":42");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 10, "\"count\":84");
  std::ofstream(dir_ / "broken.glb", std::ios::binary) << bytes;
  const Json report = validate("broken.glb");
  EXPECT_GT(report["broken.glb"]["errors"].get<int>(), 0) << report.dump();
}

}  // namespace
}  // namespace prt::testing
