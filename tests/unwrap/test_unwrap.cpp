// prt unwrap's atlas (issue 18): least squares conformal maps against the geometry they must
// reproduce, the layout checks, chart growing, and whole atlases checked by rasterising them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <map>
#include <random>
#include <set>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/unwrap/chart_layout.hpp"
#include "prt/unwrap/charts.hpp"
#include "prt/unwrap/lscm.hpp"
#include "prt/unwrap/unwrap.hpp"

namespace prt {
namespace {

using Tri = std::array<std::uint32_t, 3>;

/// An n × n grid of quads over [0,1]² (jittered inside), mapped by f(u, v) → 3D.
template <class F>
Mesh gridMesh(int n, F f, double jitter = 0.0, unsigned seed = 1) {
  Mesh m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-jitter, jitter);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      double u = double(i) / n, v = double(j) / n;
      if (i > 0 && i < n) u += d(rng) / n;
      if (j > 0 && j < n) v += d(rng) / n;
      m.positions.push_back(Vec3f(f(u, v)));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), e = c + 1;
      m.triangles.push_back({a, b, e});
      m.triangles.push_back({a, e, c});
    }
  m.normals.assign(m.positions.size(), Vec3f(0, 0, 1));
  m.source = "grid";
  return m;
}

/// A closed cylinder (radius 1, height 2) with capped ends: fan caps around centre vertices.
Mesh closedCylinder(int around, int rows) {
  Mesh m;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2 * M_PI * i / around;
      m.positions.push_back(
          Vec3f(float(std::cos(a)), float(-1 + 2.0 * j / rows), float(std::sin(a))));
    }
  const auto at = [&](int i, int j) { return std::uint32_t(j * around + (i % around)); };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < around; ++i) {
      // Outward-facing: counter-clockwise seen from outside.
      m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  const std::uint32_t bottom = std::uint32_t(m.positions.size());
  m.positions.push_back(Vec3f(0, -1, 0));
  const std::uint32_t top = bottom + 1;
  m.positions.push_back(Vec3f(0, 1, 0));
  for (int i = 0; i < around; ++i) {
    m.triangles.push_back({bottom, at(i, 0), at(i + 1, 0)});
    m.triangles.push_back({top, at(i + 1, rows), at(i, rows)});
  }
  m.normals.assign(m.positions.size(), Vec3f(0, 1, 0));
  m.source = "cylinder";
  return m;
}

/// A bumpy closed surface: the builtin sphere with each vertex moved radially by a fixed
/// pseudo-random amount (a scanned-looking closed mesh, like the bunny, in a few thousand
/// triangles).
Mesh bumpySphere() {
  Mesh m = loadMesh("builtin:sphere");
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> d(0.85f, 1.15f);
  const Vec3f c = computeBounds(m).centre();
  for (Vec3f& p : m.positions) p = c + (p - c) * d(rng);
  m.source = "bumpy sphere";
  return m;
}

double signedArea2(Vec2f a, Vec2f b, Vec2f c) {
  return (double(b.x) - a.x) * (double(c.y) - a.y) - (double(c.x) - a.x) * (double(b.y) - a.y);
}

// --- LSCM ----------------------------------------------------------------------------------

std::vector<Vec3d> positionsOf(const Mesh& m) {
  std::vector<Vec3d> p;
  for (const Vec3f& q : m.positions) p.push_back(Vec3d(q));
  return p;
}

TEST(UnwrapLscm, ReproducesAFlatMeshUpToASimilarity) {
  // A jittered grid on a tilted plane: the conformal energy has an exact zero, the plane's own
  // coordinates up to a rotation, scale and shift, which LSCM must find (no angle distortion).
  const Vec3d o(0.3, -1, 2), du(1.5, 0.5, 0.2), dv = cross(Vec3d(0.1, 0.2, 1), du);
  const Mesh m = gridMesh(
      12, [&](double u, double v) { return o + du * u + dv * v; }, 0.3);
  const std::vector<Uv2> uv = lscm(positionsOf(m), m.triangles);
  ASSERT_EQ(uv.size(), m.positions.size());
  // The plane's coordinates: z = (p − o)·du/|du| + i (p − o)·dv/|dv|. Fit w = a z + b by least
  // squares (a complex-linear map: a similarity that keeps orientation) and check the residual.
  using C = std::complex<double>;
  std::vector<C> z, w;
  for (std::size_t i = 0; i < uv.size(); ++i) {
    const Vec3d q = Vec3d(m.positions[i]) - o;
    z.push_back({dot(q, du) / length(du), dot(q, dv) / length(dv)});
    w.push_back({uv[i][0], uv[i][1]});
  }
  C zm = 0, wm = 0;
  for (std::size_t i = 0; i < z.size(); ++i) zm += z[i], wm += w[i];
  zm /= double(z.size()), wm /= double(z.size());
  C num = 0;
  double den = 0;
  for (std::size_t i = 0; i < z.size(); ++i)
    num += std::conj(z[i] - zm) * (w[i] - wm), den += std::norm(z[i] - zm);
  const C a = num / den;
  double worst = 0;
  for (std::size_t i = 0; i < z.size(); ++i)
    worst = std::max(worst, std::abs(a * (z[i] - zm) + wm - w[i]));
  EXPECT_GT(std::abs(a), 0.1);
  EXPECT_LT(worst, 1e-8 * std::abs(a)) << "LSCM of a flat mesh is not a similarity of it";
}

TEST(UnwrapLscm, UnrollsAPolyhedralCylinderWithoutDistortion) {
  // A strip of a cylinder triangulated along its rulings is developable: its triangles unroll
  // into the plane unchanged, so LSCM must keep every angle and every length ratio.
  const Mesh m = gridMesh(10, [](double u, double v) {
    const double a = 2.0 * u;  // 115 degrees of arc
    return Vec3d(std::cos(a), 1.7 * v, std::sin(a));
  });
  const std::vector<Uv2> uv = lscm(positionsOf(m), m.triangles);
  ASSERT_EQ(uv.size(), m.positions.size());
  double scale = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Tri& tri = m.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const Vec3d e = Vec3d(m.positions[tri[(k + 1) % 3]]) - Vec3d(m.positions[tri[k]]);
      const double l2 = std::hypot(uv[tri[(k + 1) % 3]][0] - uv[tri[k]][0],
                                   uv[tri[(k + 1) % 3]][1] - uv[tri[k]][1]);
      if (scale == 0) scale = l2 / length(e);
      EXPECT_NEAR(l2 / length(e), scale, 1e-7 * scale) << "triangle " << t << " edge " << k;
    }
  }
}

TEST(UnwrapLscm, KeepsOrientationOnACurvedPatch) {
  // A patch of the sphere (a non-developable chart): distortion is allowed, flips are not.
  const Mesh m = gridMesh(
      16,
      [](double u, double v) {
        const double th = 0.3 + 1.0 * v, ph = 1.2 * u;
        return Vec3d(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
      },
      0.2);
  // Outward-facing for this parameterisation? Orient the check by the first triangle's normal.
  const std::vector<Uv2> uv = lscm(positionsOf(m), m.triangles);
  ASSERT_EQ(uv.size(), m.positions.size());
  std::vector<double> area3;
  for (const Tri& t : m.triangles)
    area3.push_back(0.5 * length(cross(Vec3d(m.positions[t[1]] - m.positions[t[0]]),
                                       Vec3d(m.positions[t[2]] - m.positions[t[0]]))));
  EXPECT_EQ(checkChartLayout(uv, m.triangles, area3), LayoutFault::None);
}

TEST(UnwrapLscm, RefusesWhatItCannotSolve) {
  const std::vector<Vec3d> p = {Vec3d(0, 0, 0), Vec3d(1, 0, 0)};
  const std::vector<Tri> none;
  EXPECT_TRUE(lscm(p, none).empty());
  // Two triangles that share only a vertex, pinned one in each (vertices 3 and 1, the extremes
  // in x): four equations for six unknowns, a singular system, refused (never a layout with
  // one triangle spun arbitrarily about the shared vertex).
  const std::vector<Vec3d> q = {Vec3d(0, 0, 0), Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(-1, 0, 0.5),
                                Vec3d(0, -1, 0.5)};
  const std::vector<Tri> bowtie = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_TRUE(lscm(q, bowtie).empty());
}

// --- layout checks ---------------------------------------------------------------------------

TEST(UnwrapLayout, FindsFlipsAndOverlapsButNotTouching) {
  const std::vector<double> area = {1, 1, 1};
  // A fan of three triangles around vertex 0, touching along edges: fine.
  std::vector<Uv2> uv = {{0, 0}, {1, 0}, {0.5, 1}, {-0.5, 1}, {-1, 0}};
  std::vector<Tri> fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  EXPECT_EQ(checkChartLayout(uv, fan, area), LayoutFault::None);
  // Fold the last one back over the first: flipped.
  uv[4] = {0.9, 0.2};
  EXPECT_EQ(checkChartLayout(uv, fan, area), LayoutFault::Flipped);
  // Two separate counter-clockwise triangles lying across each other: overlap.
  const std::vector<Uv2> two = {{0, 0}, {2, 0}, {1, 2}, {0, 1}, {2, 1}, {1, 3}};
  const std::vector<Tri> pair = {{0, 1, 2}, {3, 4, 5}};
  EXPECT_EQ(checkChartLayout(two, pair, area), LayoutFault::Overlap);
  // Moved apart so that they touch at one point only: fine.
  const std::vector<Uv2> apart = {{0, 0}, {2, 0}, {1, 2}, {1, 2}, {3, 2}, {2, 4}};
  EXPECT_EQ(checkChartLayout(apart, pair, area), LayoutFault::None);
}

TEST(UnwrapLayout, PlacesARotatedRectangleOnItsSides) {
  // Points of a 3 × 1 rectangle turned by 0.4 rad and shifted: the rectangle found is 3 × 1,
  // the motion rigid (distances kept), the lower corner at the origin.
  std::vector<Uv2> uv;
  const double c = std::cos(0.4), s = std::sin(0.4);
  for (double x : {0.0, 1.0, 2.0, 3.0})
    for (double y : {0.0, 0.5, 1.0}) uv.push_back({5 + c * x - s * y, -2 + s * x + c * y});
  const std::vector<Uv2> before = uv;
  const std::array<double, 2> size = placeOnBoundingRectangle(uv);
  EXPECT_NEAR(size[0], 3, 1e-9);
  EXPECT_NEAR(size[1], 1, 1e-9);
  double lo0 = HUGE_VAL, lo1 = HUGE_VAL;
  for (std::size_t i = 0; i < uv.size(); ++i) {
    lo0 = std::min(lo0, uv[i][0]), lo1 = std::min(lo1, uv[i][1]);
    for (std::size_t j = 0; j < uv.size(); ++j)
      EXPECT_NEAR(std::hypot(uv[i][0] - uv[j][0], uv[i][1] - uv[j][1]),
                  std::hypot(before[i][0] - before[j][0], before[i][1] - before[j][1]), 1e-9);
  }
  EXPECT_NEAR(lo0, 0, 1e-12);
  EXPECT_NEAR(lo1, 0, 1e-12);
  // Orientation kept: the signed area of a triangle of the points is unchanged.
  const auto area = [](const std::vector<Uv2>& q) {
    return (q[3][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[2][0] - q[0][0]) * (q[3][1] - q[0][1]);
  };
  EXPECT_NEAR(area(uv), area(before), 1e-9);
}

// --- charts ----------------------------------------------------------------------------------

TEST(UnwrapCharts, ACylinderSplitsAtItsRimsAndStaysInsideTheCone) {
  const Mesh m = closedCylinder(32, 4);
  const TriangleAdjacency adj = buildAdjacency(m);
  for (const auto& n : adj.neighbour)
    for (std::uint32_t u : n) EXPECT_NE(u, TriangleAdjacency::kNone) << "the cylinder is closed";
  const double cone = 60 * M_PI / 180;
  const ChartSegmentation seg = growCharts(adj, cone);
  // The caps are flat (one chart each); the side's normals turn through 360° so it needs at
  // least 360 / 120 = 3 charts; no chart mixes a cap with the side (90° apart).
  EXPECT_GE(seg.count, 5u);
  std::vector<Vec3d> sum(seg.count, Vec3d(0.0));
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
    sum[seg.chartOfTriangle[t]] += adj.faceNormal[t] * adj.faceArea[t];
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
    EXPECT_GT(dot(adj.faceNormal[t], normalize(sum[seg.chartOfTriangle[t]])), std::cos(cone) - 1e-9)
        << "triangle " << t;
  // Charts are edge-connected.
  std::vector<std::vector<std::uint32_t>> members(seg.count);
  for (std::uint32_t t = 0; t < m.triangleCount(); ++t)
    members[seg.chartOfTriangle[t]].push_back(t);
  for (const auto& c : members) EXPECT_EQ(connectedComponents(adj, c).size(), 1u);
}

TEST(UnwrapCharts, WeldsSplitVerticesAndNeverCrossesParts) {
  // Two quads side by side whose shared edge uses different vertices (as a file with a normal
  // seam has): welded, they are one chart. As two parts they are two.
  Mesh m;
  m.positions = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 0),
                 Vec3f(1, 0, 0), Vec3f(2, 0, 0), Vec3f(2, 1, 0), Vec3f(1, 1, 0)};
  m.normals.assign(8, Vec3f(0, 0, 1));
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  EXPECT_EQ(growCharts(buildAdjacency(m), 1.0).count, 1u);
  m.parts = {{"a", 0, 4, 0, 2}, {"b", 4, 4, 2, 2}};
  EXPECT_EQ(growCharts(buildAdjacency(m), 1.0).count, 2u);
}

// --- whole atlases ---------------------------------------------------------------------------

/// The texels triangle p (texel units) covers with area: its clip against each texel square.
template <class F>
void rasteriseConservative(const double p[3][2], int N, F&& f) {
  const double x0 = std::min({p[0][0], p[1][0], p[2][0]}),
               x1 = std::max({p[0][0], p[1][0], p[2][0]});
  const double y0 = std::min({p[0][1], p[1][1], p[2][1]}),
               y1 = std::max({p[0][1], p[1][1], p[2][1]});
  for (int y = std::max(0, int(std::floor(y0))); y <= std::min(N - 1, int(std::floor(y1))); ++y)
    for (int x = std::max(0, int(std::floor(x0))); x <= std::min(N - 1, int(std::floor(x1))); ++x) {
      std::vector<std::array<double, 2>> poly = {
          {p[0][0], p[0][1]}, {p[1][0], p[1][1]}, {p[2][0], p[2][1]}};
      for (int side = 0; side < 4 && !poly.empty(); ++side) {
        const int d = side / 2;
        const double edge = side % 2 == 0 ? (d == 0 ? x : y) : (d == 0 ? x + 1 : y + 1);
        const auto in = [&](const std::array<double, 2>& q) {
          return side % 2 == 0 ? q[d] >= edge : q[d] <= edge;
        };
        std::vector<std::array<double, 2>> next;
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const auto& a = poly[i];
          const auto& b = poly[(i + 1) % poly.size()];
          if (in(a)) next.push_back(a);
          if (in(a) != in(b)) {
            const double t = (edge - a[d]) / (b[d] - a[d]);
            next.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])});
          }
        }
        poly.swap(next);
      }
      double area = 0;
      for (std::size_t i = 0; i < poly.size(); ++i)
        area += poly[i][0] * poly[(i + 1) % poly.size()][1] -
                poly[(i + 1) % poly.size()][0] * poly[i][1];
      if (std::abs(area) > 1e-9) f(x, y);
    }
}

/// Everything an atlas must be, checked from the outside.
void expectValidAtlas(const Mesh& in, const UnwrapResult& r, const UnwrapSettings& s) {
  const Mesh& m = r.mesh;
  SCOPED_TRACE(in.source);
  ASSERT_EQ(m.triangleCount(), in.triangleCount());
  ASSERT_EQ(m.lightmapUvs.size(), m.vertexCount());
  ASSERT_EQ(r.sourceVertex.size(), m.vertexCount());
  ASSERT_GE(m.vertexCount(), in.vertexCount());
  // The same surface: every vertex copies its source, every triangle the same corners.
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    ASSERT_EQ(m.positions[v], in.positions[r.sourceVertex[v]]);
    ASSERT_EQ(m.normals[v], in.normals[r.sourceVertex[v]]);
  }
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(r.sourceVertex[m.triangles[t][k]], in.triangles[t][k]);
  // Inside the square; every triangle with area keeps a counter-clockwise image.
  for (const Vec2f& t : m.lightmapUvs) {
    ASSERT_TRUE(t.x >= 0 && t.x <= 1 && t.y >= 0 && t.y <= 1) << t.x << ", " << t.y;
  }
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const auto& tri = m.triangles[t];
    EXPECT_GT(signedArea2(m.lightmapUvs[tri[0]], m.lightmapUvs[tri[1]], m.lightmapUvs[tri[2]]), 0)
        << "triangle " << t << " is flipped or degenerate in UV";
  }
  // The library's own check of a lightmap UV set.
  EXPECT_NO_THROW(checkLightmapUvs(m, m.lightmapUvs, s.resolution, s.resolution, "TEXCOORD_1"));
  // Rasterised conservatively at the resolution: no texel touched by two charts, and no two
  // charts' texels within `padding` texels of each other (at least `padding` empty between).
  const int N = s.resolution;
  std::vector<std::int32_t> owner(std::size_t(N) * N, -1);
  std::size_t shared = 0;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    double p[3][2];
    for (int k = 0; k < 3; ++k)
      p[k][0] = double(m.lightmapUvs[m.triangles[t][k]].x) * N,
      p[k][1] = double(m.lightmapUvs[m.triangles[t][k]].y) * N;
    const std::int32_t chart = std::int32_t(r.chartOfTriangle[t]);
    rasteriseConservative(p, N, [&](int x, int y) {
      std::int32_t& o = owner[std::size_t(y) * N + x];
      if (o >= 0 && o != chart) ++shared;
      o = chart;
    });
  }
  EXPECT_EQ(shared, 0u) << "texels covered by two charts";
  std::size_t close = 0;
  const int P = s.padding;
  for (int y = 0; y < N; ++y)
    for (int x = 0; x < N; ++x) {
      const std::int32_t o = owner[std::size_t(y) * N + x];
      if (o < 0) continue;
      EXPECT_TRUE(x >= P && y >= P && x < N - P && y < N - P)
          << "chart within the border's padding";
      for (int dy = -P; dy <= P; ++dy)
        for (int dx = -P; dx <= P; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= N || v >= N) continue;
          const std::int32_t q = owner[std::size_t(v) * N + u];
          if (q >= 0 && q != o) ++close;
        }
    }
  EXPECT_EQ(close, 0u) << "texel pairs of two charts closer than the padding";
  // Stats that say the atlas is sane.
  EXPECT_GT(r.stats.charts, 0u);
  EXPECT_GT(r.stats.chartArea, 0.05);
  EXPECT_LT(r.stats.chartArea, 1.0);
  EXPECT_GE(r.stats.stretchL2, 1.0 - 1e-6);
  EXPECT_GT(r.stats.texelsCovered, r.stats.chartArea * 0.5);
}

TEST(Unwrap, AFlatSquareIsOneUndistortedChart) {
  const Mesh m = gridMesh(
      8, [](double u, double v) { return Vec3d(2 * u, 0, -2 * v); }, 0.2);
  Mesh up = m;
  up.normals.assign(up.positions.size(), Vec3f(0, 1, 0));
  const UnwrapSettings s;
  const UnwrapResult r = unwrap(up, s);
  expectValidAtlas(up, r, s);
  EXPECT_EQ(r.stats.charts, 1u);
  EXPECT_EQ(r.mesh.vertexCount(), m.vertexCount()) << "one chart splits no vertex";
  EXPECT_NEAR(r.stats.stretchL2, 1.0, 1e-5);
  EXPECT_NEAR(r.stats.densityMin, 1.0, 1e-4);
  EXPECT_NEAR(r.stats.densityMax, 1.0, 1e-4);
  // A square on its own fills the square but for the padding from the border, (1 − 2 · 2/512)²,
  // less the packer's search (its scale to 0.2%, so the area to 0.4%).
  const double fill =
      (1.0 - 2.0 * s.padding / s.resolution) * (1.0 - 2.0 * s.padding / s.resolution);
  EXPECT_LE(r.stats.chartArea, fill);
  EXPECT_GT(r.stats.chartArea, fill * (1 - 5e-3));
}

TEST(Unwrap, ClosedMeshesMakeValidAtlases) {
  const UnwrapSettings s;
  for (const Mesh& m : {closedCylinder(48, 6), bumpySphere(), loadMesh("builtin:sphere")}) {
    const UnwrapResult r = unwrap(m, s);
    expectValidAtlas(m, r, s);
    EXPECT_GT(r.stats.charts, 2u) << m.source;
    EXPECT_LT(r.stats.stretchL2, 1.1) << m.source;
  }
}

TEST(Unwrap, BuiltinScenesMakeValidAtlasesWithTheirParts) {
  for (const std::string& name : builtinSceneNames()) {
    const Mesh m = loadMesh("builtin:" + name);
    UnwrapSettings s;
    s.resolution = 256;
    s.padding = 1;
    const UnwrapResult r = unwrap(m, s);
    expectValidAtlas(m, r, s);
    ASSERT_EQ(r.mesh.parts.size(), m.parts.size());
    std::uint32_t next = 0;
    for (std::size_t p = 0; p < m.parts.size(); ++p) {
      EXPECT_EQ(r.mesh.parts[p].name, m.parts[p].name);
      EXPECT_EQ(r.mesh.parts[p].firstVertex, next);
      EXPECT_EQ(r.mesh.parts[p].firstTriangle, m.parts[p].firstTriangle);
      EXPECT_EQ(r.mesh.parts[p].triangleCount, m.parts[p].triangleCount);
      next += r.mesh.parts[p].vertexCount;
      for (std::uint32_t v = r.mesh.parts[p].firstVertex; v < next; ++v) {
        EXPECT_GE(r.sourceVertex[v], m.parts[p].firstVertex);
        EXPECT_LT(r.sourceVertex[v], m.parts[p].firstVertex + m.parts[p].vertexCount);
      }
    }
    EXPECT_EQ(next, r.mesh.vertexCount());
    EXPECT_EQ(r.mesh.albedo.size(), m.albedo.empty() ? 0 : r.mesh.vertexCount());
  }
}

// Issue 31: a chart larger than the bound is cut into compact parts within it; under the bound
// nothing changes.
TEST(Unwrap, BoundsTheChartSizeWithCompactCharts) {
  // A jittered flat 50 × 50 grid, 5,000 triangles: the cone grows it as one chart.
  const Mesh m = gridMesh(
      50, [](double u, double v) { return Vec3d(u, v, 0); }, 0.2);
  ASSERT_EQ(m.triangleCount(), 5000u);
  UnwrapSettings s;
  s.maxChartTriangles = 500;
  UnwrapFootprint f;
  const UnwrapResult r = unwrap(m, s, {}, [&](const UnwrapFootprint& fp) { f = fp; });
  expectValidAtlas(m, r, s);  // every triangle in a chart, no two charts' texels close
  EXPECT_GE(r.grownCharts, 10u);
  EXPECT_EQ(f.charts, r.grownCharts);
  EXPECT_LE(f.largestChart, 500u) << "the footprint follows the bounded charts";
  std::vector<std::size_t> size(r.stats.charts, 0);
  std::vector<Vec3d> lo(r.stats.charts, Vec3d(HUGE_VAL)), hi(r.stats.charts, Vec3d(-HUGE_VAL));
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const std::uint32_t c = r.chartOfTriangle[t];
    ASSERT_LT(c, r.stats.charts);
    ++size[c];
    for (std::uint32_t v : m.triangles[t]) {
      lo[c] = min(lo[c], Vec3d(m.positions[v]));
      hi[c] = max(hi[c], Vec3d(m.positions[v]));
    }
  }
  // Each chart within the bound, and a blob rather than a strip: growing by the cone until the
  // bound would take the plane's rows in triangle order (every cost ties), strips of 5 × 50
  // cells; cut across its longest extent, no part is more than 3 times longer than wide.
  const TriangleAdjacency adj = buildAdjacency(m);
  for (std::size_t c = 0; c < size.size(); ++c) {
    EXPECT_LE(size[c], 500u) << "chart " << c;
    const double w = hi[c].x - lo[c].x, h = hi[c].y - lo[c].y;
    if (size[c] > 100) {
      EXPECT_LE(std::max(w, h), 3 * std::min(w, h)) << "chart " << c;
    }
  }
  const ChartSegmentation grown = growCharts(adj, 60 * M_PI / 180);
  ASSERT_EQ(grown.count, 1u);
  const ChartSegmentation bounded = boundCharts(m, adj, grown, 500);
  std::vector<std::vector<std::uint32_t>> members(bounded.count);
  for (std::uint32_t t = 0; t < m.triangleCount(); ++t)
    members[bounded.chartOfTriangle[t]].push_back(t);
  for (const auto& c : members) {
    EXPECT_LE(c.size(), 500u);
    EXPECT_EQ(connectedComponents(adj, c).size(), 1u);
  }
  // Under the bound (or unbounded) the atlas is the one unbounded growth makes.
  UnwrapSettings unbounded;
  unbounded.maxChartTriangles = 0;
  const UnwrapResult a = unwrap(m, unbounded);
  s.maxChartTriangles = 5000;
  const UnwrapResult b = unwrap(m, s);
  EXPECT_EQ(a.grownCharts, 1u);
  EXPECT_EQ(a.mesh.lightmapUvs, b.mesh.lightmapUvs);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.mesh.lightmapUvs, unwrap(m).mesh.lightmapUvs) << "the default bound is above 5,000";
}

TEST(Unwrap, IsDeterministicAndIndependentOfThreads) {
  const Mesh m = bumpySphere();
  const UnwrapResult a = unwrap(m);
  const UnwrapResult b = unwrap(m);
  UnwrapResult c;
  {
    ThreadLimit one(1);
    c = unwrap(m);
  }
  EXPECT_EQ(a.mesh.lightmapUvs, b.mesh.lightmapUvs);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.mesh.lightmapUvs, c.mesh.lightmapUvs);
  EXPECT_EQ(a.mesh.triangles, c.mesh.triangles);
}

TEST(Unwrap, RefusesBadSettingsAndEmptyMeshes) {
  const Mesh m = loadMesh("builtin:sphere");
  const auto refuses = [&](UnwrapSettings s, const std::string& mention) {
    try {
      unwrap(m, s);
      ADD_FAILURE() << "accepted " << mention;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
    }
  };
  UnwrapSettings s;
  s.resolution = 0;
  refuses(s, "resolution");
  s = {};
  s.padding = -1;
  refuses(s, "padding");
  s = {};
  s.maxConeDegrees = 90;
  refuses(s, "cone");
  s = {};
  s.maxStretch = 0.9;
  refuses(s, "stretch");
  s = {};
  s.resolution = 8;  // a gutter of 3 texels in 8 leaves no room for hundreds of charts
  refuses(s, "raise the resolution");
  Mesh empty;
  empty.source = "empty.obj";
  EXPECT_THROW(unwrap(empty), Error);
}

TEST(Unwrap, TheBunnyUnwrapsInSeconds) {
  const std::string path = "/usr/share/glmark2/models/bunny.obj";
  if (!std::filesystem::exists(path))
    GTEST_SKIP() << path << " is absent (Debian package glmark2-data, scripts/setup.sh)";
  const Mesh m = loadMesh(path);
  ASSERT_GT(m.triangleCount(), 60000u);
  UnwrapSettings s;
  s.resolution = 1024;
  const UnwrapResult r = unwrap(m, s);
  expectValidAtlas(m, r, s);
  EXPECT_LT(r.stats.seconds, 10.0);
  // Within the per-chart stretch limit (1.1) overall, and packed by shape into more of the
  // square than xatlas's atlas of the bunny covers of its own (docs/performance.md, "Unwrap":
  // L2 1.02, 54.7%).
  EXPECT_LT(r.stats.stretchL2, 1.05);
  EXPECT_GT(r.stats.densityP05, 0.7);
  EXPECT_LT(r.stats.densityP95, 1.3);
  EXPECT_TRUE(r.packedByShape);
  EXPECT_GT(r.stats.chartArea, 0.6);
  std::printf(
      "bunny: %zu charts, %.3f s, chart area %.3f, texels %.3f, L2 %.3f, density 5-95%% "
      "%.2f-%.2f\n",
      r.stats.charts, r.stats.seconds, r.stats.chartArea, r.stats.texelsCovered, r.stats.stretchL2,
      r.stats.densityP05, r.stats.densityP95);
}

// Issue 31: the progress runs once from near 0 to 1 over every phase, never back, with the
// footprint stated before the first report; cancelling from it stops the unwrap.
TEST(Unwrap, ProgressRisesOverEveryPhaseAfterTheFootprint) {
  const Mesh mesh = loadMesh("builtin:sphere?subdiv=4");
  std::vector<double> seen;
  int footprints = 0;
  std::size_t reportsBeforeFootprint = 0;
  UnwrapFootprint f;
  const UnwrapResult r = unwrap(
      mesh, {},
      [&](double x) {
        seen.push_back(x);
        return true;
      },
      [&](const UnwrapFootprint& fp) {
        ++footprints;
        reportsBeforeFootprint = seen.size();
        f = fp;
      });
  EXPECT_EQ(footprints, 1);
  EXPECT_EQ(reportsBeforeFootprint, 0u);
  EXPECT_EQ(f.triangles, mesh.triangleCount());
  EXPECT_GT(f.baseBytes, 0u);
  EXPECT_GT(f.solveBytes, 0u);
  ASSERT_GE(seen.size(), 4u);
  EXPECT_LT(seen.front(), 0.5);
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_LT(seen[i - 1], seen[i]) << i;
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  // The same atlas with or without the observers.
  EXPECT_EQ(r.mesh.lightmapUvs, unwrap(mesh).mesh.lightmapUvs);
  std::size_t calls = 0;
  EXPECT_THROW(unwrap(mesh, {}, [&](double) { return ++calls < 3; }), Cancelled);
}

}  // namespace
}  // namespace prt
