// prt web (docs/web.md): the page in headless Chromium (Debian's `chromium`, software GL through
// SwiftShader) against the library.
//   * its first frame (?screenshot) matches prt render of the same bake, light, rotation and
//     default view: RMSE < 0.02 on displayed [0, 1] colour; a turned light must not match;
//   (what the page computes as the library does — SH rotation, cluster projection, decoding,
//   framing, the light rule — is checked under node, without a browser: tests/web/golden/);
//   * bad dropped files leave the scene (bake, environments, pixels) as it was and say why; a
//     light with fewer bands than the bake is padded with the library's warning;
//   * CPCA-compressed bakes (version 3), diffuse vectors and glossy matrices, are relit in the
//     compressed space and match prt render.
// Each test skips, saying why, where chromium, node or the built page is missing.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "cli/cli_harness.hpp"
#include "common/checker_plane.hpp"
#include "common/scratch.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/lighting.hpp"
#include "web/page_harness.hpp"

namespace {

namespace fs = std::filesystem;
using prt::testing::Result;
using namespace web_harness;

const bool kCleanup = prt::testing::registerProgramScratchCleanup("web");

Result prt(const std::string& args) {
  return prt::testing::runPrt(scratch(), args);
}
std::string path(const std::string& name) {
  return (scratch() / name).string();
}

/// The page folder for a small Cornell box (RGB interreflected + scalar shadowed, 4 bands)
/// under builtin:sky, written once; "" (and `why`) when prt web cannot write it here.
const std::string& webFolder(std::string* why) {
  static std::string reason;
  static const std::string dir = []() -> std::string {
    Result r =
        prt("-q bake 'builtin:cornell?grid=12' --mode interreflected --mode shadowed "
            "--bands 4 --samples 64 -o cornell.glb");
    if (r.rc != 0) return reason = "bake failed: " + r.err, "";
    r = prt("-q web cornell.glb --env builtin:sky --env builtin:studio -o page");
    if (r.rc != 0) return reason = "prt web failed: " + r.err, "";
    return path("page");
  }();
  if (why) *why = reason;
  return dir;
}

#define PRT_REQUIRE_PAGE()                                                                 \
  do {                                                                                     \
    if (chromium().empty()) GTEST_SKIP() << "no chromium here (apt-get install chromium)"; \
    std::string why_;                                                                      \
    if (webFolder(&why_).empty()) {                                                        \
      if (why_.find("assets") != std::string::npos) GTEST_SKIP() << why_;                  \
      FAIL() << why_;                                                                      \
    }                                                                                      \
  } while (0)

/// The page's ?screenshot frame for QUERY (320x240, as tests/viewer compare prt view) as RGB bytes.
std::vector<unsigned char> pageFrame(const std::string& query) {
  std::string log;
  // At exposure 0 unless asked: these compare the drawing, and the written auto exposure is the
  // page's first view's, not that of the query's light.
  const std::string q =
      query.find("exposure=") == std::string::npos ? "exposure=0&" + query : query;
  const std::string json = runPage(webFolder(nullptr), "screenshot&size=320x240&" + q, &log);
  EXPECT_NE(json.find("\"ok\":true"), std::string::npos) << json << "\n" << log;
  return unbase64(jsonField(json, "rgb"));
}

TEST(Web, FirstFrameMatchesPrtRenderScalar) {
  PRT_REQUIRE_PAGE();
  const Result r =
      prt("-q render --exposure 0 cornell.glb --light builtin:sky --rotate 0,70,0 --mode shadowed "
          "--size 320x240 -o shadowed.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const double same =
      displayedRmse(pageFrame("env=0&rotate=0,70,0&mode=shadowed"), path("shadowed.png"));
  EXPECT_LT(same, kMatch);
  EXPECT_LT(quantile90, kInterior);
  std::cout << "page vs prt render, scalar: RMSE " << same << ", 90th percentile "
            << quantile90 * 255 << "/255\n";
  // The test can fail: another light rotation is far off.
  const double turned =
      displayedRmse(pageFrame("env=0&rotate=0,160,0&mode=shadowed"), path("shadowed.png"));
  EXPECT_GT(turned, 4 * kMatch) << "same " << same;
}

TEST(Web, FirstFrameMatchesPrtRenderRgbAndToneMap) {
  PRT_REQUIRE_PAGE();
  const Result r =
      prt("-q render cornell.glb --light builtin:studio --rotate 20,-30,10 "
          "--mode interreflected --bands 3 --exposure 0.5 --tonemap reinhard "
          "--size 320x240 -o rgb.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const double rmse = displayedRmse(
      pageFrame("env=1&rotate=20,-30,10&mode=interreflected&bands=3&exposure=0.5&tonemap=reinhard"),
      path("rgb.png"));
  EXPECT_LT(rmse, kMatch);
  EXPECT_LT(quantile90, kInterior);
  std::cout << "page vs prt render, RGB: RMSE " << rmse << ", 90th percentile " << quantile90 * 255
            << "/255\n";
}

TEST(Web, GivenCameraMatchesPrtRender) {
  PRT_REQUIRE_PAGE();
  const std::string cam = "eye=1.2,2.2,2.6;target=0.1,0.2,0;up=0.2,1,0;fov=55";
  Result r = prt("-q web cornell.glb --env builtin:studio --camera '" + cam + "' -o page_cam");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q render --exposure 0 cornell.glb --light builtin:studio --camera '" + cam +
          "' --mode shadowed --size 320x240 -o cam.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string json =
      runPage(path("page_cam"), "screenshot&size=320x240&exposure=0&mode=shadowed");
  const double e = displayedRmse(unbase64(jsonField(json, "rgb")), path("cam.png"));
  EXPECT_LT(e, kMatch) << json.substr(0, 200);
  EXPECT_LT(quantile90, kInterior);
  // The default framing is another view: far off.
  EXPECT_GT(displayedRmse(pageFrame("env=1&mode=shadowed"), path("cam.png")), 4 * kMatch);
}

// CPCA-compressed transfer (prt compress, bake version 3): the page keeps it compressed (ids and
// weights per vertex in a data texture), projects the rotated light onto the K(N+1) cluster
// vectors in JS each frame and sums N weighted values per vertex in the shader; prt render
// relights the same compressed rows on the CPU. Both transfers of the Cornell box compressed:
// RGB inter-reflected with N = 5 (two texels per vertex), scalar shadowed with N = 2 (one).
TEST(Web, CompressedFirstFrameMatchesPrtRender) {
  PRT_REQUIRE_PAGE();
  Result r = prt("-q compress cornell.glb --mode interreflected --clusters 24 --pca 5 -o c1.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q compress c1.glb --mode shadowed --clusters 16 --pca 2 -o cpca.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q web cpca.glb --env builtin:sky --env builtin:studio -o page_cpca");
  ASSERT_EQ(r.rc, 0) << r.err;
  struct Case {
    std::string render, query, compressed;
  };
  for (const Case& c :
       {Case{"--light builtin:studio --rotate 20,-30,10 --mode interreflected",
             "env=1&rotate=20,-30,10&mode=interreflected", "24x5, 32 bytes per vertex"},
        Case{"--light builtin:sky --rotate 0,70,0 --mode shadowed --bands 3",
             "env=0&rotate=0,70,0&mode=shadowed&bands=3", "16x2, 16 bytes per vertex"}}) {
    SCOPED_TRACE(c.query);
    r = prt("-q render --exposure 0 cpca.glb --size 320x240 " + c.render + " -o cpca.png");
    ASSERT_EQ(r.rc, 0) << r.err;
    std::string log;
    const std::string json =
        runPage(path("page_cpca"), "screenshot&size=320x240&exposure=0&" + c.query, &log);
    ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json << "\n" << log;
    EXPECT_EQ(jsonField(json, "compressed"), c.compressed);
    const double e = displayedRmse(unbase64(jsonField(json, "rgb")), path("cpca.png"));
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "page vs prt render, compressed " << c.compressed << ": RMSE " << e
              << ", 90th percentile " << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: the compressed page under another rotation is far off.
  const std::string json = runPage(
      path("page_cpca"), "screenshot&size=320x240&env=0&rotate=0,160,0&mode=shadowed&bands=3");
  EXPECT_GT(displayedRmse(unbase64(jsonField(json, "rgb")), path("cpca.png")), 4 * kMatch);
}

// CPCA-compressed glossy matrices: the page projects the light onto every cluster's mean and
// basis matrices in JS (B² RGB values each), and the vertex shader forms L'_v and shades it with
// the bake's material (kernels from prt web) toward the camera's eye, as prt view --glossy-on
// gpu; prt render relights the same compressed matrices on the CPU.
TEST(Web, CompressedGlossyFirstFrameMatchesPrtRender) {
  PRT_REQUIRE_PAGE();
  Result r =
      prt("-q bake 'builtin:sphere-plane?size=1.5&grid=40&subdiv=3' --mode shadowed --transfer "
          "matrix --bands 4 --samples 64 --material 'phong?exponent=8&ks=0.6&kd=0.4' -o g.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q compress g.glb --clusters 8 --pca 3 -o gc.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string cam = "eye=0.4,1.3,2.3;target=0,0.8,0;fov=45";
  r = prt("-q web gc.glb --env builtin:sky --env builtin:studio --camera '" + cam + "' -o page_g");
  ASSERT_EQ(r.rc, 0) << r.err;
  // (b = 3 of 4 bands: the table holds the transfer cut to 3 bands, as prt view's.)
  for (const auto& [rot, bands] :
       std::vector<std::pair<std::string, int>>{{"0,0,0", 4}, {"20,70,0", 4}, {"20,70,0", 3}}) {
    SCOPED_TRACE(rot + " at " + std::to_string(bands) + " bands");
    r = prt("-q render gc.glb --light builtin:studio --rotate " + rot + " --camera '" + cam +
            "' --exposure -1 --bands " + std::to_string(bands) + " --size 320x240 -o g.png");
    ASSERT_EQ(r.rc, 0) << r.err;
    std::string log;
    const std::string json = runPage(path("page_g"),
                                     "screenshot&size=320x240&env=1&exposure=-1&rotate=" + rot +
                                         "&bands=" + std::to_string(bands),
                                     &log);
    ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json << "\n" << log;
    EXPECT_EQ(jsonField(json, "compressed"), "8x3, 16 bytes per vertex");
    const double e = displayedRmse(unbase64(jsonField(json, "rgb")), path("g.png"));
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "page vs prt render, compressed glossy, rotate " << rot << ", " << bands
              << " bands: RMSE " << e << ", 90th percentile " << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: close up the lobe is a large part of the image, so the diffuse
  // part alone (render with a lambert material) is far off.
  r = prt("-q render gc.glb --light builtin:studio --rotate 20,70,0 --camera '" + cam +
          "' --exposure -1 --material 'lambert?kd=0.4' --size 320x240 -o d.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string json =
      runPage(path("page_g"), "screenshot&size=320x240&env=1&exposure=-1&rotate=20,70,0");
  EXPECT_GT(displayedRmse(unbase64(jsonField(json, "rgb")), path("d.png")), 2 * kMatch);
  // Another lobe (prt web --material, as prt render --material): the page shades with it, and
  // still matches prt render with the same material — which the bake's material does not.
  const std::string ggx = "--material 'ggx?roughness=0.35&ks=1&kd=0.05'";
  r = prt("-q web gc.glb --env builtin:studio --camera '" + cam + "' " + ggx + " -o page_m");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q render gc.glb --light builtin:studio --rotate 20,70,0 --camera '" + cam +
          "' --exposure -1 " + ggx + " --size 320x240 -o m.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string jm =
      runPage(path("page_m"), "screenshot&size=320x240&env=0&exposure=-1&rotate=20,70,0");
  ASSERT_NE(jm.find("\"ok\":true"), std::string::npos) << jm;
  const double em = displayedRmse(unbase64(jsonField(jm, "rgb")), path("m.png"));
  std::cout << "page vs prt render, --material ggx: RMSE " << em << "\n";
  EXPECT_LT(em, kMatch);
  r = prt("-q render gc.glb --light builtin:studio --rotate 20,70,0 --camera '" + cam +
          "' --exposure -1 --size 320x240 -o b.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_GT(displayedRmse(unbase64(jsonField(jm, "rgb")), path("b.png")), 2 * kMatch);
}

TEST(Web, MeshWithoutAlbedoMatchesPrtRender) {
  // An OBJ has no per-vertex albedo: no COLOR_0 in the bake, white in relight and in the page.
  PRT_REQUIRE_PAGE();
  std::ofstream(path("box.obj")) << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                                    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                                    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                    "f 4 7 3\nf 4 8 7\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
  Result r = prt("-q bake box.obj --mode unshadowed --bands 3 -o box.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q web box.glb --env builtin:studio -o page_box");
  ASSERT_EQ(r.rc, 0) << r.err;
  r =
      prt("-q render --exposure 0 box.glb --light builtin:studio --rotate 0,40,0 --size 320x240 -o "
          "box.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string json =
      runPage(path("page_box"), "screenshot&size=320x240&exposure=0&rotate=0,40,0");
  EXPECT_LT(displayedRmse(unbase64(jsonField(json, "rgb")), path("box.png")), kMatch)
      << json.substr(0, 200);
  EXPECT_LT(quantile90, kInterior);
}

// Per-texel transfer (prt bake --domain texels, a 64 × 64 lightmap): the page packs the lightmap's
// rows once into a data texture indexed by texel row, and its fragment shader fetches the four
// texels of prt render's bilinear fetch at the interpolated lightmap UV, relights each (dense, or
// CPCA from the same per-frame cluster table) and blends them, times the albedo — what prt render
// does at each ray's hit. 256 samples: on a noisy lightmap the page's one shading point per pixel
// against render's four fetches alone costs ~0.01 of RMSE (tests/viewer says the same).
TEST(Web, TexelBakeRelitPerPixelMatchesPrtRender) {
  PRT_REQUIRE_PAGE();
  Result r =
      prt("-q bake 'builtin:cornell?grid=8' --mode interreflected --mode shadowed --bands 4 "
          "--domain texels --resolution 64 --samples 256 -o texels.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q compress texels.glb --mode interreflected --clusters 8 --pca 3 -o texels-cpca.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  struct Case {
    std::string bake, render, query, compressed;
  };
  for (const Case& c :
       {Case{"texels", "--light builtin:studio --rotate 20,-30,10 --mode interreflected",
             "env=1&rotate=20,-30,10&mode=interreflected", "no"},
        Case{"texels", "--light builtin:sky --mode shadowed --bands 3",
             "env=0&mode=shadowed&bands=3", "no"},
        Case{"texels-cpca", "--light builtin:sky --rotate 0,40,0 --mode interreflected",
             "env=0&rotate=0,40,0&mode=interreflected", "8x3, 16 bytes per texel"}}) {
    SCOPED_TRACE(c.bake + " " + c.query);
    r = prt("-q web " + c.bake + ".glb --env builtin:sky --env builtin:studio -o page_" + c.bake);
    ASSERT_EQ(r.rc, 0) << r.err;
    r = prt("-q render --exposure 0 " + c.bake + ".glb --size 320x240 " + c.render + " -o t.png");
    ASSERT_EQ(r.rc, 0) << r.err;
    std::string log;
    const std::string json =
        runPage(path("page_" + c.bake), "screenshot&size=320x240&exposure=0&" + c.query, &log);
    ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json << "\n" << log;
    EXPECT_EQ(jsonField(json, "compressed"), c.compressed);
    EXPECT_NE(json.find("\"perPixel\":true"), std::string::npos) << json.substr(0, 300);
    const double e = displayedRmse(unbase64(jsonField(json, "rgb")), path("t.png"));
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "page vs prt render, per texel " << c.bake << ": RMSE " << e
              << ", 90th percentile " << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: another light rotation is far off.
  const std::string json =
      runPage(path("page_texels-cpca"), "screenshot&size=320x240&exposure=0&env=0&rotate=0,160,0");
  EXPECT_GT(displayedRmse(unbase64(jsonField(json, "rgb")), path("t.png")), 4 * kMatch);
}

// Per-texel glossy matrices, CPCA-compressed (prt bake --transfer matrix --domain texels): each
// of the four taps of prt render's bilinear fetch forms its texel's received light from the
// per-frame cluster table and shades it with the glossy response at the texel's own sample
// point, normal and albedo, which prt web computes (render::texelRelight) and ships beside the
// bake — the texel radiance prt render relights and fetches. Turned lights, a close camera (the
// lobe fills the image), the points beside the page as a file; a diffuse material (the lobe left
// out) is far off, and the bake without its points (dropped on a page) is refused by name.
TEST(Web, TexelGlossyMatricesRelitPerPixelMatchPrtRender) {
  PRT_REQUIRE_PAGE();
  Result r =
      prt("-q bake 'builtin:cornell?grid=8' --mode shadowed --transfer matrix --bands 3 "
          "--domain texels --resolution 64 --samples 256 --material 'phong?ks=0.4&exponent=6' "
          "-o gtexels.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q compress gtexels.glb --clusters 16 --pca 6 -o gtexels-cpca.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string cam = "eye=0.4,1.3,2.3;target=0,0.8,0;fov=45";
  r = prt("-q web gtexels-cpca.glb --env builtin:sky --env builtin:studio -o page_gt");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q web gtexels-cpca.glb --env builtin:sky --env builtin:studio --camera '" + cam +
          "' --embed never -o page_gt_close");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(prt::testing::slurp(path("page_gt/prt-data.js")).find("\"texelPoints\":{"),
            std::string::npos);
  ASSERT_TRUE(fs::exists(path("page_gt_close/texel-points.bin")));
  EXPECT_EQ(fs::file_size(path("page_gt_close/texel-points.bin")), 64u * 64u * 12u * 4u);
  struct Case {
    std::string page, render, query, flags;
  };
  for (const Case& c :
       {Case{"page_gt", "--light builtin:sky", "env=0", ""},
        Case{"page_gt", "--light builtin:studio --rotate 20,70,0", "env=1&rotate=20,70,0", ""},
        Case{"page_gt_close", "--light builtin:studio --rotate 20,70,0 --camera '" + cam + "'",
             "env=1&rotate=20,70,0", "--allow-file-access-from-files"}}) {
    SCOPED_TRACE(c.page + " " + c.query);
    r = prt("-q render --exposure 0 gtexels-cpca.glb --size 320x240 " + c.render + " -o gt.png");
    ASSERT_EQ(r.rc, 0) << r.err;
    std::string log;
    const std::string json =
        runPage(path(c.page), "screenshot&size=320x240&exposure=0&" + c.query, &log, c.flags);
    ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json << "\n" << log;
    EXPECT_EQ(jsonField(json, "compressed"), "16x6, 32 bytes per texel");
    EXPECT_NE(json.find("\"perPixel\":true"), std::string::npos) << json.substr(0, 300);
    const double e = displayedRmse(unbase64(jsonField(json, "rgb")), path("gt.png"));
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "page vs prt render, per-texel glossy CPCA " << c.query << ": RMSE " << e
              << ", 90th percentile " << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: close up, the diffuse part alone is far off.
  r =
      prt("-q render --exposure 0 gtexels-cpca.glb --size 320x240 --light builtin:studio "
          "--rotate 20,70,0 --camera '" +
          cam + "' --material lambert -o gd.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string json =
      runPage(path("page_gt_close"), "screenshot&size=320x240&exposure=0&env=1&rotate=20,70,0",
              nullptr, "--allow-file-access-from-files");
  const double off = displayedRmse(unbase64(jsonField(json, "rgb")), path("gd.png"));
  std::cout << "the lobe left out: RMSE " << off << "\n";
  EXPECT_GT(off, 2 * kMatch);
  // Dense per-texel matrices: prt web refuses them by name, before writing anything.
  r = prt("web gtexels.glb -o nope_gt");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("dense glossy matrices"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("nope_gt")));
}

// The base-colour texture (render/base_colour.hpp) multiplies the diffuse part per pixel on the
// page, as in prt render: GLTFLoader's map of the bake's baseColorTexture, sampled at TEXCOORD_0
// (sRGB decoded before filtering, repeat wrapping, no mipmaps) in prt_fragment.glsl, the lobe
// added after. A checker on a two-triangle square: per vertex (dense vectors, CPCA glossy
// matrices) and per texel (vectors, CPCA glossy matrices at the points prt web ships). Four
// vertices cannot carry the checker: the untextured square's render is far off.
TEST(Web, BaseColourTextureMultipliesPerPixel) {
  PRT_REQUIRE_PAGE();
  const std::string obj = prt::testing::writeCheckerPlane(scratch());
  const std::string plain = prt::testing::writeCheckerPlane(scratch(), true);
  const std::string lobe = " --material 'phong?exponent=8&ks=0.4'";
  const std::string texels = " --domain texels --resolution 32 --uv auto";
  for (const std::string& cmd : std::vector<std::string>{
           "-q bake '" + obj + "' --mode shadowed --bands 4 --samples 64 -o wtv.glb",
           "-q bake '" + plain + "' --mode shadowed --bands 4 --samples 64 -o wtp.glb",
           "-q bake '" + obj + "' --mode shadowed --transfer matrix --bands 4 --samples 64" + lobe +
               " -o wtg.glb",
           "-q compress wtg.glb --clusters 2 --pca 2 -o wtgc.glb",
           "-q bake '" + obj + "' --mode shadowed --bands 3 --samples 64" + texels + " -o wttv.glb",
           "-q bake '" + obj + "' --mode shadowed --transfer matrix --bands 3 --samples 64" +
               texels + lobe + " -o wttg.glb",
           "-q compress wttg.glb --clusters 4 --pca 3 -o wttgc.glb"}) {
    const Result r = prt(cmd);
    ASSERT_EQ(r.rc, 0) << cmd << "\n" << r.err;
  }
  const std::string cam = " --camera 'eye=0,2.5,3.5;target=0,0,0;fov=45'";
  for (const std::string bake : {"wtv", "wtgc", "wttv", "wttgc"}) {
    SCOPED_TRACE(bake);
    Result r = prt("-q web " + bake + ".glb --env builtin:studio" + cam + " -o page_" + bake);
    ASSERT_EQ(r.rc, 0) << r.err;
    r = prt("-q render --exposure 0 " + bake + ".glb --size 320x240 --light builtin:studio" + cam +
            " -o " + bake + ".png");
    ASSERT_EQ(r.rc, 0) << r.err;
    std::string log;
    const std::string json =
        runPage(path("page_" + bake), "screenshot&size=320x240&exposure=0&env=0", &log);
    ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 400) << "\n" << log;
    const double e = displayedRmse(unbase64(jsonField(json, "rgb")), path(bake + ".png"));
    EXPECT_LT(e, kMatch);
    EXPECT_LT(quantile90, kInterior);
    std::cout << "page vs prt render, textured " << bake << ": RMSE " << e << ", 90th percentile "
              << quantile90 * 255 << "/255\n";
  }
  // The comparison can fail: the page's frame against the untextured square's render.
  const Result r = prt("-q render --exposure 0 wtp.glb --size 320x240 --light builtin:studio" +
                       cam + " -o wtp.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string json = runPage(path("page_wtv"), "screenshot&size=320x240&exposure=0&env=0");
  const double off = displayedRmse(unbase64(jsonField(json, "rgb")), path("wtp.png"));
  std::cout << "the texture left out: RMSE " << off << "\n";
  EXPECT_GT(off, 4 * kMatch);
}

TEST(Web, BadDroppedFilesLeaveTheSceneAndSayWhy) {
  PRT_REQUIRE_PAGE();
  std::string log;
  // The page hands its test files to the drop handler in memory (main.js, dropTest: Chromium's
  // virtual time does not wait for Blob reads). An empty report would still be retried, twice.
  std::string json;
  for (int attempt = 0; attempt < 3 && json.empty(); ++attempt)
    json = runPage(webFolder(nullptr), "test=drop", &log);
  ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json << "\n" << log;
  const std::vector<std::pair<std::string, std::string>> expect = {
      {"garbage.glb", "garbage.glb: is not a glTF binary (.glb) file"},
      {"truncated.glb", "truncated.glb: is truncated"},
      {"plain.glb", "plain.glb: is a glTF file but not a prtkit bake"},
      {"newer.glb", "newer.glb: bake format version 99 is newer than this page reads"},
      {"broken.json", "broken.json: is not JSON"},
      {"rows.json", "rows.json: has 3 coefficients but 2 bands need 4"},
      {"picture.png", "picture.png: not a bake (.glb) or an SH light (.json, or the course's"},
      {"odd.txt", "odd.txt: has 2 lines; a light.txt has B² lines"},
  };
  for (const auto& [name, message] : expect) {
    const std::size_t at = json.find("{\"name\":\"" + name + "\"");
    ASSERT_NE(at, std::string::npos) << name << " missing in " << json;
    const std::string entry = json.substr(at, json.find('}', at) - at);
    EXPECT_NE(jsonField(entry, "message").find(message), std::string::npos) << entry;
    for (const char* same : {"\"sameBake\":true", "\"sameEnvs\":true", "\"sameFrame\":true"})
      EXPECT_NE(entry.find(same), std::string::npos) << same << " in " << entry;
  }
  // A light with fewer bands than the bake follows the library's rule (io::loadLighting): added,
  // padded with zeros (it draws what the same light with the bake's bands draws), and the
  // library's warning shown as a warning. What the library says for the same light (the same
  // file name: the page's is bare):
  std::ofstream(path("short.json")) << "{\"bands\": 2, \"coefficients\": "
                                       "[[1, 1, 1], [0, 0, 0], [0, 0, 0], [0, 0, 0]]}\n";
  const prt::io::Lighting lib = prt::io::loadLighting(path("short.json"), 4);
  ASSERT_EQ(lib.warnings.size(), 1u);
  std::string shortWarning = lib.warnings[0];
  shortWarning.erase(0, shortWarning.find("short.json"));
  {
    const std::size_t at = json.find("\"short\":{");
    ASSERT_NE(at, std::string::npos) << json;
    const std::string entry = json.substr(at, json.find('}', at) - at);
    EXPECT_EQ(jsonField(entry, "message"), shortWarning) << entry;
    EXPECT_EQ(jsonField(entry, "kind"), "warning") << entry;
    for (const char* want : {"\"added\":true", "\"changed\":true", "\"sameAsPadded\":true"})
      EXPECT_NE(entry.find(want), std::string::npos) << want << " in " << entry;
  }
  // The control: a good light file (JSON, then light.txt) is added, and clears the message.
  EXPECT_NE(json.find("\"control\":{\"message\":\"\",\"added\":true}"), std::string::npos) << json;
  // And a good bake replaces the scene (the short light, still in the list, is warned about
  // again for the new bake).
  EXPECT_NE(json.find("\"controlBake\":{\"message\":\"" + shortWarning + "\",\"replaced\":true}"),
            std::string::npos)
      << json;
}

TEST(Web, ClearMessagesWithoutDataOrWebGl2) {
  PRT_REQUIRE_PAGE();
  // No prt-data.js: the page says how to write the folder.
  const fs::path bare = scratch() / "bare";
  fs::create_directories(bare);
  for (const char* f : {"index.html", "prt-web.js"})
    fs::copy_file(fs::path(webFolder(nullptr)) / f, bare / f, fs::copy_options::overwrite_existing);
  std::string json = runPage(bare.string(), "test=none");
  EXPECT_NE(json.find("prt-data.js is missing"), std::string::npos) << json;
  // WebGL2 switched off: the page says it needs WebGL2.
  json = runPage(webFolder(nullptr), "test=none", nullptr, "--disable-webgl2");
  EXPECT_NE(json.find("needs WebGL2"), std::string::npos) << json;
}

TEST(Web, CliRefusesWhatThePageCannotShow) {
  // One-line errors before anything is written.
  std::ofstream(path("notabake.glb")) << "hello";
  Result r = prt("web notabake.glb -o nope");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("prt web: error: "), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(path("nope/prt-data.js")));
  // Dense per-texel glossy matrices: named, with what to use instead (compressed ones are
  // drawn; dense per-vertex ones are drawn on the CPU through an irradiance encoding,
  // tests/web/test_encodings_web.cpp).
  r =
      prt("-q bake 'builtin:sphere?subdiv=1' --mode unshadowed --domain texels --resolution 32 "
          "--transfer matrix --bands 2 --samples 16 -o m.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("web m.glb -o nope");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("m.glb: the unshadowed transfer holds dense glossy matrices per texel; the "
                       "browser viewer draws them CPCA-compressed only (prt compress)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(path("nope/prt-data.js")));
  r = prt("web missing.glb -o nope --tonemap sepia");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("sepia"), std::string::npos) << r.err;
}

// Large bakes (issue 16, item 7): beside prt-data.js as bake.glb instead of base64 inside it.
// --embed never forces it for a small bake; the page fetches the file and draws the frame it
// draws from the embedded copy; opened from disk, where a browser refuses the fetch, it says how
// to serve the folder. A bake beyond the page's limit is refused before it is read.
TEST(Web, LargeBakesGoBesideThePageAndAreFetched) {
  PRT_REQUIRE_PAGE();
  Result r = prt("-q web cornell.glb --embed never -o page_beside");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(prt::testing::slurp(path("page_beside/bake.glb")),
            prt::testing::slurp(path("cornell.glb")));
  const std::string data = prt::testing::slurp(path("page_beside/prt-data.js"));
  EXPECT_EQ(data.find("\"glb\""), std::string::npos);
  EXPECT_NE(data.find("\"file\":\"bake.glb\""), std::string::npos);
  // Fetched (Chromium allows file:// fetches with this flag, as a server would serve them).
  std::string log;
  std::string json =
      runPage(path("page_beside"), "screenshot&size=320x240&exposure=0&env=0&mode=shadowed", &log,
              "--allow-file-access-from-files");
  ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json << "\n" << log;
  const std::vector<unsigned char> beside = unbase64(jsonField(json, "rgb"));
  EXPECT_EQ(beside, pageFrame("env=0&mode=shadowed")) << "the same frame as the embedded bake";
  // Opened from disk without it: the fetch is refused and the page says what to do.
  json = runPage(path("page_beside"), "test=none");
  EXPECT_NE(json.find("served over http"), std::string::npos) << json;
  // An --embed that is not a choice, and a bake past the page's limit (a sparse file: refused by
  // its size, before a byte is read).
  r = prt("web cornell.glb --embed sometimes -o nope");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("--embed 'sometimes'"), std::string::npos) << r.err;
  {
    std::ofstream(path("huge.glb")) << "glTF";
    fs::resize_file(path("huge.glb"), (std::uintmax_t(1) << 30) + 1);
  }
  r = prt("web huge.glb -o nope");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("huge.glb: 1074 MB is more than the browser viewer takes"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("prt compress"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("nope")));
  fs::remove(path("huge.glb"));
}

TEST(Web, AbsurdExposureAndLightShowWhite) {
  // Issue 16, item 5: ?exposure= beyond the library's limit is clamped to it (prt-data.js
  // carries the limit), and the shared tone map saturates a light of 1e20 to white instead of
  // overflowing to black — as prt render's PNG at --exposure 64.
  PRT_REQUIRE_PAGE();
  std::string light = "{\"bands\": 4, \"coefficients\": [[1e20, 1e20, 1e20]";
  for (int i = 1; i < 16; ++i) light += ", [0, 0, 0]";
  std::ofstream(path("l20.json")) << light << "]}\n";
  Result r = prt("-q web cornell.glb --env l20.json -o page_bright");
  ASSERT_EQ(r.rc, 0) << r.err;
  for (const char* e : {"64", "1e30"}) {
    std::string log;
    const std::string json =
        runPage(path("page_bright"), "screenshot&size=64x48&exposure=" + std::string(e), &log);
    ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json << "\n" << log;
    const std::vector<unsigned char> rgb = unbase64(jsonField(json, "rgb"));
    ASSERT_EQ(rgb.size(), 64u * 48u * 3u);
    const std::size_t c = 3 * (24 * 64 + 32);
    EXPECT_EQ(rgb[c], 255) << e;
    EXPECT_EQ(rgb[c + 1], 255) << e;
    EXPECT_EQ(rgb[c + 2], 255) << e;
  }
  r = prt("-q render cornell.glb --light l20.json --exposure 64 --size 64x48 -o bright.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const prt::image::Image img = prt::image::readImage(path("bright.png"));
  EXPECT_EQ(img.at(32, 24).x, 1.0f);
  r = prt("web cornell.glb --exposure 1e30 -o nope");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("--exposure"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("nope")));
}

}  // namespace
