#pragma once
// prtkit's own lightmap atlas (issue 18, `prt unwrap`): no unwrapper library is packaged in
// Debian, so the mesh is unwrapped here, in three steps, each in its own file:
//
//   1. charts grown by normal cone over edge-adjacent triangles, those above a size cut into
//      compact parts (unwrap/charts.hpp);
//   2. each chart flattened by least squares conformal maps (Lévy et al. 2002,
//      unwrap/lscm.hpp) and checked (unwrap/chart_layout.hpp): a chart whose map flips a
//      triangle, overlaps itself or stretches more than a limit (Sander et al. 2001's L2) is
//      cut in two across its longest extent and each part flattened again, down to single
//      triangles, which always lay out;
//   3. the charts scaled to their surface area (one texel density everywhere), turned onto
//      their smallest bounding rectangles, packed by those (geometry/chart_packing.hpp), then
//      by their rasterised shapes into each other's gaps at a larger scale where that fits
//      (unwrap/atlas_packing.hpp), with a gutter.
//
// Vertices on chart boundaries are split (a vertex in two charts needs two lightmap UVs): the
// result is a new mesh with the vertices copied (position, normal, albedo, texture UV) once per
// chart using them, in the input's vertex order, the triangles in theirs.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/unwrap/atlas_stats.hpp"

namespace prt {

struct UnwrapSettings {
  int resolution = 512;        ///< the lightmap side the gutter is measured in (prt bake's default)
  int padding = 2;             ///< texels kept empty between charts (and from the border), ≥ 0
  double maxConeDegrees = 60;  ///< largest angle between a triangle's normal and its chart's mean
  std::uint32_t minChartTriangles = 8;  ///< smaller charts merge into a neighbour where they fit
  /// A chart whose conformal map stretches more than this (Sander's L2, normalised per chart:
  /// atlas_stats.hpp) is cut like one that folds.
  double maxStretch = 1.1;
  /// Charts the normal cone grows larger than this are cut into compact parts of at most this
  /// many triangles before they are flattened (unwrap/charts.hpp boundCharts), as lightmappers
  /// bound their charts: one chart's direct solve grows as t^1.75 (docs/performance.md). The
  /// default is above the largest chart of every mesh the tests and docs unwrap but the big
  /// planes (the dragon's 56k, a subdivided sphere's 82k). 0: unbounded.
  std::uint32_t maxChartTriangles = 100000;
};

struct UnwrapResult {
  Mesh mesh;                                ///< the input with split vertices and lightmapUvs
  std::vector<std::uint32_t> sourceVertex;  ///< per vertex of `mesh`: the input vertex it copies
  std::vector<std::uint32_t> chartOfTriangle;
  std::size_t grownCharts = 0;  ///< charts the normal cone grew, once bounded in size
  std::size_t splitCharts = 0;  ///< cuts made where a conformal map folded or stretched
  /// Packed by the charts' shapes (unwrap/atlas_packing.hpp); false: by their bounding
  /// rectangles, where the shapes' search would take too long (thousands of charts) or found
  /// no room at the rectangles' scale.
  bool packedByShape = false;
  AtlasStats stats;  ///< measured at settings.resolution; `seconds` is the unwrap's
};

/// The memory an unwrap holds at its peak (issue 31), estimated from the structures it allocates
/// per triangle and per vertex once the charts are grown, before any is flattened: the input and
/// output meshes and the per-triangle tables that live through the run (`baseBytes`), plus the
/// least squares conformal maps of the largest charts flattened at once, one per thread
/// (`solveBytes`: the sparse normal equations and their LDLᵀ factor, whose fill grows as
/// t·log₂ t for a chart of t triangles). docs/performance.md compares it with measured peaks.
struct UnwrapFootprint {
  std::size_t triangles = 0, vertices = 0;
  std::size_t charts = 0;        ///< grown charts
  std::size_t largestChart = 0;  ///< triangles of the largest
  std::uint64_t baseBytes = 0, solveBytes = 0;
  std::uint64_t bytes() const { return baseBytes + solveBytes; }
};

/// The footprint of unwrapping `mesh` into charts of `chartTriangles` triangles each, `threads`
/// of them flattened at once.
UnwrapFootprint unwrapFootprint(const Mesh& mesh, std::span<const std::size_t> chartTriangles,
                                int threads);

/// The footprint in one line, as prt unwrap and prt bake (unwrapping a mesh itself) state it:
/// "unwrap: 69666 triangles in 137 charts (the largest 4412 triangles): about 68.5 MB of memory
/// at peak (… of meshes and tables + … for the conformal maps of the largest charts)".
std::string describe(const UnwrapFootprint& f);

/// Called once with the footprint, before the charts are flattened (prt unwrap prints it).
using UnwrapFootprintFn = std::function<void(const UnwrapFootprint&)>;

/// Unwraps `mesh` (see the header comment). Deterministic, independent of the thread count.
/// Throws prt::Error naming mesh.source for a mesh without triangles, settings out of range
/// (resolution 1..kMaxLightmapSide, padding 0..kMaxLightmapPadding, cone in (0°, 90°)), charts
/// that cannot fit the square with that gutter, or a footprint above what this machine's memory
/// allows (fitsInMemory, the bake's policy); Cancelled through `progress`. `progress` runs once
/// from 0 to 1 over every phase (adjacency and charts, flattening, packing, the vertex split,
/// measuring), each phase's share of the fraction its estimated share of the time, so that an
/// ETA drawn from it holds.
UnwrapResult unwrap(const Mesh& mesh, const UnwrapSettings& settings = {},
                    const ProgressFn& progress = {}, const UnwrapFootprintFn& footprint = {});

}  // namespace prt
