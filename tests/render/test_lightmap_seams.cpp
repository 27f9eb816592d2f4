// The seam metric (render/lightmap_seams.hpp): a plane cut into two charts along x = 0 under a
// ball's shadow, baked per texel, agrees across its seam to a few percent (dilation and the
// fetch see the same light on both sides); the same lightmap read with one chart's UVs
// mirrored (its values no longer where its triangles are) does not; creases are not seams
// (the builtin Cornell box has none); a per-vertex transfer is refused.

#include <gtest/gtest.h>

#include <cstdio>

#include "common/error_text.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/lightmap_seams.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"

namespace prt {
namespace {

/// Two quads x ∈ [−2, 0] and [0, 2], z ∈ [−2, 2] facing +Y, each its own chart (u ∈ [0.05,
/// 0.45] and [0.55, 0.95]); a ball of radius 0.6 at height 1 above the seam at z = 1 (its shadow
/// not symmetric along the seam), without lightmap
/// area.
Mesh twoChartPlane() {
  Mesh m;
  m.source = "two-chart plane";
  for (int side = 0; side < 2; ++side) {
    const float x0 = side == 0 ? -2.0f : 0.0f, u0 = side == 0 ? 0.05f : 0.55f;
    const std::uint32_t base = std::uint32_t(m.positions.size());
    for (const auto& [dx, z] :
         std::vector<std::pair<float, float>>{{0, -2}, {2, -2}, {2, 2}, {0, 2}}) {
      m.positions.push_back({x0 + dx, 0, z});
      m.normals.push_back({0, 1, 0});
      m.lightmapUvs.push_back({u0 + 0.2f * dx, 0.05f + 0.9f * (z + 2) / 4});
    }
    m.triangles.push_back({base + 0, base + 3, base + 2});
    m.triangles.push_back({base + 0, base + 2, base + 1});
  }
  const Mesh s = builtinScene("builtin:sphere?subdiv=3&r=0.6");
  const std::uint32_t base = std::uint32_t(m.positions.size());
  for (std::size_t v = 0; v < s.vertexCount(); ++v) {
    m.positions.push_back(s.positions[v] + Vec3f(0, 1, 1));
    m.normals.push_back(s.normals[v]);
    m.lightmapUvs.push_back({0, 0});
  }
  for (const auto& t : s.triangles) m.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  return m;
}

TEST(LightmapSeams, TheSeamOfASmoothSurfaceAgreesAndAMisplacedChartDoesNot) {
  Mesh m = twoChartPlane();
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
