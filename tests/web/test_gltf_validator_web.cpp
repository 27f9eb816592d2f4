// Every kind of bake file, and prt unwrap's plain mesh, passes the Khronos glTF validator with
// 0 errors and 0 warnings: dense
// vectors of several modes, matrices, CPCA-compressed transfer, a vertex range of a split bake,
// per-texel transfer dense and compressed, a probe grid whole and a range of it, and the
// exports that are glTF (a relit probe grid, relit lightmaps).
// The only information it gives is the vendor extension it does not know
// (PRTKIT_radiance_transfer, docs/extensions/) and transfer accessors no primitive uses (they
// are read through the extension). The validator runs under node from web/node_modules; the
// test skips, saying why, without them. A broken file is checked too, so a validator that
// reports nothing fails the test.

#include <gtest/gtest.h>

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli/cli_harness.hpp"
#include "prt/core/json.hpp"
#include "prt/image/image_io.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/sh/sh.hpp"

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
  /// Every file of `report`: 0 errors, 0 warnings, and as information only our vendor extension
  /// (declared in extensionsUsed, unknown to the validator) and objects read through it.
  static void expectValidWithOurExtension(const Json& report) {
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
        std::string("compress texels.glb --clusters 4 --pca 2 -o texels-cpca.glb"),
        std::string("probes 'builtin:cornell?grid=6' --grid 3x2x2 --samples 8 -o probes.glb"),
        std::string("probes 'builtin:cornell?grid=6' --grid 3x2x2 --samples 8 --range 0:5 "
                    "-o probes-range.glb"),
        "bake " + scene + " --mode shadowed --basis haar --resolution 8 --terms 16 -o haar.glb"}) {
    const Result r = prt("-q " + cmd);
    ASSERT_EQ(r.rc, 0) << cmd << ": " << r.err;
  }
  const Json report = validate(
      "vectors.glb rgb.glb matrix.glb cpca.glb range.glb texels.glb texels-cpca.glb probes.glb "
      "probes-range.glb haar.glb");
  ASSERT_EQ(report.size(), 10u);
  expectValidWithOurExtension(report);
}

TEST_F(GltfValidatorWeb, ProbeGridExportsAreValidGltf) {
  // prt export --format probe-grid -o .glb: the relit grid under PRTKIT_probe_grid, every
  // engine's convention; no scene, the accessors read through the extension.
  ASSERT_EQ(prt("-q probes 'builtin:cornell?grid=6' --grid 3x2x2 --samples 8 -o p.glb").rc, 0);
  std::string files;
  for (const std::string engine : {"threejs", "unity", "gltf-ibl", "prtkit"}) {
    const Result r =
        prt("-q export p.glb --format probe-grid --engine " + engine + " -o " + engine + ".glb");
    ASSERT_EQ(r.rc, 0) << engine << ": " << r.err;
    files += engine + ".glb ";
  }
  const Json report = validate(files);
  ASSERT_EQ(report.size(), 4u);
  expectValidWithOurExtension(report);
}

TEST_F(GltfValidatorWeb, LightmapExportsAreValidGltf) {
  // prt export --format lightmap | lightmap-sh -o .glb: the bake's mesh and PRTKIT_lightmap's
  // float layers, for a plain lightmap and the encodings with the most layers of each kind.
  ASSERT_EQ(prt("-q bake builtin:cornell --mode interreflected --domain texels --resolution 16 "
                "--transfer matrix --samples 8 -o m.glb")
                .rc,
            0);
  std::string files;
  int count = 0;
  for (const std::string& format :
       {std::string("lightmap"), std::string("lightmap-sh --encoding l1"),
        std::string("lightmap-sh --encoding zh3-optimal"),
        std::string("lightmap-sh --encoding l2-deringed")}) {
    const std::string out = "lm" + std::to_string(count++) + ".glb";
    const Result r = prt("-q export m.glb --format " + format + " -o " + out);
    ASSERT_EQ(r.rc, 0) << format << ": " << r.err;
    files += out + " ";
  }
  const Json report = validate(files);
  ASSERT_EQ(report.size(), 4u);
  expectValidWithOurExtension(report);
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

/// The RGBA bytes of a data-URI PNG.
std::vector<unsigned char> decodeDataUriPng(const std::string& uri, int& size) {
  const std::string prefix = "data:image/png;base64,";
  EXPECT_EQ(uri.rfind(prefix, 0), 0u);
  std::string b64 = uri.substr(prefix.size());
  std::string bytes;
  unsigned v = 0;
  int n = 0;
  for (char c : b64) {
    const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = c ? std::strchr(k, c) : nullptr;
    if (!at) continue;
    v = (v << 6) | unsigned(at - k);
    if ((n += 6) >= 8) bytes.push_back(char((v >> (n -= 8)) & 0xff));
  }
  int w = 0, h = 0, channels = 0;
  stbi_uc* px = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                                      int(bytes.size()), &w, &h, &channels, 4);
  EXPECT_NE(px, nullptr);
  EXPECT_EQ(channels, 4) << "EXT_lights_image_based reads a 4-channel PNG as RGBD";
  EXPECT_EQ(w, h);
  size = w;
  std::vector<unsigned char> out(px, px + std::size_t(w) * std::size_t(h) * 4);
  stbi_image_free(px);
  return out;
}

TEST_F(GltfValidatorWeb, GltfIblLightIsACompleteValidGltf) {
  // prt light --format gltf-ibl: a whole glTF 2.0 asset (asset.version, extensionsUsed, a scene
  // using the light) whose EXT_lights_image_based light has all it requires — irradiance, and a
  // prefiltered specular cube (specularImages, specularImageSize) — passing the validator with
  // 0 errors and 0 warnings. The cube's mip 0 is the light's own radiance, RGBD-packed (Babylon's
  // rgb^2.2 / alpha), in the standard cube orientation: checked texel by texel off the axes.
  for (const std::string& cmd :
       {std::string("light builtin:sky --format gltf-ibl -o sky.gltf"),
        std::string("light builtin:sky --format gltf-ibl -o sky-ibl.json"),
        std::string("light builtin:studio --bands 5 --rotate 10,40,0 --format gltf-ibl -o studio.gltf"),
        std::string("light builtin:studio --bands 5 --rotate 10,40,0 -o studio.json")}) {
    const Result r = prt("-q " + cmd);
    ASSERT_EQ(r.rc, 0) << cmd << ": " << r.err;
  }
  EXPECT_EQ(slurp(dir_ / "sky.gltf"), slurp(dir_ / "sky-ibl.json"));
  const Json report = validate("sky.gltf studio.gltf");
  ASSERT_EQ(report.size(), 2u);
  for (const auto& [file, r] : report.items()) {
    SCOPED_TRACE(file);
    EXPECT_EQ(r["errors"], 0) << r["messages"].dump();
    EXPECT_EQ(r["warnings"], 0) << r["messages"].dump();
    for (const Json& m : r["messages"]) {
      const std::string code = m[1];
      // The validator does not know the extension (information), so neither sees the images it
      // uses (information too).
      EXPECT_TRUE(code == "UNSUPPORTED_EXTENSION" || code == "UNUSED_OBJECT") << m.dump();
    }
  }
  const Json g = Json::parse(slurp(dir_ / "studio.gltf"));
  EXPECT_EQ(g["asset"]["version"], "2.0");
  EXPECT_EQ(g["extensionsUsed"], Json::array({"EXT_lights_image_based"}));
  EXPECT_EQ(g["scenes"][g["scene"].get<int>()]["extensions"]["EXT_lights_image_based"]["light"], 0);
  const Json& light = g["extensions"]["EXT_lights_image_based"]["lights"][0];
  ASSERT_EQ(light["irradianceCoefficients"].size(), 9u);
  const int size = light["specularImageSize"];
  EXPECT_EQ(size, 64);
  const Json& mips = light["specularImages"];
  ASSERT_EQ(mips.size(), 3u);  // 64², 32², 16²: roughness 0, ½, 1
  const prt::sh::RgbSh L = prt::io::readLightJson((dir_ / "studio.json").string()).coefficients;
  double worst = 0, peak = 0, lo[3] = {1e30, 1e30, 1e30}, hi[3] = {0, 0, 0};
  for (std::size_t k = 0; k < mips.size(); ++k) {
    ASSERT_EQ(mips[k].size(), 6u);
    for (int face = 0; face < 6; ++face) {
      int n = 0;
      const auto px = decodeDataUriPng(g["images"][mips[k][face].get<std::size_t>()]["uri"], n);
      EXPECT_EQ(n, size >> k);
      for (std::size_t i = 0; i < px.size(); i += 4) {
        const double red = std::pow(px[i] / 255.0, 2.2) / (px[i + 3] / 255.0);
        lo[k] = std::min(lo[k], red);
        hi[k] = std::max(hi[k], red);
      }
      if (k != 0) continue;
      for (const auto& [x, y] : {std::pair{5, 9}, std::pair{50, 13}, std::pair{20, 44}, std::pair{60, 60}}) {
        const Vec3d d = envmap::cubeFaceDirection(face, 2 * (x + 0.5) / n - 1, 2 * (y + 0.5) / n - 1);
        const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        const Rgb want = prt::sh::reconstruct(
            L, Vec3f(float(d.x / len), float(d.y / len), float(d.z / len)));
        const unsigned char* p = &px[4 * (std::size_t(y) * std::size_t(n) + std::size_t(x))];
        for (int c = 0; c < 3; ++c) {
          const double got = std::pow(p[c] / 255.0, 2.2) / (p[3] / 255.0);
          worst = std::max(worst, std::abs(got - std::max(0.0f, want[c])));
          peak = std::max(peak, double(want[c]));
        }
      }
    }
  }
  EXPECT_LT(worst, 0.01 * peak) << "mip 0 is the light's radiance, RGBD, standard orientation";
  // Rougher mips are blurrier: the spread of the radiance shrinks (roughness 1 most).
  EXPECT_LT(hi[1] - lo[1], hi[0] - lo[0]);
  EXPECT_LT(hi[2] - lo[2], 0.8 * (hi[1] - lo[1]));
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
