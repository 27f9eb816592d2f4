// The seam metric (render/lightmap_seams.hpp): a plane cut into two charts along x = 0 under a
// ball's shadow, baked per texel, agrees across its seam to a few percent (dilation and the
// fetch see the same light on both sides); the same lightmap read with one chart's UVs
// mirrored (its values no longer where its triangles are) does not; creases are not seams
// (the builtin Cornell box has none); a per-vertex transfer is refused.

#include <gtest/gtest.h>

#include <cstdio>

#include "common/error_text.hpp"
#include "common/two_chart_plane.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/lightmap_seams.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"

namespace prt {
namespace {

TEST(LightmapSeams, TheSeamOfASmoothSurfaceAgreesAndAMisplacedChartDoesNot) {
  Mesh m = testing::twoChartPlane();
  const auto occ = makeEmbreeOccluder(m);
  BakeSettings s;
  s.mode = TransferMode::Shadowed;
  s.bands = 2;
  s.samples = 512;
  const TexelBake b = bakeTexels(m, *occ, s, m.lightmapUvs, 64, 64, 2);
  const render::SeamStats good = render::measureSeams(m, b.transfer);
  EXPECT_EQ(good.edges, 1u) << "the x = 0 edge; the ball's seams have no lightmap";
  EXPECT_NEAR(good.length, 4.0, 1e-6);
  // The right chart's UVs mirrored in v: its values meet the other half of the shadow.
  for (std::uint32_t v = 4; v < 8; ++v) m.lightmapUvs[v].y = 1.0f - m.lightmapUvs[v].y;
  const render::SeamStats bad = render::measureSeams(m, b.transfer);
  std::printf("seam mismatch: %.4f (max %.4f); mirrored chart %.4f (max %.4f)\n", good.mismatch,
              good.maxMismatch, bad.mismatch, bad.maxMismatch);
  EXPECT_LT(good.mismatch, 0.05);
  EXPECT_GT(bad.mismatch, 4 * good.mismatch);
  EXPECT_GT(bad.mismatch, 0.05);

  // Under the sun (seamLights' second light): the white sky is the default's light; the metric
  // is relative (a brighter light, the same figure); the misplaced chart still shows.
  const std::vector<render::SeamLight> lights = render::seamLights(2);
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_STREQ(lights[1].name, "sun");
  EXPECT_DOUBLE_EQ(render::measureSeams(m, b.transfer, lights[0].light).mismatch, bad.mismatch);
  const render::SeamStats sun = render::measureSeams(m, b.transfer, lights[1].light);
  sh::RgbSh brighter = lights[1].light;
  for (Rgb& c : brighter.c) c = c * 8.0f;
  EXPECT_NEAR(render::measureSeams(m, b.transfer, brighter).mismatch, sun.mismatch,
              1e-6 * sun.mismatch);
  EXPECT_NE(sun.mismatch, bad.mismatch) << "the sun weighs the shadow, not the mean";
  for (std::uint32_t v = 4; v < 8; ++v) m.lightmapUvs[v].y = 1.0f - m.lightmapUvs[v].y;
  const render::SeamStats sunGood = render::measureSeams(m, b.transfer, lights[1].light);
  std::printf("under the sun: %.4f, mirrored chart %.4f\n", sunGood.mismatch, sun.mismatch);
  EXPECT_GT(sun.mismatch, 4 * sunGood.mismatch);
}

TEST(LightmapSeams, CreasesAreNotSeamsAndVerticesAreRefused) {
  const Mesh box = builtinScene("builtin:cornell?grid=4");
  const auto occ = makeEmbreeOccluder(box);
  BakeSettings s;
  s.mode = TransferMode::Shadowed;
  s.bands = 2;
  s.samples = 16;
  const TexelBake b = bakeTexels(box, *occ, s, box.lightmapUvs, 32, 32, 2);
  EXPECT_EQ(render::measureSeams(box, b.transfer).edges, 0u);
  const Transfer v = bake(box, *occ, s);
  EXPECT_NE(testing::errorOf([&] { render::measureSeams(box, v); }).find("per-texel"),
            std::string::npos);
}

}  // namespace
}  // namespace prt
