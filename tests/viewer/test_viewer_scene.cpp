// The viewer's pieces in-process: the per-frame light packing against the library's relighting
// layout, the light drag as a rotation by a known angle (and its frame against prt render
// --rotate), band truncation, and dropped files that fail leaving the scene as it was.

#include <epoxy/gl.h>

#include <random>

#include "prt/envmap/builtin.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/shader_transfer.hpp"
#include "prt/transport/bake.hpp"
#include "renderer.hpp"
#include "scene.hpp"
#include "viewer_test_util.hpp"

namespace prt::viewer::test {
namespace {

sh::RgbSh randomLight(int bands, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  sh::RgbSh l(bands);
  for (Rgb& c : l.c) c = {u(rng), u(rng), u(rng)};
  return l;
}

TEST(LightPacker, MatchesRelightPreparedLight) {
  // relight::prepareLight is the CPU relighting's rotated light: the shader must see the same.
  const Mat3d r = rotationEulerXYZ(23, -71, 140);
  for (int bands : {1, 3, 9, 16}) {
    SCOPED_TRACE(bands);
    const sh::RgbSh light = randomLight(bands, 7u + bands);
    LightPacker p;
    p.setLight(light);
    p.pack(r, bands);
    const sh::Rotation rot(bands, r);
    const relight::PreparedLight ref = relight::prepareLight(light, bands, &rot);
    for (int i = 0; i < bands * bands; ++i)
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(p.rotated()[i][c], ref.interleaved[3 * i + c], 2e-6f) << i;
        EXPECT_EQ(p.data()[4 * i + c], p.rotated()[i][c]) << i;
      }
    // Padding up to a multiple of four coefficients is zero (the shader reads it).
    for (int i = 4 * bands * bands; i < 4 * paddedCoeffs(bands); ++i) EXPECT_EQ(p.data()[i], 0.0f);
    EXPECT_EQ(p.bytes(), 16u * paddedCoeffs(bands));
  }
}

TEST(LightPacker, TruncationEqualsRotatingTheTruncatedLight) {
  const Mat3d r = rotationEulerXYZ(-40, 15, 75);
  const sh::RgbSh light = randomLight(9, 3);
  LightPacker full, cut;
  full.setLight(light);
  cut.setLight(light.truncated(4));
  full.pack(r, 4);  // 4 of 9 bands
  cut.pack(r, 4);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(full.rotated()[i], cut.rotated()[i]);
  // And a wrong rotation gives a different answer (the check can fail).
  cut.pack(rotationEulerXYZ(-40, 16, 75), 4);
  double diff = 0;
  for (int i = 1; i < 16; ++i) diff += length(full.rotated()[i] - cut.rotated()[i]);
  EXPECT_GT(diff, 1e-3);
}

Scene smallScene(int width, int height) {
  Scene s;
  s.setBake(Scene::readCheckedBake(spherePlaneBake()), spherePlaneBake(), width, height);
  s.addEnvironment(Scene::loadEnvironment("builtin:sky", s.bakeBands()));
  return s;
}

TEST(Scene, DragByKnownPixelsIsAKnownRotation) {
  Scene s = smallScene(160, 120);
  const double pixels = 90.0 / kDragDegreesPerPixel;  // a quarter turn about +Y
  s.dragLight(pixels, 0.0);
  const Mat3d want = rotationEulerXYZ(0, 90, 0), got = s.lightRotation();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(got.m[i][j], want.m[i][j], 1e-12);
  s.resetLight();
  EXPECT_NEAR(s.lightRotation().m[0][0], 1.0, 0.0);
  // Auto-rotation is about +Y at the set speed.
  s.autoRotate = true;
  s.spinDegreesPerSecond = 45.0;
  s.advanceSpin(2.0);
  const Mat3d spun = s.lightRotation();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(spun.m[i][j], want.m[i][j], 1e-12);
}

TEST(Scene, DraggedLightFrameMatchesRenderRotate) {
  PRT_REQUIRE_HEADLESS_GL();
  const Result r =
      prt("-q render --exposure 0 '" + spherePlaneBake() + "' --size 160x120 --rotate 0,90,0 -o rotated.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Result r0 = prt("-q render --exposure 0 '" + spherePlaneBake() + "' --size 160x120 -o plain.png");
  ASSERT_EQ(r0.rc, 0) << r0.err;

  Scene s = smallScene(160, 120);
  s.dragLight(90.0 / kDragDegreesPerPixel, 0.0);
  HeadlessContext context;
  SceneView view;
  OffscreenTarget target(160, 120);
  view.renderer().draw(view.prepare(s, 160, 120), target.fbo());
  ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  image::Image shown = target.readEncoded();
  const double e = render::rmse(shown, readDisplayed(path("rotated.png")));
  EXPECT_LT(e, 0.012);
  EXPECT_GT(render::rmse(shown, readDisplayed(path("plain.png"))), 4 * 0.012);
}

TEST(Scene, BandsClampAndTruncateLive) {
  Scene s = smallScene(160, 120);
  EXPECT_EQ(s.bands(), 3);
  s.setBands(9);
  EXPECT_EQ(s.bands(), 3);
  s.setBands(0);
  EXPECT_EQ(s.bands(), 1);
  const DrawState before = s.drawState();
  s.setBands(2);
  EXPECT_FALSE(s.drawState() == before);  // what is drawn changed: a view rebuilds what needs it
  EXPECT_EQ(s.drawState().bands, 2);
  s.setBands(2);
  const DrawState same = s.drawState();
  EXPECT_TRUE(s.drawState() == same);
}

TEST(Scene, FailedDropsLeaveTheSceneAsItWas) {
  Scene s = smallScene(160, 120);
  const std::size_t envs = s.environmentCount();
  const std::size_t verts = s.bake().mesh.vertexCount();

  std::string e = s.loadDropped(path("nothere.exr"), 160, 120);
  EXPECT_NE(e.find("nothere.exr"), std::string::npos) << e;
  std::ofstream(scratch() / "dropped_broken.png") << "not a png";
  e = s.loadDropped(path("dropped_broken.png"), 160, 120);
  EXPECT_NE(e.find("dropped_broken.png"), std::string::npos) << e;
  BakeFile empty;
  empty.mesh = builtinScene("builtin:sphere?subdiv=1");
  writeBake(path("dropped_empty.glb"), empty);
  e = s.loadDropped(path("dropped_empty.glb"), 160, 120);
  EXPECT_NE(e.find("holds no transfer"), std::string::npos) << e;
  EXPECT_EQ(s.environmentCount(), envs);
  EXPECT_EQ(s.bake().mesh.vertexCount(), verts);

  // A good drop is added and shown.
  e = s.loadDropped("builtin:studio", 160, 120);
  EXPECT_EQ(e, "");
  EXPECT_EQ(s.environmentCount(), envs + 1);
  EXPECT_EQ(s.environmentIndex(), int(envs));
  // An SH light file with fewer bands than the bake's 3 is used, padded with zeros (the one
  // rule every verb follows: the transfer's upper bands see no light), and the scene says so.
  std::vector<std::string> warnings;
  s.warn = [&](const std::string& w) { warnings.push_back(w); };
  ASSERT_EQ(prt("-q light builtin:sky --bands 2 -o dropped_sky2.json").rc, 0);
  EXPECT_EQ(s.loadDropped(path("dropped_sky2.json"), 160, 120), "");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("the light has 2 bands but the transfer 3"), std::string::npos)
      << warnings[0];
  EXPECT_EQ(s.environment(s.environmentIndex()).light.bands, 3);
  EXPECT_EQ(s.environment(s.environmentIndex()).light.c[4], Rgb(0.0f));  // band 2 is zero
  // A dropped bake with other bands re-projects the environments to its bands.
  e = s.loadDropped(cornellBake(), 160, 120);
  EXPECT_EQ(e, "");
  EXPECT_EQ(s.bakeBands(), 4);
  for (std::size_t k = 0; k < s.environmentCount(); ++k) EXPECT_EQ(s.environment(k).light.bands, 4);
  EXPECT_EQ(s.transfer().recipe.mode, TransferMode::Interreflected);  // the richest first
}

/// A sphere over a plane baked twice, shadowed, 3 bands: a vector (Lambert) and a matrix
/// (Phong), in that order in the file.
BakeFile vectorAndMatrixBake() {
  BakeFile b;
  b.mesh = builtinScene("builtin:sphere-plane?grid=8&subdiv=2");
  const auto occluder = makeEmbreeOccluder(b.mesh);
  for (TransferLayout layout : {TransferLayout::Vector, TransferLayout::Matrix}) {
    BakeSettings s;
    s.layout = layout;
    s.bands = 3;
    s.samples = 16;
    if (layout == TransferLayout::Matrix)
      s.material = parseMaterial("phong?exponent=8&ks=0.5&kd=0.5");
    BakedTransfer t;
    t.recipe = s;
    t.transfer = prt::bake(b.mesh, *occluder, s, &t.stats);
    b.transfers.push_back(std::move(t));
  }
  return b;
}

TEST(Scene, PicksMatrixFirstAndItsMaterialUnlessOverridden) {
  Scene s;
  s.setBake(vectorAndMatrixBake(), "both", 64, 48);
  // pickTransfer's order: a matrix before a vector of the same mode; its material with it.
  ASSERT_TRUE(s.transfer().transfer.isMatrix());
  EXPECT_EQ(s.material().spec(), "phong?exponent=8&ks=0.5&kd=0.5");
  s.selectTransfer(1);
  EXPECT_FALSE(s.transfer().transfer.isMatrix());
  EXPECT_FALSE(s.material().glossy());
  // --material: one material for every transfer from then on.
  const Material ggx = parseMaterial("ggx?roughness=0.4&ks=0.3");
  s.overrideMaterial(ggx);
  s.selectTransfer(0);
  EXPECT_EQ(s.material(), ggx);
}

TEST(Scene, GlossyRadianceIsRenderRelightAndFollowsLightEyeAndMaterial) {
  PRT_REQUIRE_HEADLESS_GL();
  HeadlessContext context;
  Scene s;
  s.setBake(vectorAndMatrixBake(), "both", 64, 48);
  s.addEnvironment(Scene::loadEnvironment("builtin:sky", s.bakeBands()));
  s.setUserRotation(rotationEulerXYZ(10, 50, -20));
  SceneView view;
  const auto expected = [&] {
    // prt render's call: the unrotated light, the rotation, the camera's eye.
    const Mesh& m = s.bake().mesh;
    return relight::relight(
        s.transfer().transfer.cut(s.bands()), s.environment(0).light.truncated(s.bands()),
        s.material(), {m.positions, m.normals, m.albedo}, s.orbit.camera().eye, s.lightRotation());
  };
  const auto maxDiff = [&](const std::vector<Rgb>& want) {
    const std::span<const Rgb> got = view.cpuRadiance();
    EXPECT_EQ(got.size(), want.size());
    double worst = 0, peak = 0;
    for (std::size_t v = 0; v < std::min(got.size(), want.size()); ++v)
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, double(std::abs(got[v][c] - want[v][c])));
        peak = std::max(peak, double(std::abs(want[v][c])));
      }
    return worst / std::max(peak, 1e-30);
  };
  view.prepare(s, 64, 48);
  EXPECT_EQ(view.cpuRelights(), 1);
  EXPECT_LT(maxDiff(expected()), 1e-5);
  // Nothing changed: not relit.
  view.prepare(s, 64, 48);
  EXPECT_EQ(view.cpuRelights(), 1);
  // The eye moves: relit, and the lobe moves with it (the old radiance is wrong now).
  const std::vector<Rgb> before(view.cpuRadiance().begin(), view.cpuRadiance().end());
  s.orbit.orbit(0.8, 0.2);
  view.prepare(s, 64, 48);
  EXPECT_EQ(view.cpuRelights(), 2);
  EXPECT_LT(maxDiff(expected()), 1e-5);
  EXPECT_GT(maxDiff(before), 1e-2);
  // The light turns, the material changes, the bands drop: relit each time, still render's.
  s.dragLight(40, -25);
  view.prepare(s, 64, 48);
  EXPECT_LT(maxDiff(expected()), 1e-5);
  // Only the light changed (same eye): served from the view-collapsed transfer, twice.
  EXPECT_EQ(view.cpuLightOnlyRelights(), 1);
  s.dragLight(-70, 10);
  view.prepare(s, 64, 48);
  EXPECT_EQ(view.cpuLightOnlyRelights(), 2);
  EXPECT_LT(maxDiff(expected()), 1e-5);
  s.setMaterial(parseMaterial("ggx?roughness=0.3&ks=0.6&kd=0.2"));
  view.prepare(s, 64, 48);
  EXPECT_LT(maxDiff(expected()), 1e-5);
  EXPECT_EQ(view.cpuRelights(), 5);
  EXPECT_EQ(view.cpuLightOnlyRelights(), 2);  // a new material is not a light-only change
  s.setBands(2);
  view.prepare(s, 64, 48);
  EXPECT_EQ(view.cpuRelights(), 6);
  EXPECT_LT(maxDiff(expected()), 1e-5);
}

// The compressed frame against the viewer's own dense-reconstruction frame: the same bake drawn
// once from its compressed form (cluster table per frame, weighted sums in the shader) and once
// expanded (Transfer::toDense, the dense path) must agree to float rounding in linear
// radiance, vectors and glossy matrices on the GPU and on the CPU, at all and at fewer bands. Both
// are relit from the same rows (the reconstruction is linear), interpolated by the same rasteriser,
// so only the order of float operations differs.
TEST(Scene, CompressedFrameEqualsDenseReconstructionFrame) {
  PRT_REQUIRE_HEADLESS_GL();
  HeadlessContext context;
  const auto frame = [](const std::string& bakePath, bool expand, bool glossyOnGpu, int bands,
                        double turnDeg, bool* drewCompressed) {
    BakeFile b = Scene::readCheckedBake(bakePath);
    if (expand)
      for (BakedTransfer& t : b.transfers) t.transfer = t.transfer.toDense();
    Scene s;
    s.setBake(std::move(b), bakePath, 96, 72);
    s.addEnvironment(Scene::loadEnvironment("builtin:sky", s.bakeBands()));
    s.setUserRotation(rotationEulerXYZ(15, 40 + turnDeg, -10));
    s.setBands(bands);
    SceneView view;
    view.glossyOnGpu = glossyOnGpu;
    OffscreenTarget target(96, 72);
    view.renderer().draw(view.prepare(s, 96, 72), target.fbo());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    *drewCompressed = view.path() == relight::ShaderPath::CpcaVector ||
                      view.path() == relight::ShaderPath::CpcaMatrix;
    return view.renderer().readLinear();
  };
  const auto compare = [](const image::Image& a, const image::Image& b) {
    double worst = 0, peak = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, double(std::abs(a.pixels[i][c] - b.pixels[i][c])));
        peak = std::max(peak, double(std::abs(b.pixels[i][c])));
      }
    return worst / std::max(peak, 1e-30);
  };
  struct Case {
    std::string bake;
    bool glossyOnGpu;
    int bands;
  };
  // Glossy on the CPU: relight::relight of the compressed rows into the radiance buffer (the renderer draws
  // radiance, not compressed data), against relight::relight of the expanded matrices.
  for (const Case& c :
       {Case{compressedSphereBake(), false, 3}, Case{compressedSphereBake(), false, 2},
        Case{compressedCornellBake(), false, 4}, Case{compressedGlossyBake(), true, 4},
        Case{compressedGlossyBake(), true, 3}, Case{compressedGlossyBake(), false, 4},
        Case{compressedGlossyBake(), false, 3}}) {
    SCOPED_TRACE(c.bake + " bands " + std::to_string(c.bands) + (c.glossyOnGpu ? " gpu" : ""));
    const bool onGpu = c.glossyOnGpu || c.bake != compressedGlossyBake();
    bool compressed = false, dense = true;
    const image::Image a = frame(c.bake, false, c.glossyOnGpu, c.bands, 0, &compressed);
    EXPECT_EQ(compressed, onGpu);
    const image::Image b = frame(c.bake, true, c.glossyOnGpu, c.bands, 0, &dense);
    EXPECT_FALSE(dense);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_LT(compare(a, b), 1e-4);
    // The comparison can fail: the light turned by 30° is far off.
    const image::Image t = frame(c.bake, false, c.glossyOnGpu, c.bands, 30, &compressed);
    EXPECT_GT(compare(t, b), 1e-2);
  }
}

}  // namespace
}  // namespace prt::viewer::test

namespace prt::viewer::test {
namespace {

TEST(MovingObject, StaysInTheProbesBoxAndFollowsTheCursor) {
  ProbeGrid g;
  g.origin = Vec3f(0.0f);
  g.spacing = Vec3f(1.0f);
  g.count = {4, 4, 4};  // probes span [0, 3]³
  MovingObject o(builtinScene("builtin:sphere?subdiv=1"), "builtin:sphere", g);
  EXPECT_EQ(o.position(), Vec3f(1.5f));
  EXPECT_FLOAT_EQ(o.size(), 0.2f * 4.0f);  // a fifth of the grid's side, cells included
  o.moveTo({10.0f, -5.0f, 1.0f});
  EXPECT_EQ(o.position(), Vec3f(3.0f, 0.0f, 1.0f));
  // A camera on +Z looking at the object: a drag of (dx, dy) pixels moves it by dx, −dy pixels
  // of the view at its depth (2 d tan(fovY/2) / height a pixel) along right and up.
  o.moveTo(Vec3f(1.5f));
  render::Camera cam;
  cam.eye = {1.5f, 1.5f, 11.5f};
  cam.target = Vec3f(1.5f);
  cam.fovY = 60.0f;
  const int height = 500;
  o.drag(cam, 50, -25, height);
  const double perPixel = 2.0 * 10.0 * std::tan(30.0 * kPi / 180.0) / height;
  EXPECT_NEAR(o.position().x, 1.5 + 50 * perPixel, 1e-4);
  EXPECT_NEAR(o.position().y, 1.5 + 25 * perPixel, 1e-4);
  EXPECT_NEAR(o.position().z, 1.5, 1e-6);
  // Placed, its largest side is its size and its centre where it is.
  o.setSize(1.0f);
  const Mesh m = o.placed();
  const Bounds b = computeBounds(m);
  EXPECT_NEAR(b.hi.x - b.lo.x, 1.0f, 1e-5);
  EXPECT_NEAR(b.centre().x, o.position().x, 1e-5);
  o.setSize(100.0f);  // clamped to four times the default
  EXPECT_FLOAT_EQ(o.size(), 4 * o.defaultSize());
}

}  // namespace
}  // namespace prt::viewer::test
