#pragma once
// The triangle mesh every stage shares. A scene of several objects is merged into one Mesh (so
// they shadow each other and share one BVH); `parts` remembers where each object's vertices and
// triangles lie so writers can split them again.
//
// Vertices are split wherever the source file splits them (a position used with two normals or
// two UVs becomes two vertices); only exact duplicates are welded. Normals are unit length.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt {

struct MeshPart {
  std::string name;
  std::uint32_t firstVertex = 0, vertexCount = 0;
  std::uint32_t firstTriangle = 0, triangleCount = 0;
};

struct Mesh {
  std::vector<Vec3f> positions;  ///< world space (scene transforms applied)
  std::vector<Vec3f> normals;    ///< unit, one per vertex
  std::vector<Rgb> albedo;       ///< linear diffuse albedo per vertex (empty: uniform)
  std::vector<Vec2f> uvs;        ///< optional texture coordinates
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise = front
  std::vector<MeshPart> parts;                          ///< at least one part when loaded
  std::string source;                                   ///< file name or builtin:NAME, for messages

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return triangles.size(); }
  bool hasAlbedo() const { return !albedo.empty(); }
};

/// Axis-aligned bounds and the bounding sphere of the vertices.
struct Bounds {
  Vec3f lo{0.0f}, hi{0.0f};
  Vec3f centre() const { return (lo + hi) * 0.5f; }
  float radius() const { return length(hi - lo) * 0.5f; }
};
Bounds computeBounds(const Mesh& mesh);

}  // namespace prt
