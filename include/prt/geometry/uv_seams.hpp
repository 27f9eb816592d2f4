#pragma once
// The seams of a UV set (issue 18): where a smooth surface is cut into two charts, an edge the
// two triangles share in space has two places in UV space. A seam edge is an edge of exactly
// two triangles whose endpoints have equal positions (bitwise) on both sides and, at both ends,
// normals within ~2.5° (cos ≥ 0.999; a crease is not a seam: its two sides are lit apart), and
// whose UVs differ on the two sides. What the seam metric (render/lightmap_seams.hpp) measures
// and the seam fix (transport/lightmap_seam_fix.hpp) closes — one definition for both.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/geometry/mesh.hpp"

namespace prt {

struct UvSeamEdge {
  /// The edge's two vertices on each side, in the same spatial order: side[0] = {a, b} and
  /// side[1] = {a', b'} with position(a) = position(a') and position(b) = position(b').
  std::array<std::array<std::uint32_t, 2>, 2> side;
  float length = 0;  ///< world units
};

/// The seam edges of `uvs` (one per vertex of `mesh`), in a deterministic order (by the
/// endpoints' position bits). Non-manifold edges (three or more triangles) are not seams.
std::vector<UvSeamEdge> findUvSeams(const Mesh& mesh, std::span<const Vec2f> uvs);

}  // namespace prt
