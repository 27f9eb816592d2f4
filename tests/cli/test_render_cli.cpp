// prt render / merge / demo through the real binary: SH light files relight exactly like the
// environment they came from, split bakes merge into the full bake, the demo produces its folder
// (and nothing at all when it fails), bad input fails cleanly.

#include <gtest/gtest.h>

#include "common/random_data.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/render/exposure.hpp"
#include "prt/sh/sh.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using RenderCli = CliTest;

// A small shadowed scene, quick to bake (sphere over a plane, 3 bands).
constexpr const char* kScene = "'builtin:sphere-plane?grid=12&subdiv=2'";

/// The one entry in `dir` ("" if none, "several" if more).
std::string onlyEntry(const std::filesystem::path& dir) {
  std::string name;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    name = name.empty() ? e.path().filename().string() : "several";
  return name;
}

double maxRelativeDifference(const image::Image& a, const image::Image& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  double worst = 0, peak = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, double(std::abs(a.pixels[i][c] - b.pixels[i][c])));
      peak = std::max(peak, double(std::abs(a.pixels[i][c])));
    }
  }
  return worst / std::max(peak, 1e-30);
}

TEST_F(RenderCli, LightFilesRelightLikeTheirEnvironment) {
  ASSERT_EQ(prt(std::string("-q bake ") + kScene + " --mode shadowed --samples 64 -o s.glb").rc, 0);
  ASSERT_EQ(prt("-q light builtin:sky --bands 3 -o sky.json").rc, 0);
  ASSERT_EQ(prt("-q light builtin:sky --bands 3 --format games202 -o sky.txt").rc, 0);
  const std::string common = " --background none --size 64x48 --spp 1 ";
  Result r = prt("-q render s.glb --light builtin:sky" + common + "-o env.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q render s.glb --light sky.json" + common + "-o json.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q render s.glb --light sky.txt" + common + "-o txt.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  const image::Image env = image::readImage(path("env.exr"));
  // The files hold the same projection to 9 significant digits; EXR keeps the floats.
  EXPECT_LT(maxRelativeDifference(env, image::readImage(path("json.exr"))), 1e-5);
  EXPECT_LT(maxRelativeDifference(env, image::readImage(path("txt.exr"))), 1e-5);

  // A rotated light is not the same picture (the test above can fail).
  r = prt("-q render s.glb --light sky.json --rotate 0,120,0" + common + "-o rot.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_GT(maxRelativeDifference(env, image::readImage(path("rot.exr"))), 1e-2);

  // Fewer light bands than the bake: used as is, with a warning, not an error.
  ASSERT_EQ(prt("-q light builtin:sky --bands 2 -o sky2.json").rc, 0);
  r = prt("render s.glb --light sky2.json" + common + "-o two.png");
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;

  write("bad.json", "{\"bands\": 2, \"coefficients\": [[1, 2, 3]]}");
  expectCleanFailure("render s.glb --light bad.json -o out/x.png", "bad.json");
  write("bad.txt", "1 2 3\n4 5\n");
  expectCleanFailure("render s.glb --light bad.txt -o out/x.png", "bad.txt");
  expectCleanFailure("render s.glb --size 0x10 -o out/x.png", "size");
  expectCleanFailure("render s.glb -o out/x.bmp", ".png");
  expectCleanFailure("render s.glb -o no/such/dir/x.png", "no/such/dir");
  expectCleanFailure("render missing.glb -o out/x.png", "missing.glb");
}

TEST_F(RenderCli, InfoDescribesLightsAndEnvironments) {
  // A constant grey environment of 0.5: mean radiance 0.5, nothing above band 0.
  ASSERT_EQ(prt("-q light 'builtin:constant?value=0.5' --bands 3 -o c.json").rc, 0);
  ASSERT_EQ(prt("-q light 'builtin:constant?value=0.5' --bands 3 -o c.txt").rc, 0);
  for (const char* f : {"c.json", "c.txt"}) {
    const Result r = prt(std::string("info ") + f);
    ASSERT_EQ(r.rc, 0) << r.err;
    EXPECT_NE(r.out.find("bands       3 (9 coefficients)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("mean        0.5 0.5 0.5"), std::string::npos) << r.out;
  }
  EXPECT_NE(prt("info c.txt").out.find("GAMES202 light.txt"), std::string::npos);
  // The sky: its sun direction from band 1 points up (positive elevation) toward the sun.
  Result r = prt("info 'builtin:sky?elevation=40&azimuth=0'");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("solid angle 1.000000 x 4 pi"), std::string::npos) << r.out;
  const std::size_t at = r.out.find("elevation ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_GT(std::stod(r.out.substr(at + 10)), 15.0) << r.out;
  image::writeImage(path("env.exr"), image::Image(64, 32, Rgb(2.0f)));
  r = prt("info env.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("layout latlong"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("64x32, 2048 texels"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mean 2 2 2"), std::string::npos) << r.out;
  write("what.bin", "nothing");
  expectCleanFailure("info what.bin", "unknown file type");
  write("bad.json", "{\"bands\": 2}");
  expectCleanFailure("info bad.json", "bad.json");
}

TEST_F(RenderCli, MergeJoinsSplitBakesExactly) {
  const std::string bake = std::string("-q bake ") + kScene + " --mode shadowed --samples 32 ";
  ASSERT_EQ(prt(bake + "-o full.glb").rc, 0);
  const BakeFile full = readBake(path("full.glb"));
  const std::size_t n = full.mesh.vertexCount(), cut = n / 3;
  ASSERT_EQ(prt(bake + "--range " + std::to_string(cut) + ": -o b.glb").rc, 0);
  ASSERT_EQ(prt(bake + "--range 0:" + std::to_string(cut) + " -o a.glb").rc, 0);
  Result r = prt("merge b.glb a.glb -o out/m.glb");  // any order
  ASSERT_EQ(r.rc, 0) << r.err;
  const BakeFile merged = readBake(path("out/m.glb"));
  EXPECT_TRUE(merged.complete());
  ASSERT_EQ(merged.transfers.size(), 1u);
  EXPECT_EQ(testdata::valuesOf(merged.transfers[0].transfer),
            testdata::valuesOf(full.transfers[0].transfer));
  std::filesystem::remove(path("out/m.glb"));

  // Gaps, overlaps, other meshes, other settings, bad arguments.
  ASSERT_EQ(prt(bake + "--range 1:" + std::to_string(cut + 1) + " -o shifted.glb").rc, 0);
  expectCleanFailure("merge a.glb shifted.glb -o out/m.glb", "overlaps");
  ASSERT_EQ(prt(bake + "--range " + std::to_string(cut + 1) + ": -o late.glb").rc, 0);
  expectCleanFailure("merge a.glb late.glb -o out/m.glb", "gap");
  ASSERT_EQ(prt("-q bake 'builtin:sphere?subdiv=2' --mode shadowed --samples 32 --range 5: "
                "-o other.glb")
                .rc,
            0);
  expectCleanFailure("merge a.glb other.glb -o out/m.glb", "different mesh");
  ASSERT_EQ(prt(std::string("-q bake ") + kScene + " --mode shadowed --samples 16 --range " +
                std::to_string(cut) + ": -o fewer.glb")
                .rc,
            0);
  expectCleanFailure("merge a.glb fewer.glb -o out/m.glb", "different settings");
  expectCleanFailure("merge a.glb -o out/m.glb", "at least two");
  expectCleanFailure("merge a.glb b.glb -o out/m.txt", ".glb");
  expectCleanFailure("merge a.glb missing.glb -o out/m.glb", "missing.glb");
}

TEST_F(RenderCli, DemoMakesItsFolderOrNothing) {
  const std::string tiny =
      "demo --mesh 'builtin:sphere-plane?grid=8&subdiv=1' --env builtin:sky --env "
      "'builtin:constant?value=0.5' --samples 16 --reference-samples 16 --frames 2 ";
  const std::string small = tiny +
                            "--bands 3 --size 48x36 --glossy-bands 3 --glossy-samples 16 "
                            "--glossy 'phong?exponent=4&ks=0.5&kd=0.5' ";
  Result r = prt("-q " + small + "-o out/demo");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::filesystem::path d = dir_ / "out/demo";
  const std::string html = slurp(d / "index.html");
  for (const char* needle : {"unshadowed", "shadowed", "interreflected", "builtin:sky",
                             "builtin:constant?value=0.5", "truncation floor", "energy-weighted",
                             "glossy: interreflected transfer matrices, phong?exponent=4",
                             "lobe energy &gt; b", "glossy.glb"})
    EXPECT_NE(html.find(needle), std::string::npos) << needle;
  for (const char* file :
       {"scene.glb", "lights/sky.json", "lights/constant.json", "img/sky_shadowed_prt.png",
        "img/sky_shadowed_ref.png", "img/sky_shadowed_err.png", "img/sky_comparison.png",
        "img/constant_turn_01.png", "img/constant_turntable.png",
        "validation/sky_interreflected.json", "glossy.glb", "img/sky_glossy_prt.png",
        "img/sky_glossy_ref.png", "img/sky_glossy_err.png", "validation/constant_glossy.json"})
    EXPECT_TRUE(std::filesystem::exists(d / file)) << file;
  const BakeFile bake = readBake((d / "scene.glb").string());
  EXPECT_EQ(bake.transfers.size(), 3u);
  // The glossy rows: shadowed matrices with the material, and a validation whose lobe column
  // is the lobe's zonal energy beyond b bands (falls with b; exponent 4 keeps some beyond 3).
  const BakeFile glossy = readBake((d / "glossy.glb").string());
  ASSERT_EQ(glossy.transfers.size(), 1u);
  EXPECT_TRUE(glossy.transfers[0].transfer.isMatrix());
  EXPECT_EQ(glossy.transfers[0].transfer.bands(), 3);
  EXPECT_EQ(glossy.transfers[0].recipe.material.spec(), "phong?exponent=4&ks=0.5&kd=0.5");
  const std::string v = slurp(d / "validation/sky_glossy.json");
  std::vector<double> lobe;
  for (std::size_t at = v.find("\"lobeEnergyBeyond\": "); at != std::string::npos;
       at = v.find("\"lobeEnergyBeyond\": ", at + 1))
    lobe.push_back(std::stod(v.substr(at + 20)));
  ASSERT_EQ(lobe.size(), 3u) << v;
  EXPECT_GT(lobe[0], lobe[1]);
  EXPECT_GT(lobe[1], lobe[2]);
  EXPECT_GT(lobe[2], 0.0);
  // Every image the HTML names exists.
  for (std::size_t at = html.find("src=\""); at != std::string::npos;
       at = html.find("src=\"", at + 1)) {
    const std::size_t end = html.find('"', at + 5);
    EXPECT_TRUE(std::filesystem::exists(d / html.substr(at + 5, end - at - 5)))
        << html.substr(at + 5, end - at - 5);
  }
  // The live viewer (prt web) sits above the images when its page is built.
  if (html.find("src=\"web/index.html\"") != std::string::npos) {
    EXPECT_TRUE(std::filesystem::exists(d / "web/prt-data.js"));
    EXPECT_TRUE(std::filesystem::exists(d / "web/prt-web.js"));
    // The page opens at the stills' exposure of the first environment (one auto exposure).
    const std::string tag = "<h2 data-exposure=\"";
    const std::size_t at = html.find(tag);
    ASSERT_NE(at, std::string::npos);
    const std::string stills = html.substr(at + tag.size(), html.find('"', at + tag.size()) -
                                                                  at - tag.size());
    const std::string data = slurp(d / "web/prt-data.js");
    EXPECT_NE(data.find("\"exposure\":" + stills), std::string::npos)
        << "stills at " << stills << " stops; the page's view: "
        << data.substr(data.find("\"view\""), 200);
    EXPECT_NE(std::stod(stills), 0.0);
  }
  EXPECT_EQ(onlyEntry(dir_ / "out"), "demo");  // no partial folder beside it

  // A second run replaces the folder; a failing run leaves the old one and no partial folder.
  r = prt("-q " + small + "--env missing.exr -o out/demo");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("missing.exr"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::exists(d / "index.html"));
  EXPECT_EQ(onlyEntry(dir_ / "out"), "demo");  // no partial folder beside it
  std::filesystem::remove_all(d);
  expectCleanFailure(tiny + "--bands 0 -o out/demo", "--bands");
  expectCleanFailure(tiny + "--size 0x0 -o out/demo", "size");
  expectCleanFailure(tiny + "--frames many -o out/demo", "--frames");
  expectCleanFailure(tiny + "--glossy lambert -o out/demo", "--glossy 'lambert': no glossy lobe");
  expectCleanFailure(tiny + "--glossy 'phong?size=2' -o out/demo", "phong?size=2");
  expectCleanFailure(tiny + "--glossy-bands 0 -o out/demo", "--glossy-bands");
  expectCleanFailure("demo --mesh nothing.obj -o out/demo", "nothing.obj");
  // A folder that is not an earlier demo is never replaced.
  std::filesystem::create_directories(dir_ / "out/mine");
  write("out/mine/keep.txt", "precious");
  r = prt("-q " + small + "-o out/mine");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("not a prt demo folder"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir_ / "out/mine/keep.txt"), "precious");
  EXPECT_EQ(onlyEntry(dir_ / "out"), "mine");
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

// Issue 35: SH ringing that blacks out the model is said, with its share. A delta light from
// straight above cut to 5 bands has irradiance E(θ = π) = 1/4 − 1/2 + 5/16 − 3/32 = −1/32 < 0:
// the underside of a sphere relit by it (unshadowed) is negative; under a constant light the
// same bake is nowhere negative, and no warning is printed.
TEST_F(RenderCli, SaysWhenRingingBlacksOutTheModel) {
  ASSERT_EQ(prt("-q bake 'builtin:sphere?subdiv=3' --mode unshadowed --bands 5 --samples 64 "
                "-o s5.glb")
                .rc,
            0);
  io::LightFile delta;
  delta.coefficients = sh::RgbSh(5);
  double y[25];
  sh::eval(5, Vec3d(0, 1, 0), y);
  for (int i = 0; i < 25; ++i) delta.coefficients.c[i] = Rgb(float(y[i]));
  io::writeLightJson(path("delta.json"), delta);
  // Seen from below (the camera under the sphere) most of what is visible rings.
  const std::string below = " --camera 'eye=0,-3,0.5;target=0,0,0;fov=45' --size 160x120 ";
  Result r = prt("render s5.glb --light delta.json" + below + "-o d.png --json d.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the relit radiance is negative on "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("of the model's pixels, drawn black"), std::string::npos) << r.err;
  const std::string report = slurp(path("d.json"));
  const std::size_t at = report.find("\"negativeShare\": ");
  ASSERT_NE(at, std::string::npos) << report;
  const double share = std::stod(report.substr(at + 17));
  EXPECT_GT(share, render::kNegativeShareWarned);
  r = prt("render s5.glb --light builtin:constant" + below + "-o c.png --json c.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.err.find("negative"), std::string::npos) << r.err;
  const std::string constant = slurp(path("c.json"));
  EXPECT_NE(constant.find("\"negativeShare\": 0"), std::string::npos) << constant;
}

}  // namespace
}  // namespace prt
