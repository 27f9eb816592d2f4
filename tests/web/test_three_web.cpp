// The three.js module (web/three, docs/three.md) in headless Chromium: its example page loads a
// bake with three.js's own GLTFLoader and the prtkit-three plugin, in an ordinary scene, and its
// ?screenshot frame of the bake alone (&only, no tone mapping) must match prt render of the same
// bake, light, rotation, camera and exposure (--tonemap clamp --background none) as the page
// must: dense scalar and RGB vectors, CPCA-compressed vectors and CPCA-compressed glossy matrices
// shaded with the kernels the file carries, and per-texel transfer relit per pixel. A turned light
// must not match. The full scene draws standard materials beside the bake without disturbing it,
// and the plugin refuses what it cannot show with one line naming the file. Each test skips, saying
// why, where chromium or the built module is missing.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "cli/cli_harness.hpp"
#include "common/checker_plane.hpp"
#include "prt/core/base64.hpp"
#include "web/page_harness.hpp"

namespace {

namespace fs = std::filesystem;
using prt::testing::Result;
using namespace web_harness;

Result prt(const std::string& args) {
  return prt::testing::runPrt(scratch(), args);
}
std::string path(const std::string& name) {
  return (scratch() / name).string();
}

const fs::path kExample = fs::path(PRT_WEB_ASSETS_DIR) / "three" / "example";

#define PRT_REQUIRE_EXAMPLE()                                                              \
  do {                                                                                     \
    if (chromium().empty()) GTEST_SKIP() << "no chromium here (apt-get install chromium)"; \
    if (!fs::exists(kExample / "example.js"))                                              \
      GTEST_SKIP() << kExample.string()                                                    \
                   << "/example.js is not built (node or web/node_modules "                \
                      "missing: run scripts/setup.sh)";                                    \
  } while (0)

/// A copy of the example page in scratch/NAME with example-data.js holding `bake` (a file in
/// scratch) and `light` (an SH light JSON file in scratch), so it opens from file://.
std::string examplePage(const std::string& name, const std::string& bake,
                        const std::string& light) {
  const fs::path dir = scratch() / name;
  fs::create_directories(dir);
  for (const char* f : {"index.html", "example.js"})
    fs::copy_file(kExample / f, dir / f, fs::copy_options::overwrite_existing);
  std::ofstream(dir / "example-data.js")
      << "window.PRT_EXAMPLE = {\"name\": \"" << bake << "\", \"glb\": \""
      << prt::base64(prt::testing::slurp(scratch() / bake))
      << "\", \"light\": " << prt::testing::slurp(scratch() / light) << "};\n";
  return dir.string();
}

/// The example's ?screenshot frame (320x240) for QUERY, and its JSON report.
std::vector<unsigned char> exampleFrame(const std::string& dir, const std::string& query,
                                        std::string* report = nullptr) {
  std::string log;
  const std::string json = runPage(dir, "screenshot&size=320x240&" + query, &log);
  EXPECT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 400) << "\n" << log;
  if (report) *report = json;
  return unbase64(jsonField(json, "rgb"));
}

const std::string kCamera = "eye=0.3,1.4,3.4;target=0,1,0;up=0,1,0;fov=45";

/// The Cornell box with RGB inter-reflected and scalar shadowed vectors (4 bands), and the
/// studio light at 4 bands, written once.
void cornell() {
  static const bool done = [] {
    Result r =
        prt("-q bake 'builtin:cornell?grid=12' --mode interreflected --mode shadowed "
            "--bands 4 --samples 64 -o three_cornell.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    r = prt("-q light builtin:studio --bands 4 -o three_studio.json");
    EXPECT_EQ(r.rc, 0) << r.err;
    return true;
  }();
  (void)done;
}

/// RMSE of the example's frame of the bake alone against prt render with the same settings.
double versusRender(const std::string& dir, const std::string& bake, const std::string& light,
                    const std::string& camera, const std::string& rotate, const std::string& mode,
                    const std::string& exposure, int bands, const std::string& pageRotate = "") {
  const std::string b = bands ? " --bands " + std::to_string(bands) : "";
  const Result r = prt("-q render " + bake + " --light " + light + " --rotate " + rotate +
                       " --camera '" + camera + "' --exposure " + exposure +
                       " --tonemap clamp --background none --size 320x240" +
                       (mode.empty() ? "" : " --mode " + mode) + b + " -o three.png");
  EXPECT_EQ(r.rc, 0) << r.err;
  const std::string q = "only&camera=" + camera +
                        "&rotate=" + (pageRotate.empty() ? rotate : pageRotate) +
                        "&exposure=" + exposure + (mode.empty() ? "" : "&mode=" + mode) +
                        (bands ? "&bands=" + std::to_string(bands) : "");
  return displayedRmse(exampleFrame(dir, q), path("three.png"));
}

TEST(Three, DenseVectorsRelightLikePrtRender) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  const std::string dir = examplePage("three_dense", "three_cornell.glb", "three_studio.json");
  for (const auto& [mode, rotate, exposure, bands] :
       std::vector<std::tuple<std::string, std::string, std::string, int>>{
           {"shadowed", "0,70,0", "0", 0}, {"interreflected", "20,-30,10", "0.5", 3}}) {
    SCOPED_TRACE(mode);
    const double e = versusRender(dir, "three_cornell.glb", "three_studio.json", kCamera, rotate,
                                  mode, exposure, bands);
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "three.js module vs prt render, " << mode << ": RMSE " << e << ", 90th percentile "
              << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: the light turned otherwise on the page is far off.
  EXPECT_GT(versusRender(dir, "three_cornell.glb", "three_studio.json", kCamera, "0,70,0",
                         "shadowed", "0", 0, "0,160,0"),
            2 * kMatch);
}

TEST(Three, CompressedVectorsAndGlossyMatricesRelightLikePrtRender) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  Result r =
      prt("-q compress three_cornell.glb --mode interreflected --clusters 24 --pca 5 "
          "-o three_cpca.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  std::string dir = examplePage("three_cpca", "three_cpca.glb", "three_studio.json");
  double e = versusRender(dir, "three_cpca.glb", "three_studio.json", kCamera, "20,-30,10",
                          "interreflected", "0", 0);
  EXPECT_LT(e, kMatch);
  EXPECT_LT(quantile90, kInterior);
  std::cout << "three.js module vs prt render, CPCA vectors: RMSE " << e << "\n";

  // Glossy: the lobe toward the camera's eye, from the kernels the file carries.
  r = prt(
      "-q bake 'builtin:sphere-plane?size=1.5&grid=40&subdiv=3' --mode shadowed --transfer "
      "matrix --bands 4 --samples 64 --material 'phong?exponent=8&ks=0.6&kd=0.4' -o three_g.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q compress three_g.glb --clusters 8 --pca 3 -o three_gc.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  dir = examplePage("three_glossy", "three_gc.glb", "three_studio.json");
  const std::string cam = "eye=0.4,1.3,2.3;target=0,0.8,0;up=0,1,0;fov=45";
  for (const auto& [rotate, bands] :
       std::vector<std::pair<std::string, int>>{{"0,0,0", 4}, {"20,70,0", 3}}) {
    SCOPED_TRACE(rotate);
    e = versusRender(dir, "three_gc.glb", "three_studio.json", cam, rotate, "", "-1", bands);
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "three.js module vs prt render, CPCA glossy, rotate " << rotate << ", " << bands
              << " bands: RMSE " << e << ", 90th percentile " << quantile90 * 255 << "/255\n";
  }
  // The lobe matters here: the same bake rendered as a Lambertian surface is far off.
  r = prt("-q render three_gc.glb --light three_studio.json --rotate 0,0,0 --camera '" + cam +
          "' --exposure -1 --tonemap clamp --background none --size 320x240 --material "
          "'lambert?kd=0.4' -o three_lambert.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_GT(displayedRmse(exampleFrame(dir, "only&camera=" + cam + "&rotate=0,0,0&exposure=-1"),
                          path("three_lambert.png")),
            2 * kMatch);
}

// Per-texel transfer (prt bake --domain texels): the module wears lightmap.vert and three.frag
// compiled with PRT_LIGHTMAP, which fetch, relight and blend the four texels of prt render's
// bilinear fetch per pixel at the lightmap UV (the glTF's TEXCOORD_n, under the name
// prtLightmapUv); dense RGB rows and CPCA rows from the per-frame cluster table.
TEST(Three, TexelBakesRelightPerPixelLikePrtRender) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  Result r =
      prt("-q bake 'builtin:cornell?grid=8' --mode interreflected --bands 4 --domain texels "
          "--resolution 64 --samples 256 -o three_texels.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q compress three_texels.glb --clusters 8 --pca 3 -o three_texels_cpca.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  for (const std::string bake : {"three_texels", "three_texels_cpca"}) {
    SCOPED_TRACE(bake);
    const std::string dir = examplePage(bake, bake + ".glb", "three_studio.json");
    const double e =
        versusRender(dir, bake + ".glb", "three_studio.json", kCamera, "20,-30,10", "", "0", 0);
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "three.js module vs prt render, per texel " << bake << ": RMSE " << e
              << ", 90th percentile " << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: the same frame under a turned light is far off.
  const std::string dir = examplePage("three_texels", "three_texels.glb", "three_studio.json");
  EXPECT_GT(versusRender(dir, "three_texels.glb", "three_studio.json", kCamera, "20,-30,10", "",
                         "0", 0, "0,150,0"),
            4 * kMatch);
}

TEST(Three, ExampleSceneDrawsStandardMaterialsBesideTheBake) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  const std::string dir = examplePage("three_scene", "three_cornell.glb", "three_studio.json");
  const std::string cam = "eye=0.5,2.5,9;target=0,0.8,0;up=0,1,0;fov=45";
  const std::string q = "camera=" + cam + "&rotate=0,30,0&mode=shadowed";
  std::string report;
  const std::vector<unsigned char> alone = exampleFrame(dir, "only&" + q);
  const std::vector<unsigned char> scene = exampleFrame(dir, q, &report);
  ASSERT_EQ(alone.size(), scene.size());
  ASSERT_FALSE(alone.empty());
  EXPECT_NE(report.find("\"meshes\":"), std::string::npos);
  std::size_t bake = 0, kept = 0, black = 0, drawn = 0;
  for (std::size_t p = 0; p + 2 < alone.size(); p += 3) {
    const int a = alone[p] + alone[p + 1] + alone[p + 2];
    const int d = std::abs(alone[p] - scene[p]) + std::abs(alone[p + 1] - scene[p + 1]) +
                  std::abs(alone[p + 2] - scene[p + 2]);
    if (a > 0) {
      ++bake;
      kept += d <= 6;
    } else {
      ++black;
      drawn += scene[p] + scene[p + 1] + scene[p + 2] > 24;
    }
  }
  ASSERT_GT(bake, alone.size() / 3 / 20) << "the bake covers too little of the frame to judge";
  // The bake's pixels are its own (the standard objects stand beside it, the floor below) ...
  EXPECT_GT(double(kept), 0.95 * double(bake)) << kept << " of " << bake;
  // ... and where the bake alone left black, the standard materials under the light probe show.
  EXPECT_GT(double(drawn), 0.10 * double(black)) << drawn << " of " << black;
}

// prt web's folder carries the example as three/, reading the page's own ../prt-data.js: the
// same bake under the page's first environment (its SH at the bake's bands).
TEST(Three, PrtWebFolderCarriesTheExampleForItsBake) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  Result r = prt("-q web three_cornell.glb --env builtin:sky --env builtin:studio -o three_web");
  ASSERT_EQ(r.rc, 0) << r.err;
  ASSERT_TRUE(fs::exists(scratch() / "three_web" / "three" / "example.js"));
  r = prt("-q render three_cornell.glb --light builtin:sky --rotate 0,40,0 --camera '" + kCamera +
          "' --exposure 0 --tonemap clamp --background none --size 320x240 --mode shadowed -o "
          "three_web.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string q = "only&camera=" + kCamera + "&rotate=0,40,0&exposure=0&mode=shadowed";
  std::string log;
  const std::string json = runPage(path("three_web/three"), "screenshot&size=320x240&" + q, &log);
  ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 300) << log;
  EXPECT_LT(displayedRmse(unbase64(jsonField(json, "rgb")), path("three_web.png")), kMatch);
  EXPECT_LT(quantile90, kInterior);
}

// Per-texel glossy matrices (CPCA) through the plugin's texelPoints option: the prt web folder's
// example passes the points prt web wrote beside the bake, and each tap is shaded at its texel's
// point as prt render relights it. The same file on its own (no points) is refused by name.
TEST(Three, TexelGlossyMatricesShadeAtThePointsPrtWebWrites) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  Result r =
      prt("-q bake 'builtin:cornell?grid=8' --mode shadowed --transfer matrix --bands 3 "
          "--domain texels --resolution 64 --samples 256 --material 'phong?ks=0.4&exponent=6' "
          "-o three_gt.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q compress three_gt.glb --clusters 16 --pca 6 -o three_gtc.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q web three_gtc.glb --env builtin:studio -o three_web_gt");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string cam = "eye=0.4,1.3,2.3;target=0,0.8,0;up=0,1,0;fov=45";
  for (const std::string& camera : {kCamera, cam}) {
    SCOPED_TRACE(camera);
    r = prt("-q render three_gtc.glb --light builtin:studio --rotate 20,70,0 --camera '" + camera +
            "' --exposure 0 --tonemap clamp --background none --size 320x240 -o three_gt.png");
    ASSERT_EQ(r.rc, 0) << r.err;
    std::string log;
    const std::string json = runPage(
        path("three_web_gt/three"),
        "screenshot&size=320x240&only&camera=" + camera + "&rotate=20,70,0&exposure=0", &log);
    ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 300) << log;
    const double e = displayedRmse(unbase64(jsonField(json, "rgb")), path("three_gt.png"));
    std::cout << "three.js module vs prt render, per-texel glossy CPCA: RMSE " << e
              << ", 90th percentile " << quantile90 * 255 << "/255\n";
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
  }
  r = prt("-q light builtin:studio --bands 3 -o three_studio3.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  std::string log;
  const std::string json =
      runPage(examplePage("three_gt_alone", "three_gtc.glb", "three_studio3.json"),
              "screenshot&size=64x48", &log);
  EXPECT_NE(json.find("\"ok\":false"), std::string::npos) << json.substr(0, 300) << log;
  EXPECT_NE(json.find("three_gtc.glb: per-texel glossy matrices are shaded at their texels' "
                      "sample points, which prt web writes beside its own bake"),
            std::string::npos)
      << json.substr(0, 400);
}

// The base-colour texture: the plugin keeps GLTFLoader's map of the bake's baseColorTexture and
// the module's stages multiply it into the diffuse part per pixel at TEXCOORD_0, the lobe added
// after, as prt render does (render/base_colour.hpp). A checker on a two-triangle square, per
// vertex (dense vectors, CPCA glossy) and per texel (vectors); the untextured square is far off.
TEST(Three, BaseColourTextureMultipliesPerPixel) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  const std::string obj = prt::testing::writeCheckerPlane(scratch());
  const std::string plain = prt::testing::writeCheckerPlane(scratch(), true);
  for (const std::string& cmd : std::vector<std::string>{
           "-q bake '" + obj + "' --mode shadowed --bands 4 --samples 64 -o three_tv.glb",
           "-q bake '" + plain + "' --mode shadowed --bands 4 --samples 64 -o three_tp.glb",
           "-q bake '" + obj +
               "' --mode shadowed --transfer matrix --bands 4 --samples 64 "
               "--material 'phong?exponent=8&ks=0.4' -o three_tg.glb",
           "-q compress three_tg.glb --clusters 2 --pca 2 -o three_tgc.glb",
           "-q bake '" + obj +
               "' --mode shadowed --bands 4 --samples 64 --domain texels "
               "--resolution 32 --uv auto -o three_ttv.glb"}) {
    const Result r = prt(cmd);
    ASSERT_EQ(r.rc, 0) << cmd << "\n" << r.err;
  }
  const std::string cam = "eye=0,2.5,3.5;target=0,0,0;up=0,1,0;fov=45";
  for (const std::string bake : {"three_tv", "three_tgc", "three_ttv"}) {
    SCOPED_TRACE(bake);
    const std::string dir = examplePage(bake, bake + ".glb", "three_studio.json");
    const double e =
        versusRender(dir, bake + ".glb", "three_studio.json", cam, "0,30,0", "", "0", 0);
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "three.js module vs prt render, textured " << bake << ": RMSE " << e
              << ", 90th percentile " << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: the textured frame against the untextured square's render.
  const Result r =
      prt("-q render three_tp.glb --light three_studio.json --rotate 0,30,0 --camera '" + cam +
          "' --exposure 0 --tonemap clamp --background none --size 320x240 "
          "-o three_tp.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const double off =
      displayedRmse(exampleFrame(examplePage("three_tv", "three_tv.glb", "three_studio.json"),
                                 "only&camera=" + cam + "&rotate=0,30,0&exposure=0"),
                    path("three_tp.png"));
  std::cout << "the texture left out: RMSE " << off << "\n";
  EXPECT_GT(off, 4 * kMatch);
}

// PRTBake's `encoding` (docs/three.md): a dense matrix bake drawn as an engine's irradiance
// encoding shades it, kd ⊙ Ê(n)/π per vertex made in JavaScript, matches prt render --encoding;
// frames of two encodings differ.
TEST(Three, EncodingsDrawMatricesLikePrtRenderEncoding) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  Result r =
      prt("-q bake 'builtin:cornell?grid=12' --mode interreflected --transfer matrix --bands 3 "
          "--samples 32 -o three_enc.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string dir = examplePage("three_enc", "three_enc.glb", "three_studio.json");
  const auto renderWith = [&](const std::string& encoding, const std::string& png) {
    const Result rr =
        prt("-q render three_enc.glb --light three_studio.json --rotate 20,-30,10 "
            "--camera '" +
            kCamera +
            "' --exposure 0 --tonemap clamp --background "
            "none --size 320x240 --encoding " +
            encoding + " -o " + png);
    EXPECT_EQ(rr.rc, 0) << rr.err;
  };
  const std::string q = "only&camera=" + kCamera + "&rotate=20,-30,10&exposure=0&encoding=";
  for (const std::string encoding : {"l1-windowed", "zh3", "l2-deringed"}) {
    SCOPED_TRACE(encoding);
    renderWith(encoding, "three_enc_" + encoding + ".png");
    std::string report;
    const double e = displayedRmse(exampleFrame(dir, q + encoding, &report),
                                   path("three_enc_" + encoding + ".png"));
    EXPECT_EQ(jsonField(report, "encoding"), encoding);
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "three.js module vs prt render --encoding " << encoding << ": RMSE " << e << "\n";
  }
  // The comparison can fail: zh3's frame is not l1-windowed's.
  EXPECT_GT(displayedRmse(exampleFrame(dir, q + "zh3"), path("three_enc_l1-windowed.png")), kMatch);
}

TEST(Three, PluginRefusesWhatItCannotShowNamingTheFile) {
  PRT_REQUIRE_EXAMPLE();
  cornell();
  // A dense glossy matrix: the shaders draw matrices compressed only; dense ones are drawn on
  // the CPU through an irradiance encoding (l2 unless one is chosen), their diffuse part.
  Result r =
      prt("-q bake 'builtin:sphere?subdiv=2' --mode shadowed --transfer matrix --bands 3 "
          "--samples 16 --material 'phong?exponent=8&ks=0.5' -o three_m.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  std::string log;
  std::string json = runPage(examplePage("three_m", "three_m.glb", "three_studio.json"),
                             "screenshot&size=64x48", &log);
  EXPECT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 300) << log;
  EXPECT_NE(json.find("\"path\":\"matrices relit on the CPU\""), std::string::npos)
      << json.substr(0, 600);
  EXPECT_EQ(jsonField(json, "encoding"), "l2");
  // An encoding on a vector bake: refused, naming the file (PRTBake's encoding, as prt render
  // --encoding).
  json = runPage(examplePage("three_v", "three_cornell.glb", "three_studio.json"),
                 "screenshot&size=64x48&encoding=zh3", &log);
  EXPECT_NE(json.find("three_cornell.glb: holds the interreflected vector transfer: encoding zh3 "
                      "encodes the light arriving at each row"),
            std::string::npos)
      << json << log;
  // A compressed glossy file without the kernels (as written before them): named.
  r = prt("-q compress three_m.glb --clusters 4 --pca 2 -o three_mc.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  std::string bytes = prt::testing::slurp(scratch() / "three_mc.glb");
  const std::size_t at = bytes.find("\"response\":{");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = bytes.find('}', at);
  ASSERT_EQ(bytes[end + 1], ',');
  bytes.replace(at, end + 2 - at, std::string(end + 2 - at, ' '));  // JSON whitespace
  std::ofstream(scratch() / "three_old.glb", std::ios::binary) << bytes;
  json = runPage(examplePage("three_old", "three_old.glb", "three_studio.json"),
                 "screenshot&size=64x48", &log);
  EXPECT_NE(json.find("\"ok\":false"), std::string::npos) << json << log;
  EXPECT_NE(json.find("three_old.glb: the shadowed glossy transfer carries no material kernels"),
            std::string::npos)
      << json;
  // A glTF that is not a bake (required by the example): said so.
  const std::string good = prt::testing::slurp(scratch() / "three_cornell.glb");
  const std::size_t ext = good.find("\"PRTKIT_radiance_transfer\":{");
  ASSERT_NE(ext, std::string::npos);
  std::string foreign = good;
  foreign[ext + 1] = 'X';
  std::ofstream(scratch() / "three_plain.glb", std::ios::binary) << foreign;
  json = runPage(examplePage("three_plain", "three_plain.glb", "three_studio.json"),
                 "screenshot&size=64x48", &log);
  EXPECT_NE(json.find("three_plain.glb: is a glTF file but not a prtkit bake"), std::string::npos)
      << json << log;
  // The control: the untouched compressed file shows.
  json = runPage(examplePage("three_mc", "three_mc.glb", "three_studio.json"),
                 "screenshot&size=64x48", &log);
  EXPECT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 300) << log;
}

}  // namespace
