#pragma once
// A test scene with one UV seam (the seam metric's and the seam fix's tests): two quads x ∈
// [−2, 0] and [0, 2], z ∈ [−2, 2] facing +Y, each its own lightmap chart, and a ball of radius
// 0.6 at height 1 above the seam at z = 1 (its shadow crosses the seam, not symmetric along
// it), without lightmap area. The left chart is u ∈ [0.05, 0.45], v ∈ [0.05, 0.95]. The right
// chart is u ∈ [0.55, 0.95], v ∈ [0.05, 0.95] too (the same texel density, aligned), or with
// `rotatedRightChart` turned a quarter and at half the density (u ∈ [0.55, 0.95] along z, v ∈
// [0.05, 0.25] along x): the two sides of the seam then fetch unrelated texel grids.

#include <utility>
#include <vector>

#include "prt/geometry/builtin.hpp"
#include "prt/geometry/mesh.hpp"

namespace prt::testing {

inline Mesh twoChartPlane(bool rotatedRightChart = false) {
  Mesh m;
  m.source = "two-chart plane";
  for (int side = 0; side < 2; ++side) {
    const float x0 = side == 0 ? -2.0f : 0.0f;
    const std::uint32_t base = std::uint32_t(m.positions.size());
    for (const auto& [dx, z] :
         std::vector<std::pair<float, float>>{{0, -2}, {2, -2}, {2, 2}, {0, 2}}) {
      m.positions.push_back({x0 + dx, 0, z});
      m.normals.push_back({0, 1, 0});
      if (side == 0 || !rotatedRightChart)
        m.lightmapUvs.push_back({(side == 0 ? 0.05f : 0.55f) + 0.2f * dx, 0.05f + 0.9f * (z + 2) / 4});
      else
        m.lightmapUvs.push_back({0.55f + 0.1f * (z + 2), 0.05f + 0.1f * dx});
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

}  // namespace prt::testing
