#pragma once
// One chart's layout in the plane: whether it is usable (no triangle flipped, no two
// triangles overlapping), its stretch, and its placement on its smallest bounding rectangle
// for packing.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/unwrap/lscm.hpp"

namespace prt {

/// What is wrong with a chart's layout.
enum class LayoutFault { None, Flipped, Overlap };

/// Checks a chart's layout: every triangle with area in 3D (`area3d` > 0) has positive area in
/// the plane (counter-clockwise), and no two triangles' interiors overlap (separating axes,
/// pairs found through a uniform grid over the chart; touching along an edge or at a vertex is
/// no overlap). Flipped is reported before Overlap.
LayoutFault checkChartLayout(std::span<const Uv2> uv,
                             std::span<const std::array<std::uint32_t, 3>> triangles,
                             std::span<const double> area3d);

/// Turns and moves `uv` (a rigid motion) onto its minimum-area bounding rectangle (rotating
/// calipers over the convex hull: one side of that rectangle lies along a hull edge), its lower
/// corner at the origin and its longer side along u. Returns the rectangle's (width, height).
std::array<double, 2> placeOnBoundingRectangle(std::span<Uv2> uv);

}  // namespace prt
