#include "prt/unwrap/atlas_stats.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include "prt/core/error.hpp"

namespace prt {

namespace {

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

/// Whether triangle p (texel units) and the texel square [x, x+1] × [y, y+1] share area: no
/// separating axis among the square's two and the triangle's three edge normals.
bool overlapsTexel(const double p[3][2], int x, int y) {
  const double sq[4][2] = {
      {double(x), double(y)}, {x + 1.0, double(y)}, {x + 1.0, y + 1.0}, {double(x), y + 1.0}};
  constexpr double tol = 1e-9;
  for (int d = 0; d < 2; ++d) {
    const double lo = std::min({p[0][d], p[1][d], p[2][d]});
    const double hi = std::max({p[0][d], p[1][d], p[2][d]});
    if (hi <= sq[0][d] + tol || lo >= sq[2][d] - tol) return false;
  }
  for (int k = 0; k < 3; ++k) {
    const double* a = p[k];
    const double* b = p[(k + 1) % 3];
    const double nx = b[1] - a[1], ny = a[0] - b[0];
    double tmin = HUGE_VAL, tmax = -HUGE_VAL, smin = HUGE_VAL, smax = -HUGE_VAL;
    for (int j = 0; j < 3; ++j) {
      const double v = p[j][0] * nx + p[j][1] * ny;
      tmin = std::min(tmin, v), tmax = std::max(tmax, v);
    }
    for (int j = 0; j < 4; ++j) {
      const double v = sq[j][0] * nx + sq[j][1] * ny;
      smin = std::min(smin, v), smax = std::max(smax, v);
    }
    const double len = std::hypot(nx, ny);
    if (tmax <= smin + tol * len || smax <= tmin + tol * len) return false;
  }
  return true;
}

}  // namespace

AtlasStats measureAtlas(const Mesh& mesh, std::span<const Vec2f> uvs, int resolution) {
  PRT_CHECK(uvs.size() == mesh.vertexCount(), "measureAtlas: one UV per vertex");
  PRT_CHECK(resolution >= 1, "measureAtlas: resolution >= 1");
  const std::size_t V = mesh.vertexCount(), T = mesh.triangleCount();
  AtlasStats s;

  // Islands: union the corners of each triangle, and vertices with the same position and UV.
  std::vector<std::uint32_t> parent(V);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto unite = [&](std::uint32_t a, std::uint32_t b) {
    a = findRoot(parent, a), b = findRoot(parent, b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  std::vector<std::uint32_t> order(V);
  std::iota(order.begin(), order.end(), 0u);
  const auto key = [&](std::uint32_t v) {
    const Vec3f& p = mesh.positions[v];
    return std::make_tuple(p.x, p.y, p.z, uvs[v].x, uvs[v].y);
  };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  for (std::size_t i = 1; i < V; ++i)
    if (key(order[i]) == key(order[i - 1])) unite(order[i], order[i - 1]);
  for (const auto& tri : mesh.triangles) unite(tri[0], tri[1]), unite(tri[0], tri[2]);
  std::vector<std::uint8_t> isRoot(V, 0);
  for (const auto& tri : mesh.triangles) isRoot[findRoot(parent, tri[0])] = 1;
  s.charts = std::size_t(std::count(isRoot.begin(), isRoot.end(), 1));

  // Areas, densities and stretch per triangle.
  struct Tri {
    double area3, areaUv, l2sq, linfsq;
  };
  std::vector<Tri> tris;
  tris.reserve(T);
  double sum3 = 0, sumUv = 0, sumUvAll = 0;
  for (const auto& tri : mesh.triangles) {
    const Vec3d q1(mesh.positions[tri[0]]), q2(mesh.positions[tri[1]]), q3(mesh.positions[tri[2]]);
    const double s1 = uvs[tri[0]].x, t1 = uvs[tri[0]].y, s2 = uvs[tri[1]].x, t2 = uvs[tri[1]].y;
    const double s3 = uvs[tri[2]].x, t3 = uvs[tri[2]].y;
    const double a2 = (s2 - s1) * (t3 - t1) - (s3 - s1) * (t2 - t1);  // 2 A'
    const double area3 = 0.5 * length(cross(q2 - q1, q3 - q1));
    sumUvAll += 0.5 * std::abs(a2);
    if (!(area3 > 0) || a2 == 0) continue;
    const Vec3d Ss = (q1 * (t2 - t3) + q2 * (t3 - t1) + q3 * (t1 - t2)) / a2;
    const Vec3d St = (q1 * (s3 - s2) + q2 * (s1 - s3) + q3 * (s2 - s1)) / a2;
    const double a = dot(Ss, Ss), b = dot(Ss, St), c = dot(St, St);
    tris.push_back({area3, 0.5 * std::abs(a2), (a + c) / 2,
                    ((a + c) + std::sqrt((a - c) * (a - c) + 4 * b * b)) / 2});
    sum3 += area3;
    sumUv += 0.5 * std::abs(a2);
  }
  s.chartArea = sumUvAll;
  s.wastedArea = 1 - sumUvAll;
  if (!tris.empty() && sum3 > 0 && sumUv > 0) {
    const double norm2 = sumUv / sum3;  // the square of the normalisation
    double l2 = 0;
    for (const Tri& t : tris) {
      l2 += t.l2sq * t.area3;
      s.stretchL2Max = std::max(s.stretchL2Max, std::sqrt(t.l2sq * norm2));
      s.stretchLinfMax = std::max(s.stretchLinfMax, std::sqrt(t.linfsq * norm2));
    }
    s.stretchL2 = std::sqrt(l2 / sum3 * norm2);
    // ρ / mean = √((A'/A) / (ΣA'/ΣA)); percentiles weighted by surface area.
    std::vector<std::pair<double, double>> density;  // (ρ / mean, area)
    density.reserve(tris.size());
    for (const Tri& t : tris) density.push_back({std::sqrt(t.areaUv / t.area3 / norm2), t.area3});
    std::sort(density.begin(), density.end());
    s.densityMin = density.front().first;
    s.densityMax = density.back().first;
    const auto percentile = [&](double f) {
      double acc = 0;
      for (const auto& [r, w] : density) {
        acc += w;
        if (acc >= f * sum3) return r;
      }
      return density.back().first;
    };
    s.densityP05 = percentile(0.05);
    s.densityP95 = percentile(0.95);
  }

  // Texels a triangle overlaps (with area), as a bake spends them.
  const int N = resolution;
  std::vector<std::uint8_t> covered(std::size_t(N) * N, 0);
  for (const auto& tri : mesh.triangles) {
    double p[3][2];
    for (int k = 0; k < 3; ++k)
      p[k][0] = double(uvs[tri[k]].x) * N, p[k][1] = double(uvs[tri[k]].y) * N;
    const double a2 =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (!(std::abs(a2) > 1e-12)) continue;
    const int x0 = std::max(0, int(std::floor(std::min({p[0][0], p[1][0], p[2][0]}))));
    const int x1 = std::min(N - 1, int(std::floor(std::max({p[0][0], p[1][0], p[2][0]}))));
    const int y0 = std::max(0, int(std::floor(std::min({p[0][1], p[1][1], p[2][1]}))));
    const int y1 = std::min(N - 1, int(std::floor(std::max({p[0][1], p[1][1], p[2][1]}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        std::uint8_t& c = covered[std::size_t(y) * N + x];
        if (!c && overlapsTexel(p, x, y)) c = 1;
      }
  }
  s.texelsCovered = double(std::count(covered.begin(), covered.end(), 1)) / (double(N) * N);
  s.wastedTexels = 1 - s.texelsCovered;
  return s;
}

}  // namespace prt
