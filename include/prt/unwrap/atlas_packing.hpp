#pragma once
// Packing flattened charts by their rasterised shapes (issue 18, `prt unwrap`): each chart is
// rasterised conservatively at the lightmap's texel grid, in four quarter turns, and placed
// bottom-left-first into the W × W texels where its texels, grown by the padding, meet no texel
// of a chart already placed — so a chart sits in another's concavity, which packing bounding
// rectangles (geometry/chart_packing.hpp) cannot do. One scale for every chart (one texel
// density), the largest for which the greedy placement fits, found by bisection.
//
// The idea is the raster packers of lightmap tools (xatlas's "brute force" packing, after
// Lévy et al. 2002, §5, who pack charts "Tetris-like" by their horizons); the search here is
// ours: each atlas row keeps, per texel, the length of the free or occupied run starting there,
// so a candidate position is tested in O(1) per run of the chart's rows and a collision skips
// to the end of the occupied run it hit.
//
// Guarantees, for any positions: chart texels (every texel a triangle touches, borders
// included) of two charts are more than `padding` texels apart in x or in y (at least `padding`
// empty texels between, as dilation needs), and at least `padding` texels from the border.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/core/progress.hpp"

#include "prt/unwrap/lscm.hpp"

namespace prt {

/// One chart to pack: its layout in chart units (lower corner of its bounding box at the
/// origin, chart_layout.hpp's placeOnBoundingRectangle) and its triangles.
struct ChartShape {
  std::span<const Uv2> uv;
  std::span<const std::array<std::uint32_t, 3>> triangles;
  double width = 0, height = 0;  ///< the bounding box, ≥ 0
};

/// Where the packer put each chart: its raster (the cells k·q covers, with a small margin)
/// turned a number of quarter turns counter-clockwise, cell for cell, its lower corner at cell
/// (x, y) of the atlas (texelPosition says where a point lands). A cell is one texel up to
/// 1024² texels and `cell` × `cell` texels above: the search costs about the grid's area.
struct AtlasPacking {
  double texelsPerUnit = 0;  ///< k, the same for every chart
  struct Placement {
    int x = 0, y = 0;      ///< the turned raster's lower corner, in texels
    int quarterTurns = 0;  ///< 0..3
  };
  std::vector<Placement> charts;  ///< in cells
  int cell = 1;      ///< texels a side of a packing cell (above 1024² texels, several)
  int rowsUsed = 0;  ///< texel rows up to the highest chart's grown texels

  /// Chart c's point q in texel coordinates of the atlas (divide by the side for UVs).
  Uv2 texelPosition(const std::vector<ChartShape>& shapes, std::size_t c, const Uv2& q) const;
};

/// Packs `charts` into `side` × `side` texels with `padding` texels between charts and from the
/// border, at the largest texels-per-unit (to 0.2%) at which the greedy placement fits, from
/// minTexelsPerUnit up to the one at which the charts' area would fill the square.
/// Deterministic. Returns false (leaving `out` untouched) when it does not fit even at
/// minTexelsPerUnit. `progress` hears after each scale tried: the larger of the passes made
/// over the bisection's count and the steps spent over the search's cap.
bool packChartShapes(const std::vector<ChartShape>& charts, int side, int padding,
                     double minTexelsPerUnit, AtlasPacking& out, const ProgressFn& progress = {});

}  // namespace prt
