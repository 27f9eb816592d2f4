// The Haar basis through the command line (issue 33): prt bake --basis haar, prt light --basis
// haar, prt render, prt validate and prt web handle it (tests/web/test_haar_web.cpp); every other
// verb refuses it by name; bad options get one line and write nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cli_harness.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/haar_light_file.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using HaarCli = CliTest;

constexpr const char* kScene = "'builtin:sphere-plane?grid=12&subdiv=2'";

double maxRelativeDifference(const image::Image& a, const image::Image& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = a.pixels[i][std::size_t(c)], y = b.pixels[i][std::size_t(c)];
      m = std::max(m, std::abs(x - y) / std::max(1e-3, std::abs(y)));
    }
  return m;
}

TEST_F(HaarCli, BakeInfoRenderValidate) {
  Result r = prt(std::string("-q bake ") + kScene +
                 " --mode shadowed --basis haar --resolution 16 --terms 40 -o h.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const BakeFile b = readBake(path("h.glb"));
  ASSERT_EQ(b.transfers.size(), 1u);
  EXPECT_TRUE(b.transfers[0].transfer.isHaar());
  EXPECT_EQ(b.transfers[0].transfer.shape().haar, (TransferShape::HaarSize{16, 40}));
  EXPECT_EQ(b.transfers[0].recipe.samples, 1);  // one ray per cube texel unless told
  r = prt("info h.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("Haar wavelets over a 16² cube"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("_PRT_SHADOWED_HAAR"), std::string::npos) << r.out;

  // Rendered from the environment and from a Haar light file of it: the same picture.
  const std::string common = " --background none --size 48x36 --spp 1 --exposure 0 ";
  r = prt("-q render h.glb --light builtin:sky --terms 300" + common + "-o env.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q light builtin:sky --basis haar --resolution 16 --terms 300 -o sky.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(io::readHaarLightJson(path("sky.json")).light.terms(), 300u);
  r = prt("info sky.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("prtkit Haar light"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the 300 largest (area)"), std::string::npos) << r.out;
  r = prt("-q render h.glb --light sky.json" + common + "-o file.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_LT(maxRelativeDifference(image::readImage(path("file.exr")),
                                  image::readImage(path("env.exr"))),
            1e-5);

  r = prt("validate h.glb --light builtin:sky --vertices 200 --reference-samples 256 --terms "
          "50,300 --json v.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("light terms"), std::string::npos) << r.out;
  const std::string report = slurp(path("v.json"));
  EXPECT_NE(report.find("\"basis\": \"haar\""), std::string::npos) << report;
  EXPECT_NE(report.find("\"lightTerms\": 1536"), std::string::npos) << report;  // whole cube
}

TEST_F(HaarCli, InterreflectedBakeInfoRenderValidate) {
  // --mode interreflected: each row holds its bounce in --bands SH bands (RGB under a coloured
  // albedo), and every verb that relights a Haar bake adds it.
  Result r = prt(std::string("-q bake ") + kScene +
                 " --mode interreflected --bounces 1 --albedo 0.9,0.6,0.3 --basis haar "
                 "--resolution 16 --terms 40 --bands 2 -o ir.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const BakeFile b = readBake(path("ir.glb"));
  EXPECT_EQ(b.transfers[0].transfer.shape().haar, (TransferShape::HaarSize{16, 40, 2}));
  EXPECT_EQ(b.transfers[0].transfer.channels(), 3);
  r = prt("info ir.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("its bounce in 2 SH bands x 3 channel(s)"), std::string::npos) << r.out;
  const std::string common = " --background none --size 48x36 --spp 1 --exposure 0 ";
  r = prt("-q render ir.glb --light builtin:sky --terms 300" + common + "-o env.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q light builtin:sky --basis haar --resolution 16 --terms 300 -o sky.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q render ir.glb --light sky.json" + common + "-o file.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  // The light file's SH for the bounce is rebuilt from its rest and bright texels.
  EXPECT_LT(
      maxRelativeDifference(image::readImage(path("file.exr")), image::readImage(path("env.exr"))),
      1e-4);
  r = prt("-q bake " + std::string(kScene) +
          " --mode shadowed --albedo 0.9,0.6,0.3 --basis haar --resolution 16 --terms 40 -o d.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q render d.glb --light builtin:sky --terms 300" + common + "-o direct.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  // The bounce brightens the picture somewhere (the plane under the sphere) and nowhere darkens it.
  const image::Image withBounce = image::readImage(path("env.exr")),
                     direct = image::readImage(path("direct.exr"));
  double brighter = 0, darker = 0;
  for (std::size_t i = 0; i < direct.pixels.size(); ++i) {
    brighter = std::max(brighter, double(withBounce.pixels[i][0] - direct.pixels[i][0]));
    darker = std::max(darker, double(direct.pixels[i][0] - withBounce.pixels[i][0]));
  }
  EXPECT_GT(brighter, 0.01);
  EXPECT_LT(darker, 0.01 * brighter);
  r = prt("validate ir.glb --light builtin:sky --vertices 200 --reference-samples 256 --terms 300");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE((r.out + r.err).find("mode interreflected"), std::string::npos) << r.out << r.err;
}

TEST_F(HaarCli, PerTexelBakeInfoRenderValidateMerge) {
  // Per texel: --resolution is the lightmap's side, --cube-resolution the cube's.
  const std::string bake = std::string("-q bake ") + kScene +
                           " --mode shadowed --basis haar --domain texels --resolution 24 "
                           "--cube-resolution 8 --terms 24 --samples 2 ";
  Result r = prt(bake + "-o t.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const BakeFile b = readBake(path("t.glb"));
  const Transfer& t = b.transfers[0].transfer;
  EXPECT_TRUE(t.isHaar());
  EXPECT_EQ(t.domain(), TransferDomain::Texels);
  EXPECT_EQ(t.shape().lightmap.width, 24);
  EXPECT_EQ(t.shape().haar, (TransferShape::HaarSize{8, 24}));
  r = prt("info t.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("Haar wavelets over a 8² cube"), std::string::npos) << r.out;
  // Two ranges merged: the whole bake's bytes.
  ASSERT_EQ(prt(bake + "--range 0:300 -o a.glb").rc, 0);
  ASSERT_EQ(prt(bake + "--range 300:576 -o b.glb").rc, 0);
  r = prt("-q merge a.glb b.glb -o m.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const BakeFile merged = readBake(path("m.glb"));
  const Transfer& m = merged.transfers[0].transfer;
  ASSERT_EQ(m.values().size(), t.values().size());
  EXPECT_TRUE(std::equal(m.values().begin(), m.values().end(), t.values().begin()));

  r =
      prt("-q render t.glb --light builtin:sky --background none --size 48x36 --spp 1 "
          "--exposure 0 -o t.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  const image::Image img = image::readImage(path("t.exr"));
  double lit = 0;
  for (const auto& p : img.pixels) lit = std::max(lit, double(p[0]));
  EXPECT_GT(lit, 0.05) << "the relit lightmap draws the scene";
  r =
      prt("validate t.glb --light builtin:sky --vertices 150 --reference-samples 256 --terms "
          "100 --json v.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("terms per texel"), std::string::npos) << r.out;
  const std::string report = slurp(path("v.json"));
  EXPECT_NE(report.find("\"basis\": \"haar\""), std::string::npos) << report;
  // What reads lightmaps as SH refuses it by name.
  expectCleanFailure("denoise t.glb -o out/d.glb", "Haar");
  expectCleanFailure("merge a.glb b.glb --seam-fix -o out/s.glb", "Haar");
}

TEST_F(HaarCli, OtherVerbsRefuseItByName) {
  ASSERT_EQ(prt(std::string("-q bake ") + kScene +
                " --mode shadowed --basis haar --resolution 8 --terms 8 -o h.glb")
                .rc,
            0);
  ASSERT_EQ(prt("-q light builtin:sky --bands 3 -o sh.json").rc, 0);
  ASSERT_EQ(prt("-q light builtin:sky --basis haar --resolution 16 -o h16.json").rc, 0);
  expectCleanFailure("compress h.glb -o out/c.glb", "holds Haar-wavelet transfer");
  expectCleanFailure("export h.glb --format games202 -o out/t.txt", "holds Haar-wavelet transfer");
  expectCleanFailure("render h.glb --light sh.json -o out/x.png", "is an SH light file");
  expectCleanFailure("render h.glb --light h16.json -o out/x.png", "16² cube");
  expectCleanFailure("render h.glb --turntable 3 -o out/x.png", "holds Haar transfer");
  expectCleanFailure("validate h.glb --light builtin:sky --bands-list 3", "holds Haar transfer");
  // An SH bake is not relit by a Haar light, nor given Haar options.
  ASSERT_EQ(prt(std::string("-q bake ") + kScene + " --mode shadowed --samples 16 -o s.glb").rc, 0);
  expectCleanFailure("render s.glb --light h16.json -o out/x.png", "Haar bakes");
  expectCleanFailure("render s.glb --terms 20 -o out/x.png", "--terms");
  expectCleanFailure("validate s.glb --light builtin:sky --terms 20", "--terms");
}

TEST_F(HaarCli, BadOptionsWriteNothing) {
  const std::string bake = std::string("bake ") + kScene + " --basis haar ";
  expectCleanFailure(bake + "--mode interreflected --bands 6 -o out/h.glb", "--bands");
  expectCleanFailure(bake + "--mode shadowed --transfer matrix -o out/h.glb", "vector");
  expectCleanFailure(bake + "--mode shadowed --domain probes --transfer vector -o out/h.glb",
                     "probe");
  expectCleanFailure(
      bake + "--mode shadowed --domain texels --resolution 16 --denoise -o out/h.glb", "--denoise");
  expectCleanFailure(
      bake + "--mode shadowed --domain texels --resolution 16 --seam-fix -o out/h.glb",
      "--seam-fix");
  expectCleanFailure(
      bake + "--mode shadowed --domain texels --resolution 16 --cube-resolution 12 -o out/h.glb",
      "--cube-resolution: the Haar cube's side must be a power of two");
  expectCleanFailure(bake + "--mode shadowed --resolution 8 --cube-resolution 8 -o out/h.glb",
                     "give one");
  expectCleanFailure(
      std::string("bake ") + kScene + " --mode shadowed --cube-resolution 8 -o out/h.glb",
      "--basis haar");
  expectCleanFailure(bake + "--mode shadowed --resolution 24 -o out/h.glb", "power of two");
  expectCleanFailure(bake + "--mode shadowed --resolution 8 --terms 385 -o out/h.glb", "terms");
  expectCleanFailure(bake + "--mode shadowed --samples 65 -o out/h.glb", "samples");
  expectCleanFailure(std::string("bake ") + kScene + " --mode shadowed --terms 5 -o out/h.glb",
                     "--basis haar");
  expectCleanFailure("light builtin:sky --basis haar --resolution 12 -o out/l.json", "power of two");
  expectCleanFailure("light builtin:sky --basis haar --resolution 4 --terms 97 -o out/l.json",
                     "96 coefficients");
  expectCleanFailure("light builtin:sky --basis haar -o out/l.txt", ".json");
  expectCleanFailure("light builtin:sky --terms 20 -o out/l.json", "--basis haar");
  // A Haar light file is not an SH light: its SH reader says so.
  ASSERT_EQ(prt("-q light builtin:sky --basis haar --resolution 4 -o h.json").rc, 0);
  ASSERT_EQ(prt("-q bake " + std::string(kScene) + " --mode shadowed --samples 16 -o s.glb").rc,
            0);
  expectCleanFailure("render s.glb --light h.json -o out/x.png", "Haar bakes");
}

}  // namespace
}  // namespace prt
