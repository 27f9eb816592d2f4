#include "prt/geometry/uv_seams.hpp"

#include <cstring>
#include <map>
#include <utility>

#include "prt/core/error.hpp"

namespace prt {

namespace {

constexpr float kSmoothCos = 0.999f;  // normals within ~2.5° on both sides: not a crease

std::array<std::uint32_t, 3> bits(const Vec3f& p) {
  std::array<std::uint32_t, 3> b{};
  std::memcpy(b.data(), &p.x, 12);
  return b;
}

}  // namespace

std::vector<UvSeamEdge> findUvSeams(const Mesh& mesh, std::span<const Vec2f> uvs) {
  if (uvs.size() != mesh.vertexCount())
    throw Error(mesh.source, "the UV set does not match the mesh's vertices");
  // Edges by their endpoints' positions: (lower, higher) bits → the (vertex, vertex) pairs.
  using Key = std::pair<std::array<std::uint32_t, 3>, std::array<std::uint32_t, 3>>;
  std::map<Key, std::vector<std::array<std::uint32_t, 2>>> edges;
  for (const auto& tri : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      std::uint32_t a = tri[e], b = tri[(e + 1) % 3];
      auto ka = bits(mesh.positions[a]), kb = bits(mesh.positions[b]);
      if (ka == kb) continue;  // a degenerate edge
      if (kb < ka) std::swap(a, b), std::swap(ka, kb);
      edges[{ka, kb}].push_back({a, b});
    }
  const auto sameUv = [](Vec2f p, Vec2f q) { return p.x == q.x && p.y == q.y; };
  std::vector<UvSeamEdge> seams;
  for (const auto& [key, sides] : edges) {
    if (sides.size() != 2) continue;
    const auto [a0, b0] = sides[0];
    const auto [a1, b1] = sides[1];
    if (sameUv(uvs[a0], uvs[a1]) && sameUv(uvs[b0], uvs[b1])) continue;  // one chart: no seam
    if (dot(mesh.normals[a0], mesh.normals[a1]) < kSmoothCos ||
        dot(mesh.normals[b0], mesh.normals[b1]) < kSmoothCos)
      continue;  // a crease
    seams.push_back({{{{a0, b0}, {a1, b1}}}, length(mesh.positions[b0] - mesh.positions[a0])});
  }
  return seams;
}

}  // namespace prt
