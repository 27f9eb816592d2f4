// Irradiance encodings in the page (issue 34; docs/web.md "Irradiance encodings", docs/lightmaps.md
// "Seeing an encoding"): the page's `encoding` option draws a per-vertex matrix bake as an
// engine's encoding shades it, kd ⊙ Ê(n)/π per vertex made in JavaScript
// (web/src/encoded_diffuse.js, irradiance_encoding.js), and must match `prt render --encoding`
// of the same bake, light, rotation and default view (RMSE < 0.02 on displayed [0, 1] colour,
// the interior within 2.5/255, as every frame test of tests/web):
//   * a dense matrix bake (which the page now draws on the CPU, through l2 unless an encoding is
//     chosen: then exactly PRT's own radiance for a 3-band diffuse bake) through l1,
//     l1-windowed, l1-geomerics, zh3, zh3-optimal and l2-deringed, and under a turned light;
//     frames of two encodings differ, so the comparison can fail;
//   * a CPCA-compressed matrix bake through an encoding (the light arriving at each vertex from
//     the frame's cluster table), and without one on the GPU as before;
//   * what cannot be encoded is refused in one line naming the file, by the page (?encoding=)
//     and by prt web --encoding, as prt render --encoding refuses it: a vector bake, a probe
//     bake, per-texel matrices, an unknown name.
// The JavaScript encodings themselves are held to the C++ under node (tests/web/golden, 1e-5).
// Each test skips, saying why, where chromium or the built page is missing.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "cli/cli_harness.hpp"
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

/// The page folder of a small dense matrix bake of the Cornell box (RGB inter-reflected, 3
/// bands, Lambertian) under builtin:sky and builtin:studio, written once; "" (and `why`) when
/// prt web cannot write it here.
const std::string& encodingFolder(std::string* why) {
  static std::string reason;
  static const std::string dir = []() -> std::string {
    Result r =
        prt("-q bake 'builtin:cornell?grid=12' --mode interreflected --transfer matrix --bands 3 "
            "--samples 32 -o enc_m.glb");
    if (r.rc != 0) return reason = "bake failed: " + r.err, "";
    r = prt("-q web enc_m.glb --env builtin:sky --env builtin:studio -o page_enc");
    if (r.rc != 0) return reason = "prt web failed: " + r.err, "";
    return path("page_enc");
  }();
  if (why) *why = reason;
  return dir;
}

#define PRT_REQUIRE_ENCODING_PAGE()                                                        \
  do {                                                                                     \
    if (chromium().empty()) GTEST_SKIP() << "no chromium here (apt-get install chromium)"; \
    std::string why_;                                                                      \
    if (encodingFolder(&why_).empty()) {                                                   \
      if (why_.find("assets") != std::string::npos) GTEST_SKIP() << why_;                  \
      FAIL() << why_;                                                                      \
    }                                                                                      \
  } while (0)

/// The ?screenshot frame (320x240, exposure 0) of the page in `dir` for QUERY, and its report.
std::vector<unsigned char> frame(const std::string& dir, const std::string& query,
                                 std::string* report = nullptr) {
  std::string log;
  const std::string json = runPage(dir, "screenshot&size=320x240&exposure=0&" + query, &log);
  EXPECT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 400) << "\n" << log;
  if (report) *report = json;
  return unbase64(jsonField(json, "rgb"));
}

/// prt render of `bake` at 320x240, exposure 0, with `args`, into `png`.
void render(const std::string& bake, const std::string& args, const std::string& png) {
  const Result r = prt("-q render --exposure 0 " + bake + " --size 320x240 " + args + " -o " + png);
  ASSERT_EQ(r.rc, 0) << r.err;
}

TEST(WebEncodings, DenseMatricesThroughEachEncodingMatchPrtRender) {
  PRT_REQUIRE_ENCODING_PAGE();
  const std::string dir = encodingFolder(nullptr);
  struct Case {
    std::string encoding, light, rotate, env;
  };
  for (const Case& c :
       {Case{"l1", "builtin:sky", "0,0,0", "0"}, Case{"l1-windowed", "builtin:sky", "0,0,0", "0"},
        Case{"l1-geomerics", "builtin:sky", "0,0,0", "0"}, Case{"zh3", "builtin:sky", "0,0,0", "0"},
        Case{"zh3-optimal", "builtin:studio", "20,-30,10", "1"},
        Case{"l2-deringed", "builtin:sky", "0,0,0", "0"}}) {
    SCOPED_TRACE(c.encoding + " under " + c.light + " turned " + c.rotate);
    render("enc_m.glb",
           "--light " + c.light + " --rotate " + c.rotate + " --encoding " + c.encoding,
           "enc_" + c.encoding + ".png");
    std::string report;
    const std::vector<unsigned char> rgb =
        frame(dir, "env=" + c.env + "&rotate=" + c.rotate + "&encoding=" + c.encoding, &report);
    EXPECT_EQ(jsonField(report, "encoding"), c.encoding);
    EXPECT_EQ(jsonField(report, "path"), "CpuRadiance");
    const double e = displayedRmse(rgb, path("enc_" + c.encoding + ".png"));
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "page vs prt render --encoding " << c.encoding << ": RMSE " << e
              << ", 90th percentile " << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: the page's l1 frame is not prt render's l2-deringed one (the
  // interior differs, not only the edges).
  const double apart = displayedRmse(frame(dir, "env=0&encoding=l1"), path("enc_l2-deringed.png"));
  std::cout << "page l1 vs prt render l2-deringed: RMSE " << apart << ", 90th percentile "
            << quantile90 * 255 << "/255\n";
  EXPECT_GT(apart, kMatch);
  EXPECT_GT(quantile90, 2 * kInterior);
}

TEST(WebEncodings, DenseMatricesWithoutOneAreL2WhichIsPrtsOwnRadiance) {
  PRT_REQUIRE_ENCODING_PAGE();
  // No encoding chosen: the dense matrices are drawn through l2, which for a 3-band diffuse bake
  // is PRT's own radiance (the 3-band irradiance exactly): both renders match the frame.
  std::string report;
  const std::vector<unsigned char> rgb = frame(encodingFolder(nullptr), "env=0", &report);
  EXPECT_EQ(jsonField(report, "encoding"), "l2");
  render("enc_m.glb", "--light builtin:sky --encoding l2", "enc_l2.png");
  render("enc_m.glb", "--light builtin:sky", "enc_plain.png");
  for (const char* png : {"enc_l2.png", "enc_plain.png"}) {
    const double e = displayedRmse(rgb, path(png));
    EXPECT_LT(e, kMatch) << png;
    EXPECT_LT(quantile90, kInterior) << png;
  }
}

TEST(WebEncodings, CompressedMatricesThroughAnEncodingMatchPrtRender) {
  PRT_REQUIRE_ENCODING_PAGE();
  Result r = prt("-q compress enc_m.glb --clusters 16 --pca 4 -o enc_mc.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q web enc_mc.glb --env builtin:sky -o page_enc_c");
  ASSERT_EQ(r.rc, 0) << r.err;
  for (const std::string encoding : {"zh3", "none"}) {
    SCOPED_TRACE(encoding);
    render("enc_mc.glb", "--light builtin:sky --encoding " + encoding, "enc_c.png");
    std::string report;
    const std::vector<unsigned char> rgb =
        frame(path("page_enc_c"), "env=0&encoding=" + encoding, &report);
    EXPECT_EQ(jsonField(report, "path"), "CpcaMatrix");
    EXPECT_EQ(jsonField(report, "encoding"), encoding);
    const double e = displayedRmse(rgb, path("enc_c.png"));
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "page vs prt render, CPCA matrices, encoding " << encoding << ": RMSE " << e
              << "\n";
  }
}

TEST(WebEncodings, WhatCannotBeEncodedIsRefusedNamingTheFile) {
  PRT_REQUIRE_ENCODING_PAGE();
  // The page: a vector bake with ?encoding=, and an unknown name, refused in one line.
  Result r =
      prt("-q bake 'builtin:cornell?grid=6' --mode shadowed --bands 3 --samples 16 -o "
          "enc_v.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q web enc_v.glb -o page_enc_v");
  ASSERT_EQ(r.rc, 0) << r.err;
  std::string json = runPage(path("page_enc_v"), "screenshot&size=64x48&encoding=l1");
  EXPECT_NE(json.find("\"ok\":false"), std::string::npos) << json;
  EXPECT_NE(json.find("enc_v.glb: holds the shadowed vector transfer: encoding l1 encodes the "
                      "light arriving at each row, which a matrix bake holds"),
            std::string::npos)
      << json;
  json = runPage(encodingFolder(nullptr), "screenshot&size=64x48&encoding=l3");
  EXPECT_NE(json.find("enc_m.glb: encoding must be l2, l2-deringed, l1"), std::string::npos)
      << json;
  EXPECT_NE(json.find("got 'l3'"), std::string::npos) << json;
  // The control: the same vector page draws without one.
  json = runPage(path("page_enc_v"), "screenshot&size=64x48");
  EXPECT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 300);

  // prt web --encoding: refused as prt render --encoding refuses it, before anything is written.
  r = prt("-q probes 'builtin:cornell?grid=6' --grid 2x2x2 --bands 3 --samples 8 -o enc_p.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r =
      prt("-q bake 'builtin:cornell?grid=6' --mode shadowed --domain texels --resolution 16 "
          "--transfer matrix --bands 3 --samples 8 -o enc_t.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q compress enc_t.glb --clusters 4 --pca 2 -o enc_tc.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  struct Refusal {
    std::string bake, encoding, says, also;
  };
  for (const Refusal& c :
       {Refusal{"enc_v.glb", "l1",
                "enc_v.glb: holds shadowed vector transfer: --encoding encodes the light arriving "
                "at each row",
                "matrix bake"},
        Refusal{"enc_p.glb", "zh3", "enc_p.glb: holds a probe grid: --encoding", "matrix"},
        Refusal{"enc_tc.glb", "l2", "enc_tc.glb: holds ", "per vertex only"},
        Refusal{"enc_m.glb", "l9", "encoding must be l2, l2-deringed", "got 'l9'"}}) {
    SCOPED_TRACE(c.bake + " --encoding " + c.encoding);
    r = prt("web " + c.bake + " --encoding " + c.encoding + " -o nope_enc");
    EXPECT_EQ(r.rc, 1);
    EXPECT_NE(r.err.find("prt web: error: " + c.says), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.also), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(path("nope_enc")));
  }
  // The page refuses per-texel matrices with an encoding too (it draws one per vertex only).
  r = prt("-q web enc_tc.glb -o page_enc_t");
  ASSERT_EQ(r.rc, 0) << r.err;
  json = runPage(path("page_enc_t"), "screenshot&size=64x48&encoding=zh3");
  EXPECT_NE(json.find("enc_tc.glb: holds the shadowed matrices per texel: the browser viewers "
                      "draw encoding zh3 per vertex only"),
            std::string::npos)
      << json;
}

}  // namespace
