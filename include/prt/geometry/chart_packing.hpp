#pragma once
// Packing rectangular charts into the unit square of a lightmap UV set: one scale for every
// chart (the same texel density everywhere), a gutter between charts and around the border so
// that dilation and bilinear filtering never mix two charts. Used for the builtin scenes'
// lightmap UVs; prt unwrap's charts (issue 18) start from their bounding rectangles packed this
// way, then pack by shape (unwrap/atlas_packing.hpp).

#include <span>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt {

struct ChartPacking {
  float scale = 0;             ///< UV units per chart unit, the same for every chart
  std::vector<Vec2f> offsets;  ///< each chart's lower corner in [0, 1]²
  float usedArea = 0;          ///< the charts' share of the unit square (scale² Σ w h)
};

/// Places rectangles of `sizes` (width, height in any unit, each > 0) in [0, 1]² without
/// overlap, `gutter` UV units apart and from the border: shelf packing (tallest first, rows
/// filled left to right), at the largest scale that fits (bisection to 1e-4 relative).
/// Deterministic. Throws prt::Error when a size is not positive and finite or the gutter leaves
/// no room (gutter ≥ 1/2 or more charts than it allows).
ChartPacking packCharts(std::span<const Vec2f> sizes, float gutter);

}  // namespace prt
