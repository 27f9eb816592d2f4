// Packing rectangular charts into a lightmap's unit square (geometry/chart_packing.hpp): inside
// the square with the gutter around the border, at least the gutter apart, one scale, a fair
// share of the square used, the same layout every time, and bad input refused.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "common/error_text.hpp"
#include "prt/geometry/chart_packing.hpp"

namespace prt {
namespace {

using testing::errorOf;

void expectPacked(const std::vector<Vec2f>& sizes, const ChartPacking& p, float gutter) {
  ASSERT_EQ(p.offsets.size(), sizes.size());
  ASSERT_GT(p.scale, 0.0f);
  const float eps = 1e-6f;
  for (std::size_t a = 0; a < sizes.size(); ++a) {
    const Vec2f lo = p.offsets[a], hi{lo.x + p.scale * sizes[a].x, lo.y + p.scale * sizes[a].y};
    EXPECT_GE(lo.x, gutter - eps);
    EXPECT_GE(lo.y, gutter - eps);
    EXPECT_LE(hi.x, 1 - gutter + eps);
    EXPECT_LE(hi.y, 1 - gutter + eps);
    for (std::size_t b = a + 1; b < sizes.size(); ++b) {
      const Vec2f lo2 = p.offsets[b],
                  hi2{lo2.x + p.scale * sizes[b].x, lo2.y + p.scale * sizes[b].y};
      // Separated by at least the gutter along x or along y.
      const float gapX = std::max(lo2.x - hi.x, lo.x - hi2.x);
      const float gapY = std::max(lo2.y - hi.y, lo.y - hi2.y);
      EXPECT_GE(std::max(gapX, gapY), gutter - eps) << a << " and " << b;
    }
  }
}

TEST(ChartPacking, RandomChartsFitApartAtOneScale) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> side(0.2f, 2.0f);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<Vec2f> sizes;
    for (int k = 0; k < 5 + 4 * trial; ++k) sizes.push_back({side(rng), side(rng)});
    const float gutter = 4.0f / 512.0f;
    const ChartPacking p = packCharts(sizes, gutter);
    expectPacked(sizes, p, gutter);
    double area = 0;
    for (const Vec2f& s : sizes) area += double(s.x) * s.y;
    EXPECT_NEAR(p.usedArea, p.scale * p.scale * area, 1e-5);
    EXPECT_GT(p.usedArea, 0.35f) << "trial " << trial << ": shelf packing wastes too much";
    const ChartPacking again = packCharts(sizes, gutter);
    EXPECT_EQ(again.scale, p.scale);
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      EXPECT_EQ(again.offsets[k].x, p.offsets[k].x);
      EXPECT_EQ(again.offsets[k].y, p.offsets[k].y);
    }
  }
}

TEST(ChartPacking, EqualSquaresTileTheSquare) {
  // 16 unit squares with no gutter: a 4 × 4 grid, the whole square used.
  const std::vector<Vec2f> sizes(16, Vec2f{1, 1});
  const ChartPacking p = packCharts(sizes, 0.0f);
  expectPacked(sizes, p, 0.0f);
  EXPECT_NEAR(p.scale, 0.25f, 1e-4f);
  EXPECT_NEAR(p.usedArea, 1.0f, 1e-3f);
}

TEST(ChartPacking, BadInputIsRefused) {
  EXPECT_NE(errorOf([] {
              packCharts(std::vector<Vec2f>{{1, 1}}, 0.5f);
            }).find("gutter"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              packCharts(std::vector<Vec2f>{{1, 0}}, 0.01f);
            }).find("positive"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              packCharts(std::vector<Vec2f>{{std::nanf(""), 1}}, 0.01f);
            }).find("size"),
            std::string::npos);
  EXPECT_TRUE(packCharts(std::vector<Vec2f>{}, 0.01f).offsets.empty());
}

}  // namespace
}  // namespace prt
