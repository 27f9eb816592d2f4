// The lightmap domain's geometry (geometry/texel_sampling.hpp): every texel a triangle touches
// in UV space gets exactly one sample, at its centre when the triangle holds it and otherwise at
// the triangle's nearest point — checked against an independent supersampled rasterisation;
// sample points and normals interpolate the mesh; overlapping or out-of-range UV sets are refused
// by name; dilation fills exactly the rings it is asked for.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "common/error_text.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/lightmap_uvs.hpp"
#include "prt/geometry/texel_sampling.hpp"

namespace prt {
namespace {

/// A mesh of the given triangles in UV space, lifted to z = u + 2v (positions), normals +Z.
Mesh uvMesh(const std::vector<Vec2f>& uv, std::vector<std::array<std::uint32_t, 3>> tris) {
  Mesh m;
  m.source = "uv.obj";
  for (const Vec2f& t : uv) {
    m.positions.push_back({t.x, t.y, t.x + 2 * t.y});
    m.normals.push_back({0, 0, 1});
  }
  m.uvs = uv;
  m.triangles = std::move(tris);
  m.parts.push_back({"all", 0, std::uint32_t(uv.size()), 0, std::uint32_t(m.triangles.size())});
  return m;
}

using testing::errorOf;

TEST(TexelSampling, AFullQuadSamplesEveryCentreAndInterpolates) {
  const Mesh m = uvMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 1, 2}, {0, 2, 3}});
  EXPECT_NO_THROW(checkLightmapUvs(m, m.uvs, 8, 4, "TEXCOORD_1"));
  const TexelSamples s = sampleTexels(m, m.uvs, 8, 4);
  ASSERT_EQ(s.samples.size(), 32u);
  for (const TexelSample& t : s.samples) {
    EXPECT_TRUE(t.centreInside);
    const int x = int(t.texel % 8), y = int(t.texel / 8);
    const float u = (x + 0.5f) / 8, v = (y + 0.5f) / 4;
    const Vec3f p = samplePosition(m, t);
    EXPECT_NEAR(p.x, u, 1e-6);
    EXPECT_NEAR(p.y, v, 1e-6);
    EXPECT_NEAR(p.z, u + 2 * v, 1e-5);
    EXPECT_EQ(sampleNormal(m, t), Vec3f(0, 0, 1));
    EXPECT_EQ(s.sampleOfTexel[t.texel], &t - s.samples.data());
  }
}

// Independent check of conservative coverage on random small and thin triangles: a texel is
// sampled iff a 32 × 32 supersampling of its square finds a point inside the triangle (up to
// the grid's resolution at the boundary), and the sample point lies in the triangle and in (or
// at the edge of) the texel.
TEST(TexelSampling, CoverageIsConservativeAgainstSupersampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0.05f, 0.95f), D(-0.15f, 0.15f);
  constexpr int W = 24, H = 16;
  int thin = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec2f a{U(rng), U(rng)};
    Vec2f b{a.x + D(rng), a.y + D(rng)}, c{a.x + D(rng), a.y + D(rng)};
    if (trial % 3 == 0) c = {0.5f * (a.x + b.x) + 0.002f, 0.5f * (a.y + b.y) - 0.003f};  // a sliver
    const Mesh m = uvMesh({a, b, c}, {{0, 1, 2}});
    const TexelSamples s = sampleTexels(m, m.uvs, W, H);
    const auto inside = [&](double x, double y) {  // texel units
      const auto e = [](double px, double py, double qx, double qy, double rx, double ry) {
        return (qx - px) * (ry - py) - (qy - py) * (rx - px);
      };
      const double ax = a.x * W, ay = a.y * H, bx = b.x * W, by = b.y * H, cx = c.x * W,
                   cy = c.y * H;
      const double d0 = e(ax, ay, bx, by, x, y), d1 = e(bx, by, cx, cy, x, y),
                   d2 = e(cx, cy, ax, ay, x, y);
      return (d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0);
    };
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        bool hit = false;
        for (int j = 0; j < 32 && !hit; ++j)
          for (int i = 0; i < 32 && !hit; ++i) hit = inside(x + (i + 0.5) / 32, y + (j + 0.5) / 32);
        const std::size_t texel = std::size_t(y) * W + x;
        if (hit) {
          EXPECT_TRUE(s.covered(texel)) << "trial " << trial << " texel " << x << "," << y;
        }
        if (!s.covered(texel)) continue;
        const TexelSample& t = s.samples[s.sampleOfTexel[texel]];
        EXPECT_GE(std::min({t.barycentric.x, t.barycentric.y, t.barycentric.z}), 0.0f);
        EXPECT_NEAR(t.barycentric.x + t.barycentric.y + t.barycentric.z, 1.0f, 1e-5f);
        const Vec3f p = samplePosition(m, t);  // x, y are the UV
        EXPECT_GE(p.x * W, x - 1e-3);
        EXPECT_LE(p.x * W, x + 1 + 1e-3);
        EXPECT_GE(p.y * H, y - 1e-3);
        EXPECT_LE(p.y * H, y + 1 + 1e-3);
        thin += !t.centreInside;
      }
  }
  EXPECT_GT(thin, 20) << "the slivers must be sampled off-centre";
}

TEST(TexelSampling, AUvOfAnySizeSweepsOnlyTheLightmap) {
  // A corrupt file's UV of ~1e9 (one flipped exponent byte) once overflowed the texel bounds
  // and swept memory that is not the lightmap. Now it is clipped: the samples are the quad's
  // own, and the checks name the vertex.
  for (const float huge : {8e8f, -3e9f, 3.4e38f}) {
    const Mesh m = uvMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {huge, 0.5f}},
                          {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}});
    const TexelSamples s = sampleTexels(m, m.uvs, 16, 16);
    EXPECT_EQ(s.samples.size(), 256u) << huge;
    for (const TexelSample& t : s.samples) EXPECT_LT(t.texel, 256u);
    EXPECT_EQ(firstUvOutside(m.uvs), std::optional<std::size_t>(4)) << huge;
    EXPECT_NE(errorOf([&] { checkLightmapUvs(m, m.uvs, 16, 16, "the UVs"); })
                  .find("the UVs of vertex 4 is"),
              std::string::npos);
  }
}

TEST(TexelSampling, SharedEdgesGoToOneTriangleDeterministically) {
  // Two triangles meeting along the diagonal through texel centres of an 8 × 8 map.
  const Mesh m = uvMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 1, 2}, {0, 2, 3}});
  const TexelSamples s = sampleTexels(m, m.uvs, 8, 8);
  ASSERT_EQ(s.samples.size(), 64u);
  for (int k = 0; k < 8; ++k)  // the diagonal's centres lie in both: the lower index wins
    EXPECT_EQ(s.samples[s.sampleOfTexel[k * 8 + k]].triangle, 0u) << k;
  const TexelSamples again = sampleTexels(m, m.uvs, 8, 8);
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    EXPECT_EQ(s.samples[i].triangle, again.samples[i].triangle);
    EXPECT_EQ(s.samples[i].barycentric, again.samples[i].barycentric);
  }
}

// coverTexels and sampleTexelsAt answer for a few texels what sampleTexels answers for all: the
// same covered set (its count and k-th texel), and for any texels asked the same triangle,
// weights and centre flag bit for bit — on random triangles, slivers, triangles with corners on
// texel corners (edges along texel sides: touching is not covering), shared edges and partly
// covered texels of a mesh whose triangles overlap in UV space (the nearest wins, ties to the
// lower index).
TEST(TexelSampling, CoverageAndSamplesOfAFewTexelsAreTheWholeLightmaps) {
  constexpr int W = 37, H = 23;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(0.0f, 1.0f), D(-0.2f, 0.2f);
  std::uniform_int_distribution<int> X(0, W), Y(0, H), S(-6, 6);
  std::vector<Vec2f> uv;
  std::vector<std::array<std::uint32_t, 3>> tris;
  const auto clamp01 = [](Vec2f v) {
    return Vec2f{std::clamp(v.x, 0.0f, 1.0f), std::clamp(v.y, 0.0f, 1.0f)};
  };
  for (std::uint32_t t = 0; t < 90; ++t) {
    Vec2f a{U(rng), U(rng)};
    Vec2f b = clamp01({a.x + D(rng), a.y + D(rng)}), c = clamp01({a.x + D(rng), a.y + D(rng)});
    if (t % 3 == 1) {  // a sliver
      c = clamp01({0.5f * (a.x + b.x) + 0.002f, 0.5f * (a.y + b.y) - 0.003f});
    } else if (t % 3 == 2) {  // corners on texel corners
      const int x = X(rng), y = Y(rng);
      const auto corner = [&](int dx, int dy) {
        return Vec2f{float(std::clamp(x + dx, 0, W)) / W, float(std::clamp(y + dy, 0, H)) / H};
      };
      a = corner(0, 0), b = corner(S(rng), S(rng)), c = corner(S(rng), S(rng));
    }
    uv.insert(uv.end(), {a, b, c});
    tris.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  const Mesh m = uvMesh(uv, tris);
  const TexelSamples all = sampleTexels(m, m.uvs, W, H);
  const TexelCoverage covered = coverTexels(m, m.uvs, W, H);
  ASSERT_EQ(covered.count(), all.samples.size());
  for (std::size_t k = 0; k < all.samples.size(); ++k)
    ASSERT_EQ(covered.select(k), all.samples[k].texel) << k;
  for (std::size_t t = 0; t < std::size_t(W * H); ++t)
    ASSERT_EQ(covered.covered(t), all.covered(t)) << t;

  // Every texel, then random subsets (covered and not), asked alone.
  std::vector<std::uint32_t> every(W * H);
  for (std::uint32_t t = 0; t < every.size(); ++t) every[t] = t;
  std::vector<std::vector<std::uint32_t>> asks = {every, {0}, {std::uint32_t(W * H - 1)}};
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::uint32_t> some;
    for (std::uint32_t t = 0; t < every.size(); ++t)
      if (rng() % 16 == 0) some.push_back(t);
    asks.push_back(some);
  }
  int partly = 0;
  for (const auto& ask : asks) {
    const std::vector<TexelSample> few = sampleTexelsAt(m, m.uvs, W, H, ask);
    std::size_t j = 0;
    for (std::uint32_t t : ask) {
      if (!all.covered(t)) continue;
      ASSERT_LT(j, few.size());
      const TexelSample& a = all.samples[all.sampleOfTexel[t]];
      const TexelSample& b = few[j++];
      ASSERT_EQ(b.texel, t);
      EXPECT_EQ(b.triangle, a.triangle) << t;
      EXPECT_EQ(b.barycentric, a.barycentric) << t;
      EXPECT_EQ(b.centreInside, a.centreInside) << t;
      partly += !a.centreInside;
    }
    EXPECT_EQ(j, few.size()) << "a sample for a texel no triangle covers";
  }
  EXPECT_GT(partly, 50) << "the partly covered texels must be exercised";
}

TEST(TexelSampling, BadUvSetsAreRefusedByName) {
  // Overlap: a second quad on top of the first half.
  const Mesh over =
      uvMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.1f, 0.1f}, {0.6f, 0.1f}, {0.1f, 0.6f}},
             {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}});
  std::string e = errorOf([&] { checkLightmapUvs(over, over.uvs, 16, 16, "TEXCOORD_1"); });
  EXPECT_NE(e.find("uv.obj: TEXCOORD_1: triangles"), std::string::npos) << e;
  EXPECT_NE(e.find("overlap in UV space"), std::string::npos) << e;
  // A mirrored copy beside it does not overlap; sharing an edge is not an overlap.
  const Mesh beside = uvMesh({{0, 0}, {0.5f, 0}, {0.5f, 1}, {1, 0}}, {{0, 1, 2}, {3, 1, 2}});
  EXPECT_EQ(errorOf([&] { checkLightmapUvs(beside, beside.uvs, 16, 16, "TEXCOORD_1"); }), "");
  // Outside [0, 1]², non-finite, the wrong count, a bad size.
  Mesh out = uvMesh({{0, 0}, {1.5f, 0}, {0, 1}}, {{0, 1, 2}});
  e = errorOf([&] { checkLightmapUvs(out, out.uvs, 16, 16, "TEXCOORD_0"); });
  EXPECT_NE(e.find("uv.obj: TEXCOORD_0 of vertex 1 is (1.5"), std::string::npos) << e;
  out.uvs[1] = {std::nanf(""), 0};
  EXPECT_NE(errorOf([&] { checkLightmapUvs(out, out.uvs, 16, 16, "TEXCOORD_0"); }).find("vertex 1"),
            std::string::npos);
  const std::vector<Vec2f> two = {{0, 0}, {1, 0}};
  EXPECT_NE(errorOf([&] { sampleTexels(out, two, 16, 16); }).find("2 coordinates for 3 vertices"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { sampleTexels(beside, beside.uvs, 0, 16); }).find("outside 1..8192"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { sampleTexels(beside, beside.uvs, 16, 9000); }).find("16 x 9000"),
            std::string::npos);
}

// Dilation fills exactly the texels within `padding` (Chebyshev) of a chart, with means of
// their filled neighbours: a constant chart stays constant, and nothing farther is touched.
TEST(TexelSampling, DilationFillsExactlyThePaddingRings) {
  constexpr int W = 32, H = 24, P = 3;
  std::vector<std::uint8_t> filled(W * H, 0);
  std::vector<float> values(W * H * 2, -1.0f);
  const auto inChart = [](int x, int y) { return (x - 12) * (x - 12) + (y - 10) * (y - 10) <= 20; };
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (inChart(x, y)) {
        filled[y * W + x] = 1;
        values[(y * W + x) * 2] = 0.25f;
        values[(y * W + x) * 2 + 1] = 4.0f;
      }
  const std::vector<std::uint8_t> chart = filled;
  dilateTexels(values, 2, filled, W, H, P);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      int d = 1 << 20;  // Chebyshev distance to the chart
      for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
          if (chart[j * W + i]) d = std::min(d, std::max(std::abs(i - x), std::abs(j - y)));
      const std::size_t t = std::size_t(y) * W + x;
      EXPECT_EQ(filled[t] != 0, d <= P) << x << "," << y << " at " << d;
      if (d <= P) {
        EXPECT_FLOAT_EQ(values[t * 2], 0.25f);
        EXPECT_FLOAT_EQ(values[t * 2 + 1], 4.0f);
      } else {
        EXPECT_EQ(values[t * 2], -1.0f);
      }
    }
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

// The UV-set rule (geometry/lightmap_uvs.hpp): the lightmap set when it holds a lightmap, else
// the texture set, each refusal kept; both failing is one line naming the mesh and both reasons.
TEST(LightmapUvs, TheRulePicksAndSaysWhy) {
  Mesh m = uvMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 1, 2}, {0, 2, 3}});
  // The texture set only: picked under auto, refused under 1.
  LightmapUvChoice c = chooseLightmapUvs(m, UvSetOption::Auto, 32, 32);
  EXPECT_EQ(c.name, "texture UVs");
  ASSERT_EQ(c.refused.size(), 1u);
  EXPECT_EQ(c.refused[0], "lightmap UVs: the mesh has none");
  std::string e = testing::errorOf([&] { chooseLightmapUvs(m, UvSetOption::Lightmap, 32, 32); });
  EXPECT_EQ(
      e.rfind("uv.obj: no UV set can hold a 32 x 32 lightmap (lightmap UVs: the mesh has none)", 0),
      0u)
      << e;
  // A lightmap set wins; an overlapping one falls back to the texture set, saying why.
  m.lightmapUvs = {{0, 0}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}};
  EXPECT_EQ(chooseLightmapUvs(m, UvSetOption::Auto, 32, 32).name, "lightmap UVs");
  EXPECT_EQ(chooseLightmapUvs(m, UvSetOption::Texture, 32, 32).name, "texture UVs");
  m.lightmapUvs = {{0, 0}, {0.5f, 0}, {0.5f, 0.5f}, {0.5f, 0}};  // triangle 1 folds onto 0
  m.lightmapUvs[3] = {0.4f, 0.1f};
  c = chooseLightmapUvs(m, UvSetOption::Auto, 32, 32);
  EXPECT_EQ(c.name, "texture UVs");
  ASSERT_EQ(c.refused.size(), 1u);
  EXPECT_NE(c.refused[0].find("lightmap UVs: triangles 0 and 1 overlap"), std::string::npos)
      << c.refused[0];
  // Both bad: one line with both reasons.
  m.uvs[1] = {2, 0};
  e = testing::errorOf([&] { chooseLightmapUvs(m, UvSetOption::Auto, 32, 32); });
  EXPECT_NE(e.find("lightmap UVs: triangles 0 and 1 overlap"), std::string::npos) << e;
  EXPECT_NE(e.find("; texture UVs of vertex 1 is (2"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos);
  EXPECT_EQ(parseUvSetOption("1"), UvSetOption::Lightmap);
  EXPECT_NE(testing::errorOf([] { parseUvSetOption("2"); }).find("auto, 0 or 1"),
            std::string::npos);
}

}  // namespace
}  // namespace prt
