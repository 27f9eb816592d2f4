#pragma once
// The probe domain of a bake (prt/transfer/probe_grid.hpp), private to src/transport: where its
// rows are integrated (the grid's points), which of them lie inside geometry, and how those are
// refilled from their neighbours. passes.cpp asks it at its dispatch points, as it asks the
// lightmap domain (texel_domain.hpp).
//
// Inside geometry. A probe inside a closed solid (a wall, a table's leg) sees only the backs of
// the surfaces around it and would light a passing object black. Such a probe is found as a
// texel's sample point is (texel_validity.hpp: more than half of a fixed set of rays hit a back
// face), over both hemispheres about +Z: inside when both say so. It is refilled with the mean of
// its 26 neighbours outside geometry, ring by ring (a probe refilled in ring k serves ring k + 1)
// up to kProbeRefillRings, as lightmappers and engines' probe volumes do (Unity's APV
// "invalidity", Godot's SDFGI probes); each ring reads a snapshot of the one before, so the
// result does not depend on the order of the rows, nor on the range a piece of a split bake
// computes (the last pass covers the range widened by the refill's reach).

#include <cstdint>
#include <vector>

#include "bake_common.hpp"
#include "prt/transfer/probe_grid.hpp"

namespace prt::bakedetail {

inline constexpr int kProbeRefillRings = 2;

struct ProbeDomain {
  ProbeGrid grid;
  RowRange kept;                       ///< the rows whose points are kept (the last pass's)
  std::vector<RowPoint> points;        ///< of the kept rows (normal zero: the whole sphere)
  std::vector<std::uint8_t> inside;    ///< per kept row
  std::vector<std::uint32_t> invalid;  ///< rows inside geometry, ascending

  /// Rows one ring of the refill reaches from a row: a neighbour one step along every axis.
  std::size_t reach() const;
  /// `range` widened by kProbeRefillRings rings' reach (within the grid).
  RowRange widen(RowRange range) const;
  /// Refills the rows inside geometry of `values` (rows `rows` ⊆ kept, `stride` floats each)
  /// from their neighbours outside it (see the top). Rows with no such neighbour within the
  /// rings keep their own values.
  void refill(float* values, RowRange rows, std::size_t stride) const;
};

/// The probe domain of `grid`, its points and inside flags for rows `keep`.
ProbeDomain makeProbeDomain(const Mesh& mesh, const Occluder& occluder, const ProbeGrid& grid,
                            RowRange keep);

}  // namespace prt::bakedetail
