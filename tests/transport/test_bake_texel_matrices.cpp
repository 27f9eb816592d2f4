// Glossy transfer matrices per texel (transport/bake_texels.hpp with TransferLayout::Matrix,
// issue 18) against answers they cannot fake:
//   * a plane under unshadowed transfer holds in every texel, gutter included, the per-vertex
//     matrix of the plane: the hemisphere product H(n), whose M_00 is ∫_{n·ω>0} Y00² dω = 1/2;
//   * shadowed matrices of a two-triangle plane under a ball at its texels equal the per-vertex
//     matrices of the same geometry tessellated with a vertex at every texel centre — the same
//     point, normal and seed index, so the same kernel gives the same row — and the shadow is
//     there;
//   * inter-reflected matrices of a coarse Cornell box, with diffuse bounce surfaces and with
//     glossy ones (the bounces then read the previous order's matrices through the lightmap),
//     agree wall by wall with the per-vertex bake of a fine box;
//   * the same values for any thread count and for any texel range; what would not fit in
//     memory refused before any work, with the figure.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "common/error_text.hpp"
#include "common/texel_planes.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"
#include "prt/transport/texel_validity.hpp"

namespace prt {
namespace {

BakeSettings matrixSettings(TransferMode mode, int bands, int samples) {
  BakeSettings s;
  s.mode = mode;
  s.layout = TransferLayout::Matrix;
  s.bands = bands;
  s.samples = samples;
  s.seed = 91;
  return s;
}

TEST(BakeTexelMatrices, PlaneUnshadowedIsTheHemisphereProductInEveryTexel) {
  const Mesh m = testing::coarsePlane(false);
  const auto occ = makeEmbreeOccluder(m);
  constexpr int N = 16;
  const BakeSettings s = matrixSettings(TransferMode::Unshadowed, 3, 64);
  const TexelBake b = bakeTexels(m, *occ, s, m.lightmapUvs, N, N, 2);
  const Transfer& t = b.transfer;
  EXPECT_EQ(t.domain(), TransferDomain::Texels);
  EXPECT_EQ(t.layout(), TransferLayout::Matrix);
  ASSERT_EQ(t.rowCount(), std::size_t(N * N));
  ASSERT_EQ(t.stride(), std::size_t(81));
  const Transfer vertex = bake(m, *occ, s);
  EXPECT_NEAR(vertex.row(0)[0], 0.5f, 1e-6f) << "H_00 = ∫ over the hemisphere of Y00² = 1/2";
  for (std::size_t r = 0; r < t.rowCount(); ++r)
    for (std::size_t i = 0; i < 81; ++i)
      ASSERT_NEAR(t.row(r)[i], vertex.row(0)[i], 1e-6f) << "texel " << r << " entry " << i;
}

TEST(BakeTexelMatrices, ShadowedTexelsEqualVerticesAtTheirSamplePoints) {
  constexpr int N = 16;
  const Mesh coarse = testing::coarsePlane(true);
  const Mesh fine = testing::texelCentrePlane(coarse, N);
  const BakeSettings s = matrixSettings(TransferMode::Shadowed, 3, 256);
  const auto occCoarse = makeEmbreeOccluder(coarse), occFine = makeEmbreeOccluder(fine);
  BakeStats st;
  const TexelBake texels = bakeTexels(coarse, *occCoarse, s, coarse.lightmapUvs, N, N, 2, &st);
  EXPECT_GT(st.rays, 0u);
  EXPECT_GT(st.stdErrT0Max, 0.0);
  const Transfer same = bake(fine, *occFine, s);
  int shadowed = 0;
  for (int r = 0; r < N * N; ++r) {
    for (std::size_t i = 0; i < 81; ++i)
      ASSERT_NEAR(texels.transfer.row(r)[i], same.row(r)[i], 1e-5f) << r << " entry " << i;
    shadowed += texels.transfer.row(r)[0] < 0.45f;
  }
  EXPECT_GT(shadowed, 10) << "the ball's shadow must fall on the plane";
}

/// Each wall's mean M_00 per channel over its area, per texel (valid texels) and per vertex
/// (area-weighted, triangles with a vertex inside geometry left out), as in test_bake_texels.
struct WallMeans {
  std::vector<std::array<double, 3>> texels, vertices;
};
WallMeans wallMeans(const Mesh& box, const TexelBake& t, const Mesh& fine, const Occluder& fineOcc,
                    const Transfer& vertices) {
  WallMeans w;
  std::vector<std::uint8_t> invalid(t.samples.texelCount(), 0);
  for (const std::uint32_t x : t.invalid) invalid[x] = 1;
  const std::vector<std::uint8_t> inside =
      insideGeometry(fine, fineOcc, fine.positions, fine.normals);
  const int ct = t.transfer.channels(), cv = vertices.channels();
  for (std::size_t pi = 0; pi < box.parts.size(); ++pi) {
    const MeshPart& part = box.parts[pi];
    const MeshPart& fp = fine.parts[pi];
    std::array<double, 3> sumT{}, sumV{};
    std::size_t nT = 0;
    for (const TexelSample& ts : t.samples.samples)
      if (ts.triangle >= part.firstTriangle &&
          ts.triangle < part.firstTriangle + part.triangleCount && !invalid[ts.texel]) {
        for (int c = 0; c < 3; ++c) sumT[c] += t.transfer.row(ts.texel)[ct == 1 ? 0 : c];
        ++nT;
      }
    double area = 0;
    for (std::uint32_t f = fp.firstTriangle; f < fp.firstTriangle + fp.triangleCount; ++f) {
      const auto& tri = fine.triangles[f];
      if (inside[tri[0]] || inside[tri[1]] || inside[tri[2]]) continue;
      const double a = 0.5 * length(Vec3d(cross(fine.positions[tri[1]] - fine.positions[tri[0]],
                                                fine.positions[tri[2]] - fine.positions[tri[0]])));
      for (std::uint32_t v : tri)
        for (int c = 0; c < 3; ++c) sumV[c] += a / 3 * vertices.row(v)[cv == 1 ? 0 : c];
      area += a;
    }
    EXPECT_GT(nT, 50u) << part.name;
    std::array<double, 3> mt{}, mv{};
    for (int c = 0; c < 3; ++c) mt[c] = sumT[c] / double(nT), mv[c] = sumV[c] / area;
    w.texels.push_back(mt);
    w.vertices.push_back(mv);
  }
  return w;
}

TEST(BakeTexelMatrices, InterreflectedCornellAgreesWithTheVertexBakeWallByWall) {
  const Mesh box = builtinScene("builtin:cornell?grid=4");
  const Mesh fine = builtinScene("builtin:cornell?grid=64");
  const auto occ = makeEmbreeOccluder(box), fineOcc = makeEmbreeOccluder(fine);
  ASSERT_EQ(box.parts.size(), fine.parts.size());
  for (const char* spec : {"lambert", "phong?ks=0.3&exponent=4"}) {
    SCOPED_TRACE(spec);
    BakeSettings s = matrixSettings(TransferMode::Interreflected, 2, 256);
    s.bounces = 1;
    s.material = parseMaterial(spec);
    EXPECT_EQ(s.glossyBounces(TransferLayout::Matrix), std::string(spec) != "lambert");
    BakeStats st;
    const TexelBake t = bakeTexels(box, *occ, s, box.lightmapUvs, 128, 128, 2, &st);
    ASSERT_EQ(t.transfer.channels(), 3);  // the red and green walls colour the bounce
    EXPECT_EQ(st.secondsBounce.size(), 1u);
    const Transfer vertices = bake(fine, *fineOcc, s);
    // Without the bounce, for the bounce's share of each wall's light.
    BakeSettings direct = s;
    direct.mode = TransferMode::Shadowed;
    direct.bounces = 0;
    const TexelBake d = bakeTexels(box, *occ, direct, box.lightmapUvs, 128, 128, 2);
    const WallMeans w = wallMeans(box, t, fine, *fineOcc, vertices);
    const WallMeans wd = wallMeans(box, d, fine, *fineOcc, vertices);
    double worst = 0, bounced = 0;
    for (std::size_t pi = 0; pi < box.parts.size(); ++pi)
      for (int c = 0; c < 3; ++c) {
        const double mt = w.texels[pi][c], mv = w.vertices[pi][c];
        // (measured 3.3% at worst; against a 32 × 32 fine box 6%: the vertices' own
        // discretisation along the walls' edges, which M_00's grazing directions weigh more
        // than the cosine does)
        EXPECT_NEAR(mt, mv, 0.045 * std::abs(mv)) << box.parts[pi].name << " channel " << c;
        worst = std::max(worst, std::abs(mt / mv - 1));
        bounced = std::max(bounced, mt / wd.texels[pi][c] - 1);
      }
    // The bounce must add light (a lookup that read nothing would leave the direct part).
    EXPECT_GT(bounced, 0.05);
    std::cout << spec << ": per-texel vs per-vertex inter-reflected matrices, wall means of M_00:"
              << " worst " << 100 * worst << "%, the bounce adds up to " << 100 * bounced << "%\n";
  }
}

TEST(BakeTexelMatrices, TheSameForAnyThreadCountAndAnyTexelRange) {
  const Mesh box = builtinScene("builtin:cornell?grid=4");
  const auto occ = makeEmbreeOccluder(box);
  BakeSettings s = matrixSettings(TransferMode::Interreflected, 2, 32);
  s.bounces = 2;
  s.material = parseMaterial("phong?ks=0.2&exponent=6");
  const int W = 24, H = 24;
  const TexelBake many = bakeTexels(box, *occ, s, box.lightmapUvs, W, H, 2);
  TexelBake one;
  {
    const ThreadLimit limit(1);
    one = bakeTexels(box, *occ, s, box.lightmapUvs, W, H, 2);
  }
  ASSERT_EQ(one.transfer.values().size(), many.transfer.values().size());
  for (std::size_t i = 0; i < one.transfer.values().size(); ++i)
    ASSERT_EQ(one.transfer.values()[i], many.transfer.values()[i]) << i;
  const std::size_t stride = many.transfer.stride();
  for (const RowRange range : {RowRange{0, 100}, RowRange{100, 250}, RowRange{350, 0}}) {
    BakeSettings r = s;
    r.rows = range;
    const TexelBake part = bakeTexels(box, *occ, r, box.lightmapUvs, W, H, 2);
    const RowRange got = part.transfer.rows();
    ASSERT_EQ(got.first, range.first);
    ASSERT_EQ(part.transfer.values().size(), got.count * stride);
    for (std::size_t i = 0; i < got.count * stride; ++i)
      ASSERT_EQ(part.transfer.values()[i], many.transfer.values()[got.first * stride + i]) << i;
  }
  // A shadowed range samples only what it needs, with the same rows.
  BakeSettings sh = matrixSettings(TransferMode::Shadowed, 2, 32);
  const TexelBake whole = bakeTexels(box, *occ, sh, box.lightmapUvs, W, H, 2);
  sh.rows = {200, 100};
  BakeStats st, wst;
  const TexelBake part = bakeTexels(box, *occ, sh, box.lightmapUvs, W, H, 2, &st);
  for (std::size_t i = 0; i < 100 * whole.transfer.stride(); ++i)
    ASSERT_EQ(part.transfer.values()[i],
              whole.transfer.values()[200 * whole.transfer.stride() + i]);
}

TEST(BakeTexelMatrices, WhatWouldNotFitInMemoryIsRefusedWithTheFigure) {
  const Mesh box = builtinScene("builtin:cornell?grid=2");
  const auto occ = makeEmbreeOccluder(box);
  const BakeSettings s = matrixSettings(TransferMode::Shadowed, 8, 16);
  // 8 bands: 64² floats = 16.4 KB per texel; 8192² texels = 1.1 TB.
  const TexelBakeFootprint f = texelBakeFootprint(box, s, 8192, 8192);
  EXPECT_EQ(f.bytesPerRow, std::size_t(64 * 64 * 4));
  EXPECT_EQ(f.transferBytes, f.bytesPerRow * 8192 * 8192);
  const std::string e =
      testing::errorOf([&] { bakeTexels(box, *occ, s, box.lightmapUvs, 8192, 8192, 2); });
  EXPECT_NE(e.find("matrix transfer of a 8192 x 8192 lightmap at 8 bands needs 16.4 KB per texel"),
            std::string::npos)
      << e;
  // The figure: 1024² texels of 5-band matrices are 2.6 GB.
  const TexelBakeFootprint five =
      texelBakeFootprint(box, matrixSettings(TransferMode::Shadowed, 5, 16), 1024, 1024);
  EXPECT_NEAR(double(five.transferBytes), 2.62e9, 0.01e9);
}

}  // namespace
}  // namespace prt
