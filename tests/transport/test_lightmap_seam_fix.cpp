// The least-squares seam fix (transport/lightmap_seam_fix.hpp, Sylvan 2015) against what it
// must do and must not:
//   * on a plane cut into two charts of different density and orientation under a ball's
//     shadow, the seam metric (render/lightmap_seams.hpp, an independent measure at other
//     points along the seam) falls several-fold, for scalar and RGB rows alike;
//   * a constant field (the unshadowed plane: every texel the analytic value) is left as it is,
//     since it already agrees across the seam — the data term alone would pull it nowhere;
//   * texels no seam fetch reads are untouched, bit for bit; a mesh without seams (the Cornell
//     box: creases only) is returned unchanged;
//   * the fix is the same for any thread count; partial, compressed and per-vertex transfers
//     are refused by name.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "common/error_text.hpp"
#include "common/two_chart_plane.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/geometry/uv_seams.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/lightmap_seams.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"
#include "prt/transport/lightmap_seam_fix.hpp"

namespace prt {
namespace {

BakeSettings settings(TransferMode mode, int samples) {
  BakeSettings s;
  s.mode = mode;
  s.bands = 3;
  s.samples = samples;
  s.seed = 5;
  return s;
}

TEST(LightmapSeamFix, TheSeamMismatchFallsWhereTheChartsDisagree) {
  const int RES = 16;  // coarse: the shadow changes within a texel, so the grids disagree
  const Mesh m = testing::twoChartPlane(/*rotatedRightChart=*/true);
  const auto occ = makeEmbreeOccluder(m);
  const TexelBake b =
      bakeTexels(m, *occ, settings(TransferMode::Shadowed, 1024), m.lightmapUvs, RES, RES, 2);
  const render::SeamStats before = render::measureSeams(m, b.transfer);
  SeamFixStats st;
  const Transfer fixed = fixLightmapSeams(m, b.transfer, &st);
  const render::SeamStats after = render::measureSeams(m, fixed);
  std::printf("seam mismatch %.4f -> %.4f (max %.4f -> %.4f); %zu samples, %zu texels\n",
              before.mismatch, after.mismatch, before.maxMismatch, after.maxMismatch, st.samples,
              st.texels);
  EXPECT_EQ(st.edges, 1u);
  EXPECT_TRUE(fixed.shape().lightmap.seamsFixed);
  EXPECT_FALSE(b.transfer.shape().lightmap.seamsFixed);
  EXPECT_GT(before.mismatch, 0.005) << "the fixture must have a seam worth fixing";
  EXPECT_LT(after.mismatch, before.mismatch / 4);
  EXPECT_LT(after.maxMismatch, before.maxMismatch / 2);

  // Only the texels the seam fetches read change; the rest are the bake's, bit for bit.
  std::vector<std::uint8_t> tapped(fixed.rowCount(), 0);
  for (const UvSeamEdge& e : findUvSeams(m, m.lightmapUvs))
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i <= 64; ++i) {
        const float s = float(i) / 64;
        const Vec2f p = m.lightmapUvs[e.side[side][0]], q = m.lightmapUvs[e.side[side][1]];
        const TexelTaps taps = bilinearTaps({p.x + (q.x - p.x) * s, p.y + (q.y - p.y) * s}, RES, RES);
        for (std::size_t t : taps.texel) tapped[t] = 1;
      }
  std::size_t changed = 0, changedUntapped = 0;
  for (std::size_t t = 0; t < fixed.rowCount(); ++t)
    for (std::size_t k = 0; k < fixed.stride(); ++k)
      if (fixed.row(t)[k] != b.transfer.row(t)[k]) {
        ++changed;
        if (!tapped[t]) ++changedUntapped;
      }
  EXPECT_GT(changed, 0u);
  EXPECT_EQ(changedUntapped, 0u);

  // The same for any thread count (a sequential solve over texels in order).
  {
    ThreadLimit one(1);
    const Transfer again = fixLightmapSeams(m, b.transfer);
    for (std::size_t i = 0; i < fixed.values().size(); ++i)
      ASSERT_EQ(again.values()[i], fixed.values()[i]) << "value " << i;
  }
}

TEST(LightmapSeamFix, RgbRowsOfAnInterreflectedBakeAreFixedToo) {
  Mesh m = testing::twoChartPlane(true);
  // A red ball over a white plane: the bounce is RGB.
  m.albedo.assign(m.vertexCount(), Rgb(0.8f, 0.2f, 0.1f));
  for (std::size_t v = 0; v < 8; ++v) m.albedo[v] = Rgb(0.8f);
  const auto occ = makeEmbreeOccluder(m);
  BakeSettings s = settings(TransferMode::Interreflected, 256);
  s.bounces = 1;
  const TexelBake b = bakeTexels(m, *occ, s, m.lightmapUvs, 16, 16, 2);
  ASSERT_EQ(b.transfer.channels(), 3);
  const double before = render::measureSeams(m, b.transfer).mismatch;
  const double after = render::measureSeams(m, fixLightmapSeams(m, b.transfer)).mismatch;
  std::printf("RGB seam mismatch %.4f -> %.4f\n", before, after);
  EXPECT_LT(after, before / 3);
}

TEST(LightmapSeamFix, AFieldThatAlreadyAgreesIsLeftAsItIs) {
  Mesh m = testing::twoChartPlane(true);
  m.positions.resize(8), m.normals.resize(8), m.lightmapUvs.resize(8), m.triangles.resize(4);
  const auto occ = makeEmbreeOccluder(m);
  // Unshadowed transfer of a plane is the same analytic vector in every texel, gutter included.
  const TexelBake b =
      bakeTexels(m, *occ, settings(TransferMode::Unshadowed, 64), m.lightmapUvs, 32, 32, 2);
  SeamFixStats st;
  const Transfer fixed = fixLightmapSeams(m, b.transfer, &st);
  EXPECT_GT(st.texels, 0u);
  double worst = 0;
  for (std::size_t i = 0; i < fixed.values().size(); ++i)
    worst = std::max(worst, double(std::abs(fixed.values()[i] - b.transfer.values()[i])));
  EXPECT_LT(worst, 1e-5);
}

TEST(LightmapSeamFix, AMeshWithoutSeamsIsUnchangedAndBadTransfersAreRefused) {
  const Mesh box = builtinScene("builtin:cornell?grid=4");
  const auto occ = makeEmbreeOccluder(box);
  const BakeSettings s = settings(TransferMode::Shadowed, 16);
  const TexelBake b = bakeTexels(box, *occ, s, box.lightmapUvs, 32, 32, 2);
  SeamFixStats st;
  const Transfer fixed = fixLightmapSeams(box, b.transfer, &st);
  EXPECT_EQ(st.edges, 0u);
  EXPECT_EQ(st.texels, 0u);
  for (std::size_t i = 0; i < fixed.values().size(); ++i)
    ASSERT_EQ(fixed.values()[i], b.transfer.values()[i]);

  const auto refusal = [&](const Transfer& t) {
    return testing::errorOf([&] { fixLightmapSeams(box, t); });
  };
  EXPECT_NE(refusal(bake(box, *occ, s)).find("per-texel"), std::string::npos);
  BakeSettings part = s;
  part.rows = {0, 100};
  EXPECT_NE(refusal(bakeTexels(box, *occ, part, box.lightmapUvs, 32, 32, 2).transfer)
                .find("whole lightmap"),
            std::string::npos);
  CpcaOptions o;
  o.clusters = 2;
  o.basisCount = 1;
  EXPECT_NE(refusal(compressCpca(b.transfer, o)).find("before compressing"), std::string::npos);
  // Buffers that do not match the lightmap.
  std::vector<float> values(10);
  std::vector<std::uint8_t> free(10);
  EXPECT_NE(testing::errorOf([&] {
              fixLightmapSeams(box, box.lightmapUvs, 32, 32, values, 1, free);
            }).find("do not match"),
            std::string::npos);
}

}  // namespace
}  // namespace prt
