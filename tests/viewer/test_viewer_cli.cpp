// prt view through the real binary: a headless frame equals prt render's image of the same view
// and light (same tone mapping) within a small RMSE, for scalar and RGB transfer, rotated
// lights, the SH background, truncated bands and other tone maps; and it fails cleanly (one
// line, non-zero exit) without a display or with bad files.
//
// Why the thresholds hold: both renderers interpolate the same per-vertex radiance
// R = albedo ⊙ T·D(R)L perspective-correctly across triangles, average 4 samples per pixel in
// linear light and apply the same tone map; they differ only in sample positions (the MSAA
// pattern against Sobol' points), float round-off and 8-bit rounding. Inside surfaces that
// leaves one or two codes (the 90th-percentile pixel error is below 2.5/255); on silhouettes
// and creases a pixel can differ by most of its range when the two sample sets fall on
// different sides of an edge, and that is what the RMSE is made of: measured ≈ 0.012 for the
// Cornell box at 320×240 (0.017 under a bright SH sky; 0.008 at 640×480, 0.02 at 160×120).
// Each test also checks that a wrong answer (another light rotation) is far above the
// threshold, so the comparison can fail.

#include <unistd.h>

#include <algorithm>

#include "common/checker_plane.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/io/bake_file.hpp"
#include "viewer_test_util.hpp"

namespace prt::viewer::test {
namespace {

constexpr double kMatch = 0.02;            // displayed RMSE of a matching pair at kSize
constexpr double kInterior = 2.5 / 255.0;  // 90th-percentile pixel error of a matching pair
constexpr const char* kSize = "--size 320x240";

/// Renders `bake` with prt render and prt view (same extra arguments) and returns the RMSE.
double compareWithRender(const std::string& bake, const std::string& args,
                         const std::string& viewArgs = "") {
  const Result r = prt("-q render '" + bake + "' " + kSize + " " + args + " -o render.png");
  EXPECT_EQ(r.rc, 0) << r.err;
  const Result v = prt("-q view '" + bake + "' --headless " + kSize + " " + args + " " + viewArgs +
                       " --screenshot view.png");
  EXPECT_EQ(v.rc, 0) << v.err;
  if (r.rc != 0 || v.rc != 0) return 1.0;
  EXPECT_LT(displayedErrorQuantile(path("view.png"), path("render.png"), 0.9), kInterior) << args;
  return displayedRmse(path("view.png"), path("render.png"));
}

TEST(ViewCli, HeadlessFrameMatchesRenderRgbTransfer) {
  PRT_REQUIRE_HEADLESS_GL();
  const double e = compareWithRender(cornellBake(), "--mode interreflected");
  EXPECT_LT(e, kMatch);
  // The comparison can fail: the same view under a turned light is far off.
  const Result v = prt("-q view '" + cornellBake() + "' --headless " + std::string(kSize) +
                       " --mode interreflected --rotate 0,120,0 --screenshot turned.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_GT(displayedRmse(path("turned.png"), path("render.png")), 4 * kMatch);
}

TEST(ViewCli, HeadlessFrameMatchesRenderScalarTransfer) {
  PRT_REQUIRE_HEADLESS_GL();
  EXPECT_LT(compareWithRender(cornellBake(), "--mode shadowed"), kMatch);
  EXPECT_LT(compareWithRender(spherePlaneBake(), ""), kMatch);
}

TEST(ViewCli, RotatedLightMatchesRenderRotate) {
  PRT_REQUIRE_HEADLESS_GL();
  EXPECT_LT(compareWithRender(spherePlaneBake(), "--rotate 0,90,0"), kMatch);
  EXPECT_LT(compareWithRender(cornellBake(), "--rotate 30,60,10"), kMatch);
  // Unrotated against rotated: far apart.
  const Result v = prt("-q view '" + cornellBake() + "' --headless " + std::string(kSize) +
                       " --screenshot plain.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_GT(displayedRmse(path("plain.png"), path("render.png")), 4 * kMatch);
}

TEST(ViewCli, AutoRotationAndCameraMatchRender) {
  PRT_REQUIRE_HEADLESS_GL();
  // At a fixed exposure: the auto exposure follows the light each verb starts from.
  // Headless frames are 1/60 s apart: frame 31 of a 180°/s spin shows the light turned by
  // 30/60 · 180° = 90° about +Y, i.e. render --rotate 0,90,0.
  const Result r = prt("-q render --exposure 0 '" + spherePlaneBake() + "' " + std::string(kSize) +
                       " --rotate 0,90,0 -o render.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Result v =
      prt("-q view --exposure 0 '" + spherePlaneBake() + "' --headless " + std::string(kSize) +
          " --frames 31 --auto-rotate --spin 180 --screenshot spun.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_LT(displayedRmse(path("spun.png"), path("render.png")), kMatch);
  const Result v1 = prt("-q view '" + spherePlaneBake() + "' --headless " + std::string(kSize) +
                        " --frames 21 --auto-rotate --spin 180 --screenshot spun60.png");
  ASSERT_EQ(v1.rc, 0) << v1.err;
  EXPECT_GT(displayedRmse(path("spun60.png"), path("render.png")), 2 * kMatch);
  // A given camera, as prt render --camera.
  EXPECT_LT(compareWithRender(cornellBake(), "--camera 'eye=2,1.6,4;target=0,0.8,0;fov=50'"),
            kMatch);
}

TEST(ViewCli, ShBackgroundTruncatedBandsAndToneMapsMatch) {
  PRT_REQUIRE_HEADLESS_GL();
  EXPECT_LT(compareWithRender(cornellBake(), "--background sh --rotate 0,45,0"), kMatch);
  EXPECT_LT(compareWithRender(cornellBake(), "--bands 2"), kMatch);
  EXPECT_LT(compareWithRender(cornellBake(), "--tonemap reinhard --exposure 1.5"), kMatch);
  EXPECT_LT(compareWithRender(cornellBake(), "--light builtin:studio --background none"), kMatch);
}

// Glossy (matrix) transfer: the viewer relights it on the CPU with relight::Relighter, each vertex
// seen from the orbit camera's eye, exactly as prt render does; so the same thresholds hold.
// Measured at 320×240 under llvmpipe: RMSE 0.005–0.007 for each matching pair below, 0.056 for
// the diffuse-only view against the glossy render close up.
TEST(ViewCli, GlossyMatrixBakeMatchesRender) {
  PRT_REQUIRE_HEADLESS_GL();
  EXPECT_LT(compareWithRender(glossyBake(), ""), kMatch);
  // The lobe follows the eye: another camera and a turned light.
  EXPECT_LT(compareWithRender(glossyBake(),
                              "--rotate 20,70,0 --camera 'eye=-2.5,1.2,2;target=0,0.3,0;fov=40'"),
            kMatch);
  // --material overrides the bake's (a GGX lobe), and --bands cuts the matrices.
  EXPECT_LT(compareWithRender(glossyBake(), "--material 'ggx?roughness=0.35&ks=0.5&kd=0.3'"),
            kMatch);
  EXPECT_LT(compareWithRender(glossyBake(), "--bands 3 --light builtin:studio"), kMatch);
  // The comparison can fail: close up, the lobe is a large part of the image (the bake's
  // diffuse part alone is far off), so a lobe left out or aimed wrong shows.
  const std::string close = " --exposure -1 --camera 'eye=0.4,1.3,2.3;target=0,0.8,0;fov=45'";
  EXPECT_LT(compareWithRender(glossyBake(), close), kMatch);
  const Result d = prt("-q view '" + glossyBake() + "' --headless " + std::string(kSize) + close +
                       " --material 'lambert?kd=0.4' --screenshot diffuse.png");
  ASSERT_EQ(d.rc, 0) << d.err;
  EXPECT_GT(displayedRmse(path("diffuse.png"), path("render.png")), 2 * kMatch);
}

// The other glossy path: the matrices in a texture buffer, M·L and the two kernels (SH of the
// normal and of the reflected view, evaluated in GLSL) in the vertex shader. Same answers.
TEST(ViewCli, GlossyOnGpuMatchesRender) {
  PRT_REQUIRE_HEADLESS_GL();
  const std::string gpu = "--glossy-on gpu";
  EXPECT_LT(compareWithRender(glossyBake(), "", gpu), kMatch);
  EXPECT_LT(compareWithRender(glossyBake(),
                              "--exposure -1 --rotate 20,70,0 "
                              "--camera 'eye=0.4,1.3,2.3;target=0,0.8,0;fov=45'",
                              gpu),
            kMatch);
  EXPECT_LT(compareWithRender(glossyBake(), "--material 'ggx?roughness=0.35&ks=0.5&kd=0.3'", gpu),
            kMatch);
  EXPECT_LT(compareWithRender(glossyBake(), "--bands 3 --light builtin:studio", gpu), kMatch);
  // Frame 31 of a 180°/s spin against render --rotate 0,90,0: the light follows per frame.
  const Result r = prt("-q render --exposure 0 '" + glossyBake() + "' " + std::string(kSize) +
                       " --rotate 0,90,0 -o render.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Result v =
      prt("-q view --exposure 0 '" + glossyBake() + "' --headless " + std::string(kSize) +
          " --frames 31 --auto-rotate --spin 180 --glossy-on gpu --screenshot g.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_LT(displayedRmse(path("g.png"), path("render.png")), kMatch);
}

// CPCA-compressed transfer (bake version 3) is relit in the compressed space on the GPU: per
// frame the cluster projections on the CPU, per vertex N weighted sums in the vertex shader.
// prt render relights the same compressed rows on the CPU (relight::relight of the compressed
// rows), so a matching frame meets the same thresholds as a dense one.
TEST(ViewCli, CompressedVectorBakeMatchesRender) {
  PRT_REQUIRE_HEADLESS_GL();
  EXPECT_LT(compareWithRender(compressedSphereBake(), ""), kMatch);
  EXPECT_LT(compareWithRender(compressedSphereBake(), "--rotate 10,80,0 --bands 2"), kMatch);
  EXPECT_LT(compareWithRender(compressedCornellBake(), "--mode interreflected"), kMatch);
  // The shadowed transfer of the same file is dense and still drawn by the dense path.
  EXPECT_LT(compareWithRender(compressedCornellBake(), "--mode shadowed"), kMatch);
  // The comparison can fail: the compressed frame under a turned light is far off.
  const Result r = prt("-q render '" + compressedCornellBake() + "' " + std::string(kSize) +
                       " --mode interreflected -o render.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Result v = prt("view '" + compressedCornellBake() + "' --headless " + std::string(kSize) +
                       " --mode interreflected --rotate 0,120,0 --stats --screenshot turned.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_GT(displayedRmse(path("turned.png"), path("render.png")), 4 * kMatch);
  // --stats says it relit compressed, and what it uploaded: N = 5 weights and the id are two
  // RGBA32F texels (32 bytes) per vertex against 16 texels (256 bytes) of dense RGB 4-band rows;
  // the table is K(N+1) = 144 texels.
  EXPECT_NE(v.out.find("relit compressed (CPCA 24 x 5) per vertex: 32 bytes per vertex uploaded "
                       "once ("),
            std::string::npos)
      << v.out;
  EXPECT_NE(v.out.find("; dense: 256), 2304 bytes of cluster table per frame"), std::string::npos)
      << v.out;
  // A dense bake says so.
  const Result d = prt("view '" + spherePlaneBake() + "' --headless " + std::string(kSize) +
                       " --stats --screenshot dense.png");
  ASSERT_EQ(d.rc, 0) << d.err;
  EXPECT_NE(d.out.find("dense transfer relit per vertex: 48 bytes per vertex"), std::string::npos) << d.out;
}

// Per-texel transfer (prt bake --domain texels) is relit per pixel: the fragment shader fetches
// the four texels of prt render's bilinear fetch at the interpolated lightmap UV, relights each
// (dense T·L', or CPCA from the cluster table) and blends them, times the interpolated albedo.
// prt render relights every texel on the CPU and makes the same fetch at each ray's hit, so a
// matching frame meets the per-vertex thresholds (the remaining differences are the same: sample
// positions, round-off, 8-bit codes).
TEST(ViewCli, TexelBakeRelitPerPixelMatchesRender) {
  PRT_REQUIRE_HEADLESS_GL();
  EXPECT_LT(compareWithRender(texelBake(), "--mode interreflected"), kMatch);
  EXPECT_LT(compareWithRender(texelBake(), "--mode shadowed --bands 3"), kMatch);
  EXPECT_LT(compareWithRender(texelBake(), "--mode interreflected --rotate 30,60,10"), kMatch);
  EXPECT_LT(compareWithRender(texelBake(),
                              "--mode interreflected --camera "
                              "'eye=0.3,0.5,1.6;target=0,0.2,0;fov=50'"),
            kMatch);
  EXPECT_LT(compareWithRender(compressedTexelBake(), "--mode interreflected --rotate 0,40,0"),
            kMatch);
  // The comparison can fail: the same view under a turned light is far off.
  const Result r = prt("-q render '" + texelBake() + "' " + std::string(kSize) +
                       " --mode interreflected -o render.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Result v = prt("view '" + texelBake() + "' --headless " + std::string(kSize) +
                       " --mode interreflected --rotate 0,120,0 --stats --screenshot turned.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_GT(displayedRmse(path("turned.png"), path("render.png")), 4 * kMatch);
  // --stats says it relit per pixel, and what it uploaded: 16 RGB coefficients, 16 texels (256
  // bytes) per lightmap texel.
  EXPECT_NE(v.out.find("dense transfer relit per pixel from a 64 x 64 lightmap: 256 bytes per "
                       "texel uploaded"),
            std::string::npos)
      << v.out;
  const Result c = prt("view '" + compressedTexelBake() + "' --headless " + std::string(kSize) +
                       " --mode interreflected --stats --screenshot c.png");
  ASSERT_EQ(c.rc, 0) << c.err;
  EXPECT_NE(c.out.find("relit compressed (CPCA 8 x 3) per pixel from a 64 x 64 lightmap: 16 "
                       "bytes per texel"),
            std::string::npos)
      << c.out;
}

// Per-texel glossy matrices, CPCA-compressed, relit per pixel: each of the four taps forms its
// texel's received light from the cluster table and shades it at the texel's own point (what
// prt render relights each texel to), under turned lights and cameras; a diffuse material
// instead (the lobe left out) is far off. The dense file is refused by name.
TEST(ViewCli, TexelGlossyMatricesRelitPerPixelMatchRender) {
  PRT_REQUIRE_HEADLESS_GL();
  const std::string& c = compressedGlossyTexelBake();
  const std::string close = "--exposure 0 --camera 'eye=0.4,1.3,2.3;target=0,0.8,0;fov=45'";
  for (const std::string& args :
       {std::string(), std::string("--exposure 0 --rotate 20,70,0"), close}) {
    const double e = compareWithRender(c, args);
    std::printf("per-texel glossy CPCA, view vs render (%s): RMSE %.4f\n", args.c_str(), e);
    EXPECT_LT(e, kMatch) << args;
  }
  const Result d = prt("view '" + c + "' --headless " + std::string(kSize) + " " + close +
                       " --material 'lambert' --stats --screenshot diffuse.png");
  ASSERT_EQ(d.rc, 0) << d.err;
  const double off = displayedRmse(path("diffuse.png"), path("render.png"));
  std::printf("the lobe left out: RMSE %.4f\n", off);
  EXPECT_GT(off, 2 * kMatch);
  EXPECT_NE(d.out.find("relit compressed glossy matrices (CPCA 16 x 6) per pixel from a 64 x 64 "
                       "lightmap"),
            std::string::npos)
      << d.out;
  const Result dense = prt("view '" + path("glossy-texels.glb") + "' --headless " +
                           std::string(kSize) + " --screenshot dense.png");
  EXPECT_NE(dense.rc, 0);
  EXPECT_NE(dense.err.find("drawn CPCA-compressed (prt compress)"), std::string::npos) << dense.err;
}

// The base-colour texture multiplies the diffuse part per pixel in every path, as prt render
// (render/base_colour.hpp): a checker on a two-triangle square, per vertex (dense vectors; glossy
// matrices on the CPU — the lobe relit apart — and on the GPU; CPCA glossy) and per texel
// (vectors; CPCA glossy, shaded at the texels' points). The square without its texture is far
// off (its four vertices cannot carry the checker); a material kd replaces the texture, as in
// prt render.
TEST(ViewCli, BaseColourTextureMultipliesPerPixelInEveryPath) {
  PRT_REQUIRE_HEADLESS_GL();
  const std::string obj = prt::testing::writeCheckerPlane(scratch());
  const std::string plain = prt::testing::writeCheckerPlane(scratch(), true);
  const std::string lobe = "--material 'phong?exponent=8&ks=0.4'";
  const std::string texels = "--domain texels --resolution 32 --uv auto";
  for (const std::string& bake : std::vector<std::string>{
           "-q bake '" + obj + "' --mode shadowed --bands 4 --samples 64 -o tv.glb",
           "-q bake '" + plain + "' --mode shadowed --bands 4 --samples 64 -o tp.glb",
           "-q bake '" + obj + "' --mode shadowed --transfer matrix --bands 4 --samples 64 " +
               lobe + " -o tg.glb",
           "-q compress tg.glb --clusters 2 --pca 2 -o tgc.glb",
           "-q bake '" + obj + "' --mode shadowed --bands 3 --samples 64 " + texels + " -o ttv.glb",
           "-q bake '" + obj + "' --mode shadowed --transfer matrix --bands 3 --samples 64 " +
               texels + " " + lobe + " -o ttg.glb",
           "-q compress ttg.glb --clusters 4 --pca 3 -o ttgc.glb",
           "-q bake '" + obj + "' --mode shadowed --basis haar --cube-resolution 8 --terms 32 " +
               texels + " -o tth.glb",
           "-q bake '" + plain + "' --mode shadowed --basis haar --cube-resolution 8 --terms 32 " +
               texels + " -o tph.glb"}) {
    const Result r = prt(bake);
    ASSERT_EQ(r.rc, 0) << bake << "\n" << r.err;
  }
  const std::string close =
      "--light builtin:studio --exposure 0 --camera 'eye=0,2.5,3.5;target=0,0,0;fov=45'";
  struct Case {
    std::string bake, view;
  };
  for (const Case& c :
       {Case{"tv.glb", ""}, Case{"tg.glb", "--glossy-on cpu"}, Case{"tg.glb", "--glossy-on gpu"},
        Case{"tgc.glb", ""}, Case{"ttv.glb", ""}, Case{"ttgc.glb", ""}, Case{"tth.glb", ""}}) {
    const double e = compareWithRender(path(c.bake), close, c.view);
    std::printf("textured %s %s, view vs render: RMSE %.4f\n", c.bake.c_str(), c.view.c_str(), e);
    EXPECT_LT(e, kMatch) << c.bake << " " << c.view;
  }
  // A material kd replaces the texture in both.
  EXPECT_LT(compareWithRender(path("tg.glb"),
                              close + " --material 'phong?exponent=8&ks=0.4&kd=0.5,0.5,0.5'"),
            kMatch);
  // The control: the textured view against the untextured square's render.
  ASSERT_EQ(prt("-q view '" + path("tv.glb") + "' --headless " + std::string(kSize) + " " + close +
                " --screenshot textured.png")
                .rc,
            0);
  ASSERT_EQ(prt("-q render '" + path("tp.glb") + "' " + std::string(kSize) + " " + close +
                " -o plain.png")
                .rc,
            0);
  const double off = displayedRmse(path("textured.png"), path("plain.png"));
  std::printf("the texture left out: RMSE %.4f\n", off);
  EXPECT_GT(off, 4 * kMatch);
  // And per-texel Haar transfer: prt render multiplies the texture per pixel too.
  for (const char* haar : {"tth", "tph"})
    ASSERT_EQ(prt("-q render '" + path(std::string(haar) + ".glb") + "' " + std::string(kSize) +
                  " " + close + " -o " + haar + ".png")
                  .rc,
              0);
  const double haarOff = displayedRmse(path("tth.png"), path("tph.png"));
  std::printf("per-texel Haar, the texture left out: RMSE %.4f\n", haarOff);
  EXPECT_GT(haarOff, 4 * kMatch);
}

// Compressed glossy matrices: on the CPU by relight::Relighter (the default), or in the
// vertex shader (--glossy-on gpu) from per-cluster L'_kj = B_kj L' tables. Both against prt
// render of the same compressed bake.
TEST(ViewCli, CompressedGlossyBakeMatchesRenderOnCpuAndGpu) {
  PRT_REQUIRE_HEADLESS_GL();
  const std::string turned = "--rotate 20,70,0 --camera 'eye=-2.5,1.2,2;target=0,0.3,0;fov=40'";
  const std::string close = "--exposure -1 --camera 'eye=0.4,1.3,2.3;target=0,0.8,0;fov=45'";
  for (const std::string on : {"cpu", "gpu"}) {
    SCOPED_TRACE(on);
    EXPECT_LT(compareWithRender(compressedGlossyBake(), "", "--glossy-on " + on), kMatch);
    EXPECT_LT(compareWithRender(compressedGlossyBake(), turned, "--glossy-on " + on), kMatch);
    EXPECT_LT(compareWithRender(compressedGlossyBake(), close, "--glossy-on " + on), kMatch);
  }
  // The comparison can fail: the lobe left out (a diffuse material) is far off close up.
  const Result d =
      prt("-q view '" + compressedGlossyBake() + "' --headless " + std::string(kSize) + " " +
          close + " --glossy-on gpu --material 'lambert?kd=0.4' --screenshot diffuse.png");
  ASSERT_EQ(d.rc, 0) << d.err;
  EXPECT_GT(displayedRmse(path("diffuse.png"), path("render.png")), 2 * kMatch);
}

TEST(ViewCli, GlossyRelitEveryFrameAsLightAndCameraMove) {
  PRT_REQUIRE_HEADLESS_GL();
  // Frame 31 of a 180°/s spin is the light turned 90° about +Y (see AutoRotation... above): the
  // radiance must be recomputed as the light turns, not kept from the first frame.
  const Result r = prt("-q render --exposure 0 '" + glossyBake() + "' " + std::string(kSize) +
                       " --rotate 0,90,0 -o render.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Result v = prt("view --exposure 0 '" + glossyBake() + "' --headless " + std::string(kSize) +
                       " --frames 31 --auto-rotate --spin 180 --stats --screenshot spun.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_LT(displayedRmse(path("spun.png"), path("render.png")), kMatch);
  EXPECT_NE(v.out.find("shadowed matrix transfer"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("glossy relighting"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("over 30 relit frames"), std::string::npos) << v.out;
  // A glossy material on a vector (diffuse) bake is refused politely: a warning, diffuse image.
  const Result w = prt("view '" + spherePlaneBake() + "' --headless " + std::string(kSize) +
                       " --material 'phong?exponent=8&ks=0.5' --screenshot vec.png");
  EXPECT_EQ(w.rc, 0) << w.err;
  EXPECT_NE(w.err.find("needs a matrix bake"), std::string::npos) << w.err;
}

TEST(ViewCli, ProbeBakeWithAMovingObjectMatchesRender) {
  // A probe grid (prt probes): the scene and the object placed in it, every vertex lit through
  // the relit probes, as prt render --object draws them; under a turned light too.
  PRT_REQUIRE_HEADLESS_GL();
  const Result b = prt("-q probes 'builtin:cornell?grid=12' --grid 6x6x6 --samples 64 -o probes.glb");
  ASSERT_EQ(b.rc, 0) << b.err;
  const std::string object = "--object 'builtin:sphere?subdiv=3' --object-size 0.7 ";
  EXPECT_LT(compareWithRender(path("probes.glb"), object + "--at -0.4,0.5,0.3"), kMatch);
  EXPECT_LT(compareWithRender(path("probes.glb"), object + "--at 0.3,1.2,-0.2 --rotate 0,90,0"),
            kMatch);
  // The comparison can fail: the object elsewhere is far from render's image of it here.
  const Result moved = prt("-q view '" + path("probes.glb") + "' --headless " + kSize + " " +
                           object + "--at -0.4,1.5,0.3 --rotate 0,90,0 --screenshot moved.png");
  ASSERT_EQ(moved.rc, 0) << moved.err;
  EXPECT_GT(displayedRmse(path("moved.png"), path("render.png")), 2 * kMatch);
  // Probe markers draw; a surface bake has no grid to place an object in.
  const Result markers = prt("-q view '" + path("probes.glb") + "' --headless " + kSize +
                             " --show-probes --screenshot markers.png");
  EXPECT_EQ(markers.rc, 0) << markers.err;
  const Result surface = prt("-q view '" + cornellBake() + "' --headless " + kSize +
                             " --object builtin:sphere --screenshot no.png");
  EXPECT_NE(surface.rc, 0);
  EXPECT_NE(surface.err.find("place an object in a probe grid"), std::string::npos)
      << surface.err;
}

TEST(ViewCli, ViewerLightEnvFlagIsItsEnvironment) {
  PRT_REQUIRE_HEADLESS_GL();
  // prt view names the environment --env (several allowed; the first is shown first).
  const Result r = prt("-q render '" + cornellBake() + "' " + std::string(kSize) +
                       " --light builtin:studio -o render.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Result v = prt("-q view '" + cornellBake() + "' --headless " + std::string(kSize) +
                       " --env builtin:studio --env builtin:sky --screenshot view.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_LT(displayedRmse(path("view.png"), path("render.png")), kMatch);
}

TEST(ViewCli, ShLightFileMatchesRender) {
  PRT_REQUIRE_HEADLESS_GL();
  // An SH light file with more bands than the bake is cut to the bake's bands exactly.
  const Result l = prt("-q light builtin:studio --bands 6 -o studio6.json");
  ASSERT_EQ(l.rc, 0) << l.err;
  EXPECT_LT(compareWithRender(cornellBake(), "--light studio6.json --rotate 0,30,0"), kMatch);
  const Result t = prt("-q light builtin:sky --bands 4 -o sky4.txt");
  ASSERT_EQ(t.rc, 0) << t.err;
  EXPECT_LT(compareWithRender(cornellBake(), "--light sky4.txt --background sh"), kMatch);
}

TEST(ViewCli, StatsAndLinearScreenshot) {
  PRT_REQUIRE_HEADLESS_GL();
  const Result v = prt("-q view '" + spherePlaneBake() + "' --headless " + std::string(kSize) +
                       " --frames 3 --auto-rotate --stats --screenshot frame.exr");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_NE(v.out.find("frame time"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("light upload"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("triangles"), std::string::npos) << v.out;
  const image::Image img = image::readImage(path("frame.exr"));
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.height, 240);
}

/// One stderr line "prt view: error: ... MENTION ...", non-zero exit.
void expectCleanFailure(const std::string& args, const std::string& mention,
                        const std::string& prefix = "") {
  SCOPED_TRACE(args);
  const Result r = prt("view " + args, prefix);
  EXPECT_NE(r.rc, 0);
  EXPECT_LT(r.rc, 128) << "crashed";
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("prt view: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(mention), std::string::npos) << "expected '" << mention << "' in " << r.err;
}

TEST(ViewCli, HaarBakeMatchesRenderUnderATurnedLight) {
  // A Haar bake (prt bake --basis haar): every vertex relit on the CPU under the environment's
  // largest wavelet terms, as prt render draws it; a turned light resamples the environment.
  PRT_REQUIRE_HEADLESS_GL();
  const Result b =
      prt("-q bake 'builtin:sphere-plane?size=1.5&grid=40&subdiv=3' --mode shadowed "
          "--basis haar --resolution 16 --terms 64 -o haar.glb");
  ASSERT_EQ(b.rc, 0) << b.err;
  EXPECT_LT(compareWithRender(path("haar.glb"), "--light builtin:sky"), kMatch);
  EXPECT_LT(compareWithRender(path("haar.glb"), "--light builtin:sky --rotate 0,120,0"), kMatch);
  // The comparison can fail: the unturned view against render's image of the turned light.
  const Result v = prt("-q view '" + path("haar.glb") + "' --headless " + std::string(kSize) +
                       " --light builtin:sky --screenshot unturned.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_GT(displayedRmse(path("unturned.png"), path("render.png")), 2 * kMatch);
  // What it cannot draw is refused in one line: an SH light file holds no wavelets.
  ASSERT_EQ(prt("-q light builtin:sky --bands 3 -o sky3.json").rc, 0);
  // (Appended, not "'" + ...: GCC 12 reports a false -Wrestrict on that operator+ here.)
  std::string view = "'";
  view += path("haar.glb");
  view += "' --headless ";
  view += kSize;
  expectCleanFailure(view + " --light sky3.json", "sky3.json: is an SH light file");
  expectCleanFailure(view + " --bands 2", "holds Haar transfer");
  expectCleanFailure(view + " --background sh", "holds Haar transfer");
}

TEST(ViewCli, PerTexelHaarBakeRelitPerPixelMatchesRender) {
  // A per-texel Haar bake: every texel relit on the CPU at its normal (a gutter texel at its
  // neighbour's), uploaded as a one-band lightmap against the light's first coefficient and
  // fetched per pixel as an SH lightmap is, the Cornell box's wall colours multiplied per pixel
  // — prt render's image (render/haar_shader.hpp), under turned lights, bounces and a kd that
  // replaces the walls' colours.
  PRT_REQUIRE_HEADLESS_GL();
  const Result b =
      prt("-q bake 'builtin:cornell?grid=8' --mode shadowed --mode interreflected --bounces 1 "
          "--basis haar --domain texels --resolution 64 --cube-resolution 16 --terms 48 "
          "-o haar-texels.glb");
  ASSERT_EQ(b.rc, 0) << b.err;
  const std::string bake = path("haar-texels.glb");
  EXPECT_LT(compareWithRender(bake, "--mode shadowed --light builtin:sky"), kMatch);
  EXPECT_LT(compareWithRender(bake, "--mode shadowed --light builtin:sky --rotate 20,150,0"),
            kMatch);
  EXPECT_LT(compareWithRender(bake, "--mode interreflected --light builtin:studio"), kMatch);
  EXPECT_LT(compareWithRender(bake,
                              "--mode shadowed --light builtin:sky --material "
                              "'lambert?kd=0.2,0.6,0.9'"),
            kMatch);
  // The comparison can fail: the unturned view against render's image of the turned light.
  const Result r = prt("-q render '" + bake + "' " + std::string(kSize) +
                       " --mode shadowed --light builtin:sky --rotate 0,120,0 -o render.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Result v = prt("view '" + bake + "' --headless " + std::string(kSize) +
                       " --mode shadowed --light builtin:sky --stats --screenshot unturned.png");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_GT(displayedRmse(path("unturned.png"), path("render.png")), 2 * kMatch);
  // --stats says what the CPU uploads at each relight: a 16-byte texel a lightmap texel.
  EXPECT_NE(v.out.find("16 bytes of radiance per texel per relit frame, drawn per pixel from a "
                       "64 x 64 lightmap"),
            std::string::npos)
      << v.out;
}

TEST(ViewCli, HaarBakeOverACubeTooFineToTurnProjectsTheEnvironment) {
  // Past haar::kMaxTurnedResolution (64² a face) the viewer keeps no finer cube to splat: each
  // turn projects the environment itself (haar_view.hpp), which must still be prt render's.
  PRT_REQUIRE_HEADLESS_GL();
  const Result b =
      prt("-q bake 'builtin:sphere-plane?size=1.5&grid=6&subdiv=1' --mode shadowed "
          "--basis haar --resolution 128 --terms 32 -o haar128.glb");
  ASSERT_EQ(b.rc, 0) << b.err;
  EXPECT_LT(compareWithRender(path("haar128.glb"), "--light builtin:sky --rotate 0,120,0"), kMatch);
}

TEST(ViewCli, NoDisplayFailsCleanly) {
  // No skip: this needs no OpenGL at all.
  expectCleanFailure("'" + spherePlaneBake() + "'", "no display",
                     "env -u DISPLAY -u WAYLAND_DISPLAY ");
  // An unreachable display is an error too, not a crash.
  expectCleanFailure("'" + spherePlaneBake() + "'", "display",
                     "env -u WAYLAND_DISPLAY DISPLAY=:97 ");
}

TEST(ViewCli, BadFilesAtStartupFailCleanly) {
  expectCleanFailure("missing.glb --headless", "missing.glb: ");
  // A bake file without transfer.
  BakeFile empty;
  empty.mesh = builtinScene("builtin:sphere?subdiv=1");
  writeBake(path("notransfer.glb"), empty);
  expectCleanFailure("notransfer.glb --headless", "notransfer.glb: the bake holds no transfer");
  // Not a bake at all.
  std::ofstream(scratch() / "garbage.glb") << "not a glb";
  expectCleanFailure("garbage.glb --headless", "garbage.glb: ");
  // Unreadable environments.
  std::ofstream(scratch() / "broken.png") << "not a png";
  expectCleanFailure("'" + spherePlaneBake() + "' --headless --env broken.png", "broken.png: ");
  expectCleanFailure("'" + spherePlaneBake() + "' --headless --env nothere.exr", "nothere.exr");
  // Bad requests.
  expectCleanFailure("'" + spherePlaneBake() + "' --headless --mode interreflected",
                     "no interreflected transfer");
  expectCleanFailure("'" + spherePlaneBake() + "' --headless --bands 40", "--bands");
  expectCleanFailure("'" + spherePlaneBake() + "' --headless --screenshot out.jpg", "out.jpg");
  expectCleanFailure("'" + spherePlaneBake() + "' --screenshot out.png", "--headless");
  expectCleanFailure("'" + spherePlaneBake() + "' --headless --size 0x10", "--size");
  expectCleanFailure("'" + glossyBake() + "' --headless --material 'phong?exponent=-1'",
                     "phong?exponent=-1");
}

// An SH light with fewer bands than the bake (4) is used as it is, with the warning every verb
// gives (the one rule: the transfer's upper bands see no light).
TEST(ViewCli, ALightWithFewerBandsWarnsAndRuns) {
  PRT_REQUIRE_HEADLESS_GL();
  ASSERT_EQ(prt("-q light builtin:sky --bands 2 -o sky2.json").rc, 0);
  const Result v = prt("view '" + cornellBake() + "' --headless " + std::string(kSize) +
                       " --env sky2.json --screenshot few.png");
  EXPECT_EQ(v.rc, 0) << v.err;
  EXPECT_NE(v.err.find("sky2.json: the light has 2 bands but the transfer 4"), std::string::npos)
      << v.err;
  const Result r = prt("render '" + cornellBake() + "' --light sky2.json --size 32x24 -o few.png");
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("sky2.json: the light has 2 bands but the transfer 4"), std::string::npos)
      << r.err;
}

TEST(ViewCli, MoreBandsThanTheBakeWarnsAndRuns) {
  PRT_REQUIRE_HEADLESS_GL();
  const Result v = prt("view '" + spherePlaneBake() + "' --headless " + std::string(kSize) +
                       " --bands 9 --screenshot many.png");
  EXPECT_EQ(v.rc, 0) << v.err;
  EXPECT_NE(v.err.find("but the bake has only 3 bands"), std::string::npos) << v.err;
}

/// The fraction of pixels where the window's screenshot differs from the bare headless frame
/// (by more than 8 code values in a channel): what the panel covers.
double panelCoverage(const image::Image& win, const image::Image& off) {
  std::size_t differ = 0;
  for (std::size_t i = 0; i < win.pixels.size(); ++i) {
    const Rgb d = win.pixels[i] - off.pixels[i];
    if (std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) > 8.0f / 255.0f) ++differ;
  }
  return double(differ) / double(win.pixels.size());
}

TEST(ViewCli, WindowUnderXvfbShowsTheHeadlessFrameAndAPanelThatLeavesItVisible) {
  // The interactive path (GLFW window, ImGui panel) needs a display: use a virtual one when the
  // machine has xvfb-run, else skip.
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (apt-get install xvfb xauth)";
  const auto window = [&](const std::string& size, const std::string& name) {
    const Result w =
        prt("-q view '" + cornellBake() + "' " + size + " --frames 3 --screenshot " + name,
            "xvfb-run -a -s '-screen 0 1600x1000x24' ");
    return w;
  };
  const Result w = window("--size 640x480", "small.png");
  if (w.rc != 0 && w.err.find("cannot open") != std::string::npos)
    GTEST_SKIP() << "no usable virtual display: " << w.err;
  ASSERT_EQ(w.rc, 0) << w.err;
  PRT_REQUIRE_HEADLESS_GL();
  const Result h = prt("-q view '" + cornellBake() +
                       "' --size 640x480 --headless --screenshot "
                       "small-headless.png");
  ASSERT_EQ(h.rc, 0) << h.err;
  const image::Image win = readDisplayed(path("small.png")),
                     off = readDisplayed(path("small-headless.png"));
  ASSERT_EQ(win.width, 640);
  ASSERT_EQ(win.height, 480);
  // The bottom band of the window is the scene alone, and the same OpenGL draws it as the
  // headless frame (both on the same Mesa here).
  const image::Image a = image::crop(win, 0, 420, 640, 60), b = image::crop(off, 0, 420, 640, 60);
  EXPECT_LT(render::rmse(a, b), 2.0 / 255.0);
  // A small window starts with the panel collapsed to its title bar, at the top left.
  EXPECT_GT(render::rmse(image::crop(win, 0, 0, 80, 24), image::crop(off, 0, 0, 80, 24)), 0.02);
  EXPECT_LT(panelCoverage(win, off), 0.03);

  // The default window (1280×800) opens the panel, which still leaves most of the view clear.
  const Result big = window("", "default.png");
  ASSERT_EQ(big.rc, 0) << big.err;
  const Result bigOff =
      prt("-q view '" + cornellBake() + "' --headless --screenshot default-headless.png");
  ASSERT_EQ(bigOff.rc, 0) << bigOff.err;
  const image::Image bw = readDisplayed(path("default.png")),
                     bo = readDisplayed(path("default-headless.png"));
  ASSERT_EQ(bw.width, 1280);
  ASSERT_EQ(bw.height, 800);
  const double covered = panelCoverage(bw, bo);
  EXPECT_GT(covered, 0.03) << "the panel is open";
  EXPECT_LT(covered, 0.15) << "the panel covers " << 100 * covered << "% of the window";
}

}  // namespace
}  // namespace prt::viewer::test
