// The offline renderer: camera framing, primary rays, anti-aliased coverage against the
// analytic silhouette of a sphere, barycentric interpolation, determinism, a golden image with
// an update mode (PRT_UPDATE_GOLDEN=1, see docs/render.md), and the lit side of a relit sphere.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/envmap/analytic.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/image/image_io.hpp"
#include "prt/relight/relight.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/metrics.hpp"
#include "prt/render/primary.hpp"
#include "prt/render/render.hpp"

namespace prt {
namespace {

using render::Camera;
using render::FrameSettings;

TEST(Camera, FramingPutsTheWholeBoundingSphereOnScreen) {
  const Vec3f centre(0.3f, -1.0f, 2.0f);
  const float r = 2.5f;
  for (auto [w, h] : {std::pair{64, 64}, std::pair{200, 50}, std::pair{50, 200}}) {
    const Camera cam = render::frameSphere(centre, r, w, h);
    const render::RayGenerator gen(cam, w, h);
    float minX = 1e9f, maxX = -1e9f, minY = 1e9f, maxY = -1e9f;
    // The silhouette: points on the sphere whose normal is perpendicular to the eye ray.
    for (int i = 0; i < 2000; ++i) {
      const float z = 1.0f - (2.0f * i + 1.0f) / 2000.0f, s = std::sqrt(1 - z * z);
      const Vec3f n(s * std::cos(2.399963f * i), z, s * std::sin(2.399963f * i));
      float px, py;
      ASSERT_TRUE(gen.project(centre + n * r, px, py));
      minX = std::min(minX, px), maxX = std::max(maxX, px);
      minY = std::min(minY, py), maxY = std::max(maxY, py);
    }
    EXPECT_GE(minX, 0.0f);
    EXPECT_LE(maxX, float(w));
    EXPECT_GE(minY, 0.0f);
    EXPECT_LE(maxY, float(h));
    // ... and fills it: the sphere spans most of the limiting dimension.
    const float span = std::max((maxX - minX) / w, (maxY - minY) / h);
    EXPECT_GT(span, 0.8f) << w << "x" << h;
    // Default view: from above and in front, looking at the centre, +Y up.
    EXPECT_GT(cam.eye.y, centre.y);
    EXPECT_GT(cam.eye.z, centre.z);
    EXPECT_EQ(cam.target, centre);
  }
}

TEST(Camera, RaysAndProjectionAreInverse) {
  Camera cam;
  cam.eye = {1, 2, 3};
  cam.target = {0, 0.5f, 0};
  cam.fovY = 55;
  const render::RayGenerator gen(cam, 120, 80);
  for (float px : {0.0f, 17.5f, 60.0f, 120.0f})
    for (float py : {0.0f, 40.0f, 79.0f}) {
      const Ray r = gen.ray(px, py);
      EXPECT_NEAR(length(r.dir), 1.0f, 1e-6f);
      float qx, qy;
      ASSERT_TRUE(gen.project(r.origin + r.dir * 7.0f, qx, qy));
      EXPECT_NEAR(qx, px, 1e-3f);
      EXPECT_NEAR(qy, py, 1e-3f);
    }
  // The image centre looks at the target; the top row looks up.
  const Ray c = gen.ray(60, 40);
  EXPECT_NEAR(dot(c.dir, normalize(cam.target - cam.eye)), 1.0f, 1e-6f);
  EXPECT_GT(gen.ray(60, 0).dir.y, c.dir.y);
}

TEST(Camera, ParsesSpecsAndRejectsBadOnes) {
  const Camera c = render::parseCamera("eye=1,2,3;target=0,1,0; fov=30", Camera{});
  EXPECT_EQ(c.eye, Vec3f(1, 2, 3));
  EXPECT_EQ(c.target, Vec3f(0, 1, 0));
  EXPECT_EQ(c.fovY, 30.0f);
  EXPECT_EQ(c.up, Vec3f(0, 1, 0));
  EXPECT_THROW(render::parseCamera("eye=1,2", Camera{}), Error);
  EXPECT_THROW(render::parseCamera("fov=0", Camera{}), Error);
  EXPECT_THROW(render::parseCamera("fov=abc", Camera{}), Error);
  EXPECT_THROW(render::parseCamera("zoom=2", Camera{}), Error);
  EXPECT_THROW(render::parseCamera("eye=0,0,0;target=0,0,0", Camera{}), Error);
  EXPECT_THROW(render::parseCamera("eye=0,5,0;target=0,0,0", Camera{}), Error);  // up ∥ view
}

TEST(Render, RejectsBadFrameSettings) {
  const Mesh m = builtinScene("builtin:sphere?subdiv=1");
  const auto occ = makeEmbreeOccluder(m);
  const std::vector<Rgb> rad(m.vertexCount(), Rgb(1.0f));
  for (auto [w, h, spp] :
       {std::tuple{0, 10, 1}, std::tuple{10, 0, 1}, std::tuple{-3, 10, 1}, std::tuple{10, 10, 0}}) {
    FrameSettings s{w, h, spp, 0};
    EXPECT_THROW(render::renderRelit(m, *occ, rad, Camera{}, s, {}), Error);
  }
  const std::vector<Rgb> wrong(m.vertexCount() - 1, Rgb(1.0f));
  EXPECT_THROW(render::renderRelit(m, *occ, wrong, Camera{}, {8, 8, 1, 0}, {}), Error);
}

TEST(Render, CameraInsideMeshIsDetected) {
  const Mesh m = builtinScene("builtin:sphere?subdiv=2");
  const auto occ = makeEmbreeOccluder(m);
  EXPECT_TRUE(render::eyeInsideMesh(m, *occ, Vec3f(0.1f, 0.2f, 0.0f)));
  EXPECT_FALSE(render::eyeInsideMesh(m, *occ, Vec3f(0.0f, 0.5f, 4.0f)));
}

TEST(Render, CoverageOfASphereMatchesItsAnalyticSilhouette) {
  // A sphere of constant radiance c in front of a black background: pixels average c times the
  // covered fraction, so the image sum / c is the silhouette area in pixels. Seen from distance
  // d, the silhouette is a circle of angular radius asin(r/d), i.e. of radius
  // tan(asin(r/d)) / tan(fovY/2) · h/2 pixels when centred. The mesh is an icosphere, whose
  // silhouette is a little inside the true sphere: allow 1%.
  const Mesh m = builtinScene("builtin:sphere?subdiv=5");
  const auto occ = makeEmbreeOccluder(m);
  const Rgb c(0.5f, 1.0f, 2.0f);
  const std::vector<Rgb> rad(m.vertexCount(), c);
  Camera cam;
  cam.eye = {0, 0, 4};
  cam.fovY = 40;
  const FrameSettings s{96, 96, 16, 3};
  const image::Image img = render::renderRelit(m, *occ, rad, cam, s, {});
  double sum = 0;
  for (const Rgb& p : img.pixels) sum += p.y / c.y;
  const double rPix = std::tan(std::asin(1.0 / 4.0)) / std::tan(20.0 * kPi / 180) * 48;
  EXPECT_NEAR(sum / (kPi * rPix * rPix), 1.0, 0.01);
  // Fully covered pixels are exactly c; edge pixels are fractions of it (anti-aliasing).
  EXPECT_EQ(img.at(48, 48), c);
  int partial = 0;
  for (const Rgb& p : img.pixels) partial += (p.y > 0.05f && p.y < 0.95f);
  EXPECT_GT(partial, int(2 * kPi * rPix * 0.5));  // most of the rim is anti-aliased
}

TEST(Render, InterpolatesVertexRadianceWithBarycentrics) {
  // Radiance linear in position is reproduced exactly at every hit point on flat triangles.
  const Mesh m = builtinScene("builtin:sphere?subdiv=3");
  const auto occ = makeEmbreeOccluder(m);
  std::vector<Rgb> rad(m.vertexCount());
  auto f = [](const Vec3f& p) { return Rgb(2 + p.x, 2 + p.y, 2 + 0.5f * p.z); };
  for (std::size_t v = 0; v < rad.size(); ++v) rad[v] = f(m.positions[v]);
  const auto shade = render::vertexRadianceShader(m, rad);
  const Camera cam = render::frameMesh(m, 32, 32);
  const render::RayGenerator gen(cam, 32, 32);
  int hits = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const Ray r = gen.ray(x + 0.5f, y + 0.5f);
      const Hit h = occ->intersect(r);
      if (!h.hit) continue;
      ++hits;
      const Rgb expected = f(r.origin + r.dir * h.t);
      const Rgb got = shade(r, h);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], expected[c], 1e-4f);
    }
  EXPECT_GT(hits, 500);  // the framed sphere covers ~60% of the image
}

TEST(Render, DeterministicAndIndependentOfThreads) {
  const Mesh m = builtinScene("builtin:sphere?subdiv=2");
  const auto occ = makeEmbreeOccluder(m);
  std::vector<Rgb> rad(m.vertexCount());
  for (std::size_t v = 0; v < rad.size(); ++v) rad[v] = Rgb(m.normals[v].x + 1, 0.5f, 1.0f);
  const Camera cam = render::frameMesh(m, 40, 30);
  const auto bg = render::colourBackground(Rgb(0.2f, 0.3f, 0.4f));
  const FrameSettings s{40, 30, 8, 11};
  image::Image one;
  {
    ThreadLimit limit(1);
    one = render::renderRelit(m, *occ, rad, cam, s, bg);
  }
  const image::Image all = render::renderRelit(m, *occ, rad, cam, s, bg);
  EXPECT_EQ(render::rmse(one, all), 0.0);
  FrameSettings other = s;
  other.seed = 12;
  EXPECT_GT(render::rmse(render::renderRelit(m, *occ, rad, cam, other, bg), all), 0.0);
  for (int c = 0; c < 3; ++c)  // background in the corner
    EXPECT_NEAR(all.at(0, 0)[c], Rgb(0.2f, 0.3f, 0.4f)[c], 1e-6f);
}

TEST(Render, SubpixelOffsetsAreStratified) {
  // 16 samples of one pixel: one in each cell of a 4×4 grid (the (0,2)-net property).
  const FrameSettings s{10, 10, 16, 5};
  bool cell[4][4] = {};
  for (int k = 0; k < 16; ++k) {
    const Vec2f o = render::subpixelOffset(s, 3, 7, k);
    ASSERT_GE(o.x, 0.0f);
    ASSERT_LT(o.x, 1.0f);
    cell[int(o.x * 4)][int(o.y * 4)] = true;
  }
  for (auto& row : cell)
    for (bool b : row) EXPECT_TRUE(b);
}

// The golden scene: a unit icosphere whose transfer is the analytic unshadowed clamped-cosine
// lobe, T_lm(n) = (Λ_l/π) Y_lm(n) (exact, no bake), lit by a bright cap toward `lightDir` plus a
// little constant sky, 3 bands.
struct Golden {
  Mesh mesh;
  Transfer transfer;
  sh::RgbSh light;
  Vec3f lightDir = normalize(Vec3f(1.0f, 0.6f, 0.4f));
};

Golden goldenScene() {
  Golden g;
  g.mesh = builtinScene("builtin:sphere?subdiv=3&albedo=0.8");
  const int bands = 3;
  const double lambda[3] = {kPi, 2 * kPi / 3, kPi / 4};
  std::vector<float> values;
  for (const Vec3f& n : g.mesh.normals) {
    double y[9];
    sh::evalReference(bands, Vec3d(n), y);
    for (int l = 0; l < bands; ++l)
      for (int m = -l; m <= l; ++m) values.push_back(float(lambda[l] / kPi * y[sh::index(l, m)]));
  }
  TransferShape shape;
  shape.bands = bands;
  shape.rows = {0, g.mesh.vertexCount()};
  g.transfer = Transfer::dense(shape, FloatArray(std::move(values)));
  envmap::Cap cap;
  cap.direction = g.lightDir;
  cap.halfAngle = 0.35;
  cap.radiance = Rgb(6.0f, 5.0f, 4.0f);
  g.light = envmap::capSh(bands, cap);
  const sh::RgbSh sky = envmap::constantSh(bands, Rgb(0.05f, 0.07f, 0.1f));
  for (int i = 0; i < bands * bands; ++i) g.light.c[i] += sky.c[i];
  return g;
}

TEST(Render, LitSideFacesTheLight) {
  const Golden g = goldenScene();
  const auto occ = makeEmbreeOccluder(g.mesh);
  const auto rad =
      relight::relight(g.transfer, g.light, Material{}, {{}, {}, g.mesh.albedo}, Vec3f(0.0f));
  const Camera cam = render::frameMesh(g.mesh, 64, 64);
  const image::Image img = render::renderRelit(g.mesh, *occ, rad, cam, {64, 64, 4, 0}, {});
  // Luminance-weighted centroid of the image, relative to where the sphere centre projects,
  // must point where the light direction projects.
  const render::RayGenerator gen(cam, 64, 64);
  float cx, cy, lx, ly;
  ASSERT_TRUE(gen.project(Vec3f(0.0f), cx, cy));
  ASSERT_TRUE(gen.project(g.lightDir, lx, ly));
  double sx = 0, sy = 0, sw = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double w = image::luminance(img.at(x, y));
      sx += w * (x + 0.5 - cx), sy += w * (y + 0.5 - cy), sw += w;
    }
  const double dx = sx / sw, dy = sy / sw, ex = lx - cx, ey = ly - cy;
  const double cosAngle = (dx * ex + dy * ey) / std::hypot(dx, dy) / std::hypot(ex, ey);
  EXPECT_GT(cosAngle, 0.95);
  EXPECT_GT(std::hypot(dx, dy), 3.0);  // clearly off-centre, not a flat disc
  // Rotating the light by 180° about +Y moves the lit side: the centroid's x flips sign.
  const auto rotated = relight::relight(g.transfer, g.light, Material{}, {{}, {}, g.mesh.albedo},
                                        Vec3f(0.0f), rotationEulerXYZ(0, 180, 0));
  const image::Image img2 = render::renderRelit(g.mesh, *occ, rotated, cam, {64, 64, 4, 0}, {});
  double sx2 = 0, sw2 = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double w = image::luminance(img2.at(x, y));
      sx2 += w * (x + 0.5 - cx), sw2 += w;
    }
  EXPECT_LT(sx2 / sw2 * dx, 0.0);
}

TEST(Render, GoldenImage) {
  const Golden g = goldenScene();
  const auto occ = makeEmbreeOccluder(g.mesh);
  const auto rad =
      relight::relight(g.transfer, g.light, Material{}, {{}, {}, g.mesh.albedo}, Vec3f(0.0f));
  const Camera cam = render::frameMesh(g.mesh, 64, 48);
  image::Image img = render::renderRelit(g.mesh, *occ, rad, cam, {64, 48, 4, 0},
                                         render::shBackground(g.light, Mat3d::identity()));
  // Compare display-referred values (clamp tone map), which is what the PNG stores.
  for (Rgb& p : img.pixels) p = image::toneMap(p, image::ToneMap::Clamp);
  const std::string path = std::string(PRT_SOURCE_DIR) + "/tests/data/golden/render_sphere_cap.png";
  const char* update = std::getenv("PRT_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    image::WriteOptions o;
    o.toneMap = image::ToneMap::Clamp;
    image::writeImage(path, img, o);
    GTEST_SKIP() << "golden image updated: " << path;
  }
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " missing: run with PRT_UPDATE_GOLDEN=1";
  const image::Image golden = image::readImage(path);
  const render::ErrorStats e = render::compareImages(img, golden);
  // 8-bit sRGB quantisation alone gives an RMSE below 0.002 in linear units.
  EXPECT_LT(e.rmse, 0.004) << "max abs " << e.maxAbs;
}

TEST(Metrics, KnownDifferences) {
  image::Image a(4, 3, Rgb(0.5f)), b(4, 3, Rgb(0.5f));
  EXPECT_EQ(render::rmse(a, b), 0.0);
  for (Rgb& p : a.pixels) p += Rgb(0.1f, 0.1f, 0.1f);
  EXPECT_NEAR(render::rmse(a, b), 0.1, 1e-6);
  EXPECT_NEAR(render::relativeRmse(a, b, 0.0), 0.2, 1e-6);
  a.at(2, 1) = Rgb(1.5f, 0.6f, 0.6f);  // one channel off by 1.0
  const auto e = render::compareImages(a, b);
  EXPECT_NEAR(e.maxAbs, 1.0, 1e-6);
  EXPECT_NEAR(e.rmse, std::sqrt((35 * 0.01 + 1.0) / 36), 1e-6);
  EXPECT_THROW(render::rmse(a, image::Image(3, 4)), Error);
  EXPECT_THROW(render::rmse(image::Image(), image::Image()), Error);
}

TEST(Metrics, FalseColourIsMonotoneAndErrorImageScales) {
  float prev = -1;
  for (int i = 0; i <= 100; ++i) {
    const float l = image::luminance(render::falseColour(i / 100.0f));
    EXPECT_GT(l, prev);
    prev = l;
  }
  image::Image ref(10, 1, Rgb(1.0f)), test = ref;
  for (int x = 0; x < 10; ++x) test.at(x, 0) = Rgb(1.0f + 0.1f * x);
  const image::Image err = render::errorImage(test, ref, 0.9);
  EXPECT_EQ(err.at(0, 0), render::falseColour(0.0f));
  EXPECT_EQ(err.at(9, 0), render::falseColour(1.0f));
  for (int x = 1; x < 10; ++x)
    EXPECT_GT(image::luminance(err.at(x, 0)), image::luminance(err.at(x - 1, 0)));
}

TEST(ContactSheet, TilesFramesInOrder) {
  std::vector<image::Image> frames;
  for (int k = 0; k < 5; ++k) frames.emplace_back(4, 3, Rgb(float(k + 1)));
  const image::Image sheet = render::contactSheet(frames, 0, 1);
  EXPECT_EQ(sheet.width, 3 * 4 + 4);   // 3 columns
  EXPECT_EQ(sheet.height, 2 * 3 + 3);  // 2 rows
  EXPECT_EQ(sheet.at(1, 1), Rgb(1.0f));
  EXPECT_EQ(sheet.at(1 + 5, 1), Rgb(2.0f));
  EXPECT_EQ(sheet.at(1 + 5, 1 + 4), Rgb(5.0f));
  EXPECT_EQ(sheet.at(0, 0), Rgb(0.0f));                               // border
  EXPECT_EQ(sheet.at(sheet.width - 2, sheet.height - 2), Rgb(0.0f));  // empty 6th cell
}

}  // namespace
}  // namespace prt
