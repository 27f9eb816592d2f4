// Packing charts by their rasterised shapes (unwrap/atlas_packing.hpp): small charts go into the
// notches of L-shaped ones, which bounding rectangles leave empty; whatever the turns and the
// scale, no texel of one chart comes within the padding of another's or of the border.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/geometry/chart_packing.hpp"
#include "prt/unwrap/atlas_packing.hpp"

namespace prt {
namespace {

using Tri = std::array<std::uint32_t, 3>;

/// An L of three unit squares in the box [0, 2]² (the upper right square missing), six
/// counter-clockwise triangles.
struct LChart {
  std::vector<Uv2> uv = {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}, {0, 2}, {1, 2}};
  std::vector<Tri> triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {3, 4, 7}, {3, 7, 6}};
  ChartShape shape() const { return {uv, triangles, 2.0, 2.0}; }
};

/// Every texel a chart's triangle overlaps with area, by its packed corners (sampled densely:
/// the triangles are axis-aligned halves of squares), marked with the chart's index.
std::vector<int> owners(const std::vector<ChartShape>& shapes, const AtlasPacking& p, int side) {
  std::vector<int> owner(std::size_t(side) * side, -1);
  for (std::size_t c = 0; c < shapes.size(); ++c)
    for (const Tri& t : shapes[c].triangles) {
      const Uv2 a = p.texelPosition(shapes, c, shapes[c].uv[t[0]]);
      const Uv2 b = p.texelPosition(shapes, c, shapes[c].uv[t[1]]);
      const Uv2 d = p.texelPosition(shapes, c, shapes[c].uv[t[2]]);
      constexpr int n = 64;  // points strictly inside the triangle
      for (int i = 1; i < n; ++i)
        for (int j = 1; i + j < n; ++j) {
          const double u = double(i) / n, v = double(j) / n, w = 1 - u - v;
          const double x = w * a[0] + u * b[0] + v * d[0], y = w * a[1] + u * b[1] + v * d[1];
          const int tx = int(std::floor(x)), ty = int(std::floor(y));
          EXPECT_TRUE(tx >= 0 && ty >= 0 && tx < side && ty < side) << x << ", " << y;
          if (tx < 0 || ty < 0 || tx >= side || ty >= side) continue;
          int& o = owner[std::size_t(ty) * side + tx];
          EXPECT_TRUE(o < 0 || o == int(c)) << "texel " << tx << ", " << ty << " in two charts";
          o = int(c);
        }
    }
  return owner;
}

/// No two charts' texels within `pad` texels of each other (in x and y), none within `pad` of
/// the border.
void expectApart(const std::vector<int>& owner, int side, int pad) {
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int o = owner[std::size_t(y) * side + x];
      if (o < 0) continue;
      ASSERT_TRUE(x >= pad && y >= pad && x < side - pad && y < side - pad)
          << "texel " << x << ", " << y << " within the border's padding";
      for (int dy = -pad; dy <= pad; ++dy)
        for (int dx = -pad; dx <= pad; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= side || v >= side) continue;
          const int q = owner[std::size_t(v) * side + u];
          ASSERT_TRUE(q < 0 || q == o) << "charts " << o << " and " << q << " closer than " << pad;
        }
    }
}

TEST(AtlasPacking, SmallChartsFillTheGapsOfLargeOnesWhereRectanglesCannot) {
  // Eight Ls (2 × 2 boxes with a 1 × 1 notch) and eight squares a little smaller than the
  // notch: by their boxes the squares need room of their own; by shape each fits in an L's notch.
  const LChart l;
  const std::vector<Uv2> squareUv = {{0, 0}, {0.8, 0}, {0.8, 0.8}, {0, 0.8}};
  const std::vector<Tri> squareTriangles = {{0, 1, 2}, {0, 2, 3}};
  std::vector<ChartShape> shapes(8, l.shape());
  shapes.resize(16, ChartShape{squareUv, squareTriangles, 0.8, 0.8});
  std::vector<Vec2f> boxes(8, Vec2f{2, 2});
  boxes.resize(16, Vec2f{0.8f, 0.8f});
  for (const int pad : {0, 2}) {
    SCOPED_TRACE(pad);
    const int side = 128;
    const ChartPacking rect = packCharts(boxes, float((pad + 1 + 1e-3) / side));  // unwrap.cpp's
    const double rectK = double(rect.scale) * side;
    AtlasPacking p;
    ASSERT_TRUE(packChartShapes(shapes, side, pad, rectK, p));
    // The squares' 8 · 0.64 of the boxes' 37.1 units² go: the scale may grow by up to
    // √(37.1 / 32) ≈ 1.08 less the texels lost to conservative rasterisation.
    EXPECT_GT(p.texelsPerUnit, 1.04 * rectK) << "rectangles " << rectK;
    EXPECT_LE(p.rowsUsed, side);
    // Some part of a chart (an L's square, a square) lies inside another L's box, in its notch,
    // where rectangles leave nothing.
    int nested = 0;
    for (std::size_t s = 0; s < 16; ++s)
      for (std::size_t c = 0; c < 8; ++c) {
        if (s == c) continue;
        const Uv2 lo = p.texelPosition(shapes, c, {0, 0}), hi = p.texelPosition(shapes, c, {2, 2});
        const std::vector<Uv2> parts = s < 8 ? std::vector<Uv2>{{0.5, 0.5}, {1.5, 0.5}, {0.5, 1.5}}
                                             : std::vector<Uv2>{{0.4, 0.4}};
        for (const Uv2& part : parts) {
          const Uv2 q = p.texelPosition(shapes, s, part);
          nested += q[0] > std::min(lo[0], hi[0]) && q[0] < std::max(lo[0], hi[0]) &&
                    q[1] > std::min(lo[1], hi[1]) && q[1] < std::max(lo[1], hi[1]);
        }
      }
    EXPECT_GT(nested, 0);
    expectApart(owners(shapes, p, side), side, pad);
  }
}

TEST(AtlasPacking, LargeAtlasesPackWholeCellsAndKeepThePadding) {
  const LChart l;
  const std::vector<ChartShape> shapes(24, l.shape());
  const int side = 3000, pad = 2;  // cells of three texels: a gutter of one cell
  AtlasPacking p;
  ASSERT_TRUE(packChartShapes(shapes, side, pad, 100, p));
  EXPECT_EQ(p.cell, 3);
  expectApart(owners(shapes, p, side), side, pad);
}

TEST(AtlasPacking, SaysWhenNothingFits) {
  const LChart l;
  const std::vector<ChartShape> shapes(4, l.shape());
  AtlasPacking p;
  // At 20 texels a unit four 40-texel Ls cannot share 32 × 32 texels.
  EXPECT_FALSE(packChartShapes(shapes, 32, 2, 20, p));
  EXPECT_TRUE(p.charts.empty());
}

}  // namespace
}  // namespace prt
