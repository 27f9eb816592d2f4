#pragma once
// Which texel sample points lie inside geometry (issue 18): a texel a triangle only partly
// covers, or whose chart runs under another surface (a block standing on a floor), can have
// its sample point where no light reaches — under the block, behind a wall — and would bake
// black, a dark line along every contact in the lightmap. Such a point sees mostly the *backs*
// of the surfaces around it: of kValidityProbeRays rays over its hemisphere (fixed
// cosine-distributed directions, a Fibonacci spiral: deterministic, the same for every texel),
// more than half hit a triangle from behind (against its counter-clockwise front). The bake
// marks those texels invalid and refills them from their valid neighbours (bake_texels.hpp),
// as lightmappers do (Bakery, Unity's and Godot's lightmappers).
//
// Open meshes seen from behind on purpose (a leaf card, a one-sided wall seen through) can be
// marked too; the threshold of "more than half" keeps a point on a thin surface with open sky
// valid.

#include <cstdint>
#include <span>
#include <vector>

#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"

namespace prt {

/// Probe rays per sample point.
inline constexpr int kValidityProbeRays = 32;

/// Per point (with its unit normal): 1 if more than half its probe rays hit a back face.
std::vector<std::uint8_t> insideGeometry(const Mesh& mesh, const Occluder& occluder,
                                         std::span<const Vec3f> positions,
                                         std::span<const Vec3f> normals);

/// Per point in space with no surface of its own (a probe, probe_grid.hpp): 1 if it is inside
/// geometry over both hemispheres about +Z — it sees back faces all around. The one rule for a
/// probe bake's refill and for which probes a validation may compare.
std::vector<std::uint8_t> insideGeometryAllAround(const Mesh& mesh, const Occluder& occluder,
                                                  std::span<const Vec3f> positions);

}  // namespace prt
