#pragma once
// Test scenes for per-texel transfer against per-vertex transfer of the same geometry:
//   * coarsePlane: a plane [-2, 2]² at y = 0 facing +Y, two triangles whose lightmap UVs map it
//     onto [0, 1]² (u = (x + 2)/4, v = (z + 2)/4); with `ball`, a sphere of radius 0.6 at height
//     1 above it (no lightmap area: its UVs are all 0, so it holds no texels but casts its
//     shadow);
//   * texelCentrePlane: the same geometry with a vertex at every texel centre of an N × N
//     lightmap of the plane — vertex j·N + i at texel (i, j), same point, normal and seed index,
//     so the same kernel gives the same row — and the ball's vertices after them.

#include <cstdint>
#include <utility>
#include <vector>

#include "prt/geometry/builtin.hpp"
#include "prt/geometry/mesh.hpp"

namespace prt::testing {

inline Mesh coarsePlane(bool ball) {
  Mesh m;
  m.source = "coarse-plane";
  for (const auto& [x, z] :
       std::vector<std::pair<float, float>>{{-2, -2}, {2, -2}, {2, 2}, {-2, 2}}) {
    m.positions.push_back({x, 0, z});
    m.normals.push_back({0, 1, 0});
    m.lightmapUvs.push_back({(x + 2) / 4, (z + 2) / 4});
  }
  m.triangles = {{0, 3, 2}, {0, 2, 1}};
  if (ball) {
    const Mesh s = builtinScene("builtin:sphere?subdiv=3&r=0.6");
    const std::uint32_t base = std::uint32_t(m.positions.size());
    for (std::size_t v = 0; v < s.vertexCount(); ++v) {
      m.positions.push_back(s.positions[v] + Vec3f(0, 1, 0));
      m.normals.push_back(s.normals[v]);
      m.lightmapUvs.push_back({0, 0});
    }
    for (const auto& t : s.triangles)
      m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return m;
}

inline Mesh texelCentrePlane(const Mesh& coarse, int n) {
  Mesh fine;
  fine.source = "fine-plane";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      fine.positions.push_back({-2 + 4 * (i + 0.5f) / n, 0, -2 + 4 * (j + 0.5f) / n});
      fine.normals.push_back({0, 1, 0});
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      fine.triangles.push_back({a, c, d});
      fine.triangles.push_back({a, d, b});
    }
  const std::uint32_t base = std::uint32_t(fine.positions.size());
  for (std::size_t v = 4; v < coarse.vertexCount(); ++v) {
    fine.positions.push_back(coarse.positions[v]);
    fine.normals.push_back(coarse.normals[v]);
  }
  for (std::size_t t = 2; t < coarse.triangleCount(); ++t)
    fine.triangles.push_back({coarse.triangles[t][0] - 4 + base, coarse.triangles[t][1] - 4 + base,
                              coarse.triangles[t][2] - 4 + base});
  return fine;
}

}  // namespace prt::testing
