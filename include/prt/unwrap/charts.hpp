#pragma once
// Charts grown by normal cone (issue 18, `prt unwrap`): the mesh is cut into charts of
// edge-connected triangles whose normals stay within a cone around the chart's mean normal, so
// that each chart is nearly a height field over its mean plane and flattens with little
// distortion (Lévy, Petitjean, Ray & Maillot 2002, §4 grow charts from seeds by a similar
// criterion; Sander, Snyder, Gortler & Hoppe 2001 merge charts by planarity).
//
// Topology is that of the positions: vertices the file split (by normal or texture seams) are
// welded by exact position, so a chart may cross such a seam; charts never cross a mesh part,
// a non-manifold edge (three or more triangles) or an edge whose two triangles disagree in
// orientation.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/geometry/mesh.hpp"

namespace prt {

/// Triangle adjacency over welded positions.
struct TriangleAdjacency {
  std::vector<std::uint32_t> weldedVertex;  ///< per vertex: the first vertex at its position
                                            ///< in its part (its representative)
  /// Per triangle and edge k (corners k → k+1): the triangle across it, or kNone.
  std::vector<std::array<std::uint32_t, 3>> neighbour;
  std::vector<Vec3d> faceNormal;  ///< unit, (0, 0, 0) for a triangle without area
  std::vector<double> faceArea;
  static constexpr std::uint32_t kNone = 0xffffffffu;
};

/// Builds the adjacency of `mesh` (see the header comment). Deterministic.
TriangleAdjacency buildAdjacency(const Mesh& mesh);

/// Charts of the triangles: chartOfTriangle[t] in 0..count−1.
struct ChartSegmentation {
  std::vector<std::uint32_t> chartOfTriangle;
  std::uint32_t count = 0;
};

/// Grows charts: seeded at the lowest-numbered triangle not yet in a chart, a chart takes the
/// edge neighbour whose normal is closest to its area-weighted mean normal first (a priority
/// queue), as long as the angle between them stays below `maxConeRadians`; triangles without
/// area join whichever chart reaches them. Charts of fewer than `minTriangles` triangles are
/// then merged into the neighbour they share the longest edge with, when all their triangles
/// lie within the cone of its mean normal widened by half. Deterministic.
ChartSegmentation growCharts(const TriangleAdjacency& adjacency, double maxConeRadians,
                             std::uint32_t minTriangles = 8);

/// Bounds the charts' size (issue 31): each chart of more than `maxTriangles` triangles is cut,
/// as the flattening cuts a chart that folds (unwrap.cpp), across the longest extent of its
/// triangles' centroids, into k = ⌈t / maxTriangles⌉ shares (⌊k/2⌋ : ⌈k/2⌉ of them on either
/// side, ties by triangle index), each edge-connected part of a side cut again while above the
/// bound: compact parts of at most `maxTriangles` triangles, so that no direct solve is larger
/// (its time grows as t^1.75). 0 bounds nothing; a segmentation within the bound is returned
/// unchanged, else renumbered in order of each chart's first triangle. Deterministic.
ChartSegmentation boundCharts(const Mesh& mesh, const TriangleAdjacency& adjacency,
                              ChartSegmentation segmentation, std::uint32_t maxTriangles);

/// `triangles` ordered across the longest extent of their centroids (the axis of the bounding
/// box's longest side; ties by triangle index): the first `lower` are one side of a cut there,
/// the rest the other. The one cut of the unwrap, where a flattened chart folds or stretches (at
/// the median) and where boundCharts cuts an oversized one.
std::vector<std::uint32_t> orderAcrossLongestExtent(const Mesh& mesh,
                                                    std::span<const std::uint32_t> triangles);

/// The edge-connected components of `triangles` (adjacency restricted to the set), each in
/// increasing triangle order, the components ordered by their first triangle.
std::vector<std::vector<std::uint32_t>> connectedComponents(
    const TriangleAdjacency& adjacency, std::span<const std::uint32_t> triangles);

}  // namespace prt
