#pragma once
// An object placed in a probe grid (issue 32): what an engine lights through the grid as it
// moves — prt render's --object and prt view's moving object, placed by one rule.

#include "prt/geometry/mesh.hpp"
#include "prt/transfer/probe_grid.hpp"

namespace prt::render {

/// The box the grid's probes span (its first probe to its last).
Bounds probeGridBounds(const ProbeGrid& grid);
/// Where an object goes by default: the grid's centre.
Vec3f defaultObjectPosition(const ProbeGrid& grid);
/// How large it is by default along its largest side: a fifth of the grid's largest side (the
/// cells' included).
float defaultObjectSize(const ProbeGrid& grid);
/// `object` scaled to `size` along its largest side, the centre of its bounds moved to `at`.
Mesh placeObject(Mesh object, const Vec3f& at, float size);

}  // namespace prt::render
