// The auto exposure (image/exposure.hpp, render/exposure.hpp) and the default framing
// (render::meshFraming): at most 2% of model pixels clip, brighter radiance gets exactly fewer
// stops, and an object on a ground plane fills at least 40% of the frame's width.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "prt/envmap/load.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/image/exposure.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/exposure.hpp"
#include "prt/transport/bake.hpp"

namespace prt {
namespace {

using image::ToneMap;

std::vector<Rgb> logNormalPixels(std::size_t n, float sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::lognormal_distribution<float> d(0.0f, sigma);
  std::vector<Rgb> px(n);
  for (Rgb& p : px) p = Rgb(d(rng), d(rng) * 0.8f, d(rng) * 0.6f);
  return px;
}

TEST(AutoExposure, ClipsAtMostTwoPercentAndScalesWithRadiance) {
  for (ToneMap op : {ToneMap::Aces, ToneMap::Reinhard, ToneMap::Clamp})
    for (float sigma : {0.2f, 1.0f, 3.0f}) {  // sigma 3: a few very bright highlights
      std::vector<Rgb> px = logNormalPixels(20000, sigma, 7);
      const float stops = image::autoExposure(px, op);
      EXPECT_LE(image::clippedFraction(px, op, stops), image::kAutoExposureClipFraction);
      // Exposed at 0 the wide images clip far more: the rule is doing the work.
      if (sigma >= 3.0f) {
        EXPECT_GT(image::clippedFraction(px, op, stops + 2.0f), 0.02f);
      }
      for (float k : {8.0f, 1.0f / 32.0f, 1000.0f}) {
        std::vector<Rgb> brighter = px;
        for (Rgb& p : brighter) p = p * k;
        EXPECT_NEAR(image::autoExposure(brighter, op), stops - std::log2(k), 1e-4)
            << "k " << k << " sigma " << sigma;
      }
    }
  EXPECT_EQ(image::autoExposure({}, ToneMap::Aces), 0.0f);
  const std::vector<Rgb> black(10, Rgb(0.0f));
  EXPECT_EQ(image::autoExposure(black, ToneMap::Aces), 0.0f);
}

TEST(AutoExposure, ClipInputIsWhereTheToneMapReachesCode255) {
  for (ToneMap op : {ToneMap::Aces, ToneMap::Reinhard, ToneMap::Clamp}) {
    const float v = image::clipInput(op);
    EXPECT_TRUE(image::clipped(Rgb(v * 1.001f), op, 0.0f));
    EXPECT_FALSE(image::clipped(Rgb(v * 0.999f), op, 0.0f));
  }
  EXPECT_NEAR(image::clipInput(ToneMap::Aces), 6.38f, 0.01f);
}

TEST(DefaultLook, ObjectOnGroundPlaneIsFramedAndExposed) {
  // The object on a ground plane under the default light, as prt render shows it by default.
  const Mesh mesh = builtinScene("builtin:sphere-plane");
  ASSERT_EQ(mesh.parts.size(), 2u);
  EXPECT_TRUE(render::isGroundPart(mesh, mesh.parts[0]));
  EXPECT_FALSE(render::isGroundPart(mesh, mesh.parts[1]));
  const auto occluder = makeEmbreeOccluder(mesh);
  BakeSettings s;
  s.mode = TransferMode::Shadowed;
  s.bands = 3;
  s.samples = 64;
  const Transfer t = bake(mesh, *occluder, s);
  const envmap::LoadedEnvironment sky = envmap::loadEnvironment("builtin:sky");
  const sh::RgbSh light = envmap::projectEnvironment(sky.env, 3);
  const int w = 640, h = 480;
  const render::Camera cam = render::frameMesh(mesh, w, h);
  const std::vector<Rgb> radiance =
      relight::relight(t, light, Material{}, {mesh.positions, mesh.normals, mesh.albedo}, cam.eye);
  const float stops =
      render::autoExposure(mesh, *occluder, radiance, cam, w, h, ToneMap::Aces);
  const std::vector<Rgb> px = render::modelPixels(mesh, *occluder, radiance, cam, w, h);
  const float clipped = image::clippedFraction(px, ToneMap::Aces, stops);
  EXPECT_LE(clipped, 0.02f);

  // The sphere's width in the frame: the extent of its projected vertices.
  const auto widthFraction = [&](const render::Camera& c) {
    const render::RayGenerator gen(c, w, h);
    float lo = 1e30f, hi = -1e30f;
    const MeshPart& sphere = mesh.parts[1];
    for (std::uint32_t v = sphere.firstVertex; v < sphere.firstVertex + sphere.vertexCount; ++v) {
      float px_ = 0, py = 0;
      if (!gen.project(mesh.positions[v], px_, py)) continue;
      lo = std::min(lo, px_), hi = std::max(hi, px_);
    }
    return (hi - lo) / float(w);
  };
  const Bounds all = computeBounds(mesh);
  const float before = widthFraction(render::frameSphere(all.centre(), all.radius(), w, h));
  const float after = widthFraction(cam);
  RecordProperty("clipped_fraction", std::to_string(clipped));
  RecordProperty("width_fraction_before", std::to_string(before));
  RecordProperty("width_fraction_after", std::to_string(after));
  std::printf("clipped %.4f at %.2f stops (%.4f at 0); sphere width %.3f (whole-mesh framing %.3f)\n",
              clipped, stops, image::clippedFraction(px, ToneMap::Aces, 0.0f), after, before);
  EXPECT_GE(after, 0.4f);
  EXPECT_LT(before, 0.4f);
}

TEST(DefaultLook, MeshWithoutGroundIsFramedWhole) {
  const Mesh mesh = builtinScene("builtin:sphere");
  EXPECT_FALSE(render::isGroundPart(mesh, mesh.parts[0]));
  EXPECT_EQ(render::framedVertices(mesh).size(), mesh.vertexCount());
  const Mesh plane = builtinScene("builtin:plane");  // only ground: the whole plane
  EXPECT_EQ(render::framedVertices(plane).size(), plane.vertexCount());
}

}  // namespace
}  // namespace prt
