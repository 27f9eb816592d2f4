#include "prt/unwrap/unwrap.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/units.hpp"
#include "prt/geometry/chart_packing.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/unwrap/atlas_packing.hpp"
#include "prt/unwrap/chart_layout.hpp"
#include "prt/unwrap/charts.hpp"
#include "prt/unwrap/lscm.hpp"

namespace prt {

namespace {

constexpr std::uint32_t kNone = TriangleAdjacency::kNone;

/// A flattened chart: its triangles (input indices, increasing), their corners as indices into
/// `uv` (one per welded vertex of the chart).
struct Piece {
  std::vector<std::uint32_t> triangles;
  std::vector<std::array<std::uint32_t, 3>> local;
  std::vector<Uv2> uv;
};

/// Sander et al.'s L2 stretch of one chart's layout, normalised by the chart's own area ratio
/// (atlas_stats.hpp has the formula): 1 for a layout that is an isometry up to scale.
double chartStretch(const std::vector<Vec3d>& p,
                    const std::vector<std::array<std::uint32_t, 3>>& tris,
                    const std::vector<Uv2>& uv) {
  double sum3 = 0, sumUv = 0, l2 = 0;
  for (const auto& t : tris) {
    const Vec3d &q1 = p[t[0]], &q2 = p[t[1]], &q3 = p[t[2]];
    const double s1 = uv[t[0]][0], t1 = uv[t[0]][1], s2 = uv[t[1]][0], t2 = uv[t[1]][1];
    const double s3 = uv[t[2]][0], t3 = uv[t[2]][1];
    const double a2 = (s2 - s1) * (t3 - t1) - (s3 - s1) * (t2 - t1);
    const double area3 = 0.5 * length(cross(q2 - q1, q3 - q1));
    if (!(area3 > 0) || !(a2 > 0)) continue;
    const Vec3d Ss = (q1 * (t2 - t3) + q2 * (t3 - t1) + q3 * (t1 - t2)) / a2;
    const Vec3d St = (q1 * (s3 - s2) + q2 * (s1 - s3) + q3 * (s2 - s1)) / a2;
    l2 += (dot(Ss, Ss) + dot(St, St)) / 2 * area3;
    sum3 += area3;
    sumUv += a2 / 2;
  }
  return sum3 > 0 && sumUv > 0 ? std::sqrt(l2 / sum3 * sumUv / sum3) : 1.0;
}

class Flattener {
 public:
  Flattener(const Mesh& mesh, const TriangleAdjacency& adj, double maxStretch)
      : mesh_(mesh), adj_(adj), maxStretch_(maxStretch) {}

  /// Flattens `triangles` (edge-connected) into one or more pieces, appended to `out` in a
  /// fixed order; returns the number of cuts made.
  std::size_t flatten(std::vector<std::uint32_t> triangles, std::vector<Piece>& out) const {
    Piece piece = localise(triangles);
    std::vector<Vec3d> positions(piece.uv.size());
    for (std::size_t t = 0; t < piece.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        positions[piece.local[t][k]] =
            Vec3d(mesh_.positions[mesh_.triangles[piece.triangles[t]][k]]);
    std::vector<double> area3(piece.triangles.size());
    for (std::size_t t = 0; t < area3.size(); ++t) area3[t] = adj_.faceArea[piece.triangles[t]];
    std::vector<Uv2> uv = lscm(positions, piece.local);
    if (triangles.size() == 1 &&
        (uv.empty() || checkChartLayout(uv, piece.local, area3) != LayoutFault::None))
      uv = layOutAlone(positions, piece.local[0]);
    if (!uv.empty() &&
        (triangles.size() == 1 || (checkChartLayout(uv, piece.local, area3) == LayoutFault::None &&
                                   chartStretch(positions, piece.local, uv) <= maxStretch_))) {
      piece.uv = std::move(uv);
      out.push_back(std::move(piece));
      return 0;
    }
    // Cut across the longest extent of the triangles' centroids, at the median (ties by index),
    // and flatten each edge-connected part of either half.
    const std::vector<std::uint32_t> order = orderAcrossLongestExtent(mesh_, triangles);
    const std::size_t half = order.size() / 2;
    std::size_t cuts = 1;
    for (int side = 0; side < 2; ++side) {
      const auto cut = order.begin() + std::ptrdiff_t(half);
      const std::vector<std::uint32_t> part = side == 0
                                                  ? std::vector<std::uint32_t>(order.begin(), cut)
                                                  : std::vector<std::uint32_t>(cut, order.end());
      for (std::vector<std::uint32_t>& c : connectedComponents(adj_, part))
        cuts += flatten(std::move(c), out);
    }
    return cuts;
  }

 private:
  /// The piece's triangles and their corners numbered by welded vertex (first appearance).
  Piece localise(std::vector<std::uint32_t>& triangles) const {
    std::sort(triangles.begin(), triangles.end());
    std::vector<std::uint32_t> welded;
    welded.reserve(3 * triangles.size());
    for (std::uint32_t t : triangles)
      for (std::uint32_t v : mesh_.triangles[t]) welded.push_back(adj_.weldedVertex[v]);
    std::sort(welded.begin(), welded.end());
    welded.erase(std::unique(welded.begin(), welded.end()), welded.end());
    Piece piece;
    piece.triangles = triangles;
    piece.local.resize(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
      for (int k = 0; k < 3; ++k)
        piece.local[i][k] =
            std::uint32_t(std::lower_bound(welded.begin(), welded.end(),
                                           adj_.weldedVertex[mesh_.triangles[triangles[i]][k]]) -
                          welded.begin());
    piece.uv.resize(welded.size());
    return piece;
  }

  /// One triangle in its own plane (an equilateral one of the mesh's scale without area).
  std::vector<Uv2> layOutAlone(const std::vector<Vec3d>& p,
                               const std::array<std::uint32_t, 3>& tri) const {
    std::vector<Uv2> uv(p.size(), Uv2{0, 0});
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) return {};
    const Vec3d e1 = p[tri[1]] - p[tri[0]], e2 = p[tri[2]] - p[tri[0]];
    const double len1 = length(e1), area2 = length(cross(e1, e2));
    if (len1 > 0 && area2 > 1e-12 * len1 * len1) {
      uv[tri[1]] = {len1, 0};
      uv[tri[2]] = {dot(e2, e1) / len1, area2 / len1};
    } else {
      const double s = std::max({len1, length(e2), 1e-6});
      uv[tri[1]] = {s, 0};
      uv[tri[2]] = {s / 2, s * std::sqrt(3.0) / 2};
    }
    return uv;
  }

  const Mesh& mesh_;
  const TriangleAdjacency& adj_;
  double maxStretch_;
};

/// The unwrap's progress over all its phases, as one fraction that never goes back (issue 31).
/// Each phase is given its estimated share of the time (costs in about nanoseconds on one core,
/// measured on planes, icospheres and the Stanford dragon: docs/performance.md), so that the
/// fraction moves with the clock and an ETA drawn from it holds.
class PhasedProgress {
 public:
  explicit PhasedProgress(const ProgressFn& fn) : fn_(fn) {}
  /// The costs of the phases still to come, in order: they share what remains of the fraction.
  void plan(std::vector<double> costs) {
    costs_ = std::move(costs);
    next_ = 0;
    origin_ = last_;
    double total = 0;
    for (double c : costs_) total += c;
    total_ = total > 0 ? total : 1;
    spent_ = 0;
  }
  /// A ProgressFn for the next planned phase (mapping its 0..1 into its share).
  ProgressFn phase() {
    const double lo = origin_ + (1 - origin_) * spent_ / total_;
    const double c = next_ < costs_.size() ? costs_[next_] : 0;
    spent_ += c;
    ++next_;
    const double hi = origin_ + (1 - origin_) * std::min(spent_ / total_, 1.0);
    return [this, lo, hi](double f) { return forward(lo + (hi - lo) * std::clamp(f, 0.0, 1.0)); };
  }
  /// Reports `f` of the whole run directly (a phase before the plan); throws Cancelled on a
  /// request to stop.
  void report(double f) {
    if (!forward(f)) throw Cancelled();
  }
  /// The end of a phase that reported through phase(): its whole share is done.
  void finish(const ProgressFn& p) {
    if (p && !p(1.0)) throw Cancelled();
  }

 private:
  bool forward(double f) {
    if (cancelRequested()) return false;
    if (!(f > last_)) return true;  // never back, never the same twice
    last_ = f;
    return fn_ ? fn_(f) : true;
  }
  ProgressFn fn_;
  std::vector<double> costs_;
  std::size_t next_ = 0;
  double origin_ = 0, last_ = 0, total_ = 1, spent_ = 0;
};

/// The estimated time, in about nanoseconds on one core, of flattening a chart of t triangles:
/// assembly and checks grow as t, the sparse LDLᵀ factorisation (AMD ordering) as about t^1.75
/// (measured on one chart of a plane: 125k triangles 2.4 s, 500k triangles 28 s).
double flattenCost(std::size_t t) {
  const double x = double(t);
  return 2e3 * x + 3.0 * std::pow(x, 1.75);
}

/// The estimated time of the packing, in about nanoseconds: the rectangles' packing, then the
/// search by shape, which stops at its cap of steps (unwrap/atlas_packing.cpp, about 2.5 s);
/// measured 0.18 s for 7 charts, 0.6 s for the dragon's 3,686 (6,338 once cut).
double packingCost(std::size_t charts) {
  return std::min(1.5e8 + 1.2e5 * double(charts), 2.5e9);
}

void checkSettings(const Mesh& mesh, const UnwrapSettings& s) {
  if (mesh.triangleCount() == 0) throw Error(mesh.source, "has no triangles to unwrap");
  if (s.resolution < 1 || s.resolution > kMaxLightmapSide)
    throw Error(mesh.source, "unwrap: a resolution of " + std::to_string(s.resolution) +
                                 " is outside 1.." + std::to_string(kMaxLightmapSide));
  if (s.padding < 0 || s.padding > kMaxLightmapPadding)
    throw Error(mesh.source, "unwrap: a padding of " + std::to_string(s.padding) +
                                 " texels is outside 0.." + std::to_string(kMaxLightmapPadding));
  if (!(s.maxStretch >= 1))
    throw Error(mesh.source, "unwrap: a stretch limit of " + std::to_string(s.maxStretch) +
                                 " is below 1, the least any layout has");
  if (!(s.maxConeDegrees > 0 && s.maxConeDegrees < 90))
    throw Error(mesh.source, "unwrap: a cone of " + std::to_string(s.maxConeDegrees) +
                                 " degrees is outside (0, 90)");
}

}  // namespace

UnwrapFootprint unwrapFootprint(const Mesh& mesh, std::span<const std::size_t> chartTriangles,
                                int threads) {
  UnwrapFootprint f;
  const std::uint64_t T = mesh.triangleCount(), V = mesh.vertexCount();
  f.triangles = T;
  f.vertices = V;
  f.charts = chartTriangles.size();
  // Bytes per vertex of the input and of the output (whose split vertices are bounded here by
  // 1.5 V: 1.44 V on the Stanford dragon's 6,338 charts, 1.01-1.05 V on smooth meshes).
  const std::uint64_t attributes =
      (mesh.normals.empty() ? 0 : 12) + (mesh.hasAlbedo() ? 12 : 0) + (mesh.uvs.empty() ? 0 : 8);
  const std::uint64_t Vout = V + V / 2;
  const std::uint64_t input = V * (12 + attributes + (mesh.lightmapUvs.empty() ? 0 : 8)) + 12 * T;
  const std::uint64_t output = Vout * (12 + attributes + 8 + 4) + (12 + 4) * T;
  // Live through the run: the adjacency (welded vertex; face normal, area, neighbours), the
  // charts and their pieces (triangles, corners, UVs) and the packing's copy of their shapes,
  // the corner UVs, the (vertex, chart) uses, and measureAtlas's per-triangle records; then the
  // output mesh and the GLB's buffer of it.
  const std::uint64_t adjacency = 4 * V + 44 * T;
  const std::uint64_t charts = 8 * T + 2 * (16 * T + 16 * Vout);
  const std::uint64_t assembly = 24 * T + 8 * (3 * T + V) + V + 48 * T;
  f.baseBytes = input + adjacency + charts + assembly + 2 * output;
  // The conformal maps in flight: the `threads` largest charts. Per chart of t triangles and
  // v ≈ t/2 vertices: the piece (36 t + 40 v), the normal equations AᵀA (2v unknowns, 2×2
  // blocks over each vertex and its ~6 neighbours: 28 v entries of 12 bytes) with their
  // permuted upper half (15 v entries), and the LDLᵀ factor, kFill·log₂ v entries per vertex
  // under Eigen's AMD ordering (a 2D mesh's fill grows as v log v; kFill fitted to measured
  // peaks of one-chart planes of 125k, 500k and 2M triangles: 1.49, 1.45 and 1.75 kB per
  // triangle).
  constexpr double kFill = 12;
  std::vector<std::size_t> sizes(chartTriangles.begin(), chartTriangles.end());
  const std::size_t inFlight =
      std::min<std::size_t>(sizes.size(), std::size_t(std::max(threads, 1)));
  std::partial_sort(sizes.begin(), sizes.begin() + std::ptrdiff_t(inFlight), sizes.end(),
                    std::greater<>());
  f.largestChart = sizes.empty() ? 0 : sizes.front();
  for (std::size_t i = 0; i < inFlight; ++i) {
    const double t = double(sizes[i]), v = t / 2 + 3;
    const double entries = 28 * v + 15 * v + kFill * v * std::log2(v);
    f.solveBytes += std::uint64_t(36 * t + 40 * v + 12 * entries + 64 * v);
  }
  return f;
}

UnwrapResult unwrap(const Mesh& mesh, const UnwrapSettings& settings, const ProgressFn& progress,
                    const UnwrapFootprintFn& onFootprint) {
  checkSettings(mesh, settings);
  const auto start = std::chrono::steady_clock::now();
  const std::size_t T = mesh.triangleCount();
  // Progress: the adjacency and the charts (about 1.2 µs a triangle) come before the plan of the
  // rest is known, and are reported, once done, as their share of the whole; the vertex split
  // and the measures take about 0.5 µs a triangle each.
  PhasedProgress phases(progress);
  const double kGrowCost = 1.2e3, kSplitCost = 0.5e3, kMeasureCost = 0.45e3;
  const TriangleAdjacency adj = buildAdjacency(mesh);
  const ChartSegmentation seg = boundCharts(
      mesh, adj,
      growCharts(adj, settings.maxConeDegrees * M_PI / 180.0, settings.minChartTriangles),
      settings.maxChartTriangles);
  std::vector<std::vector<std::uint32_t>> grown(seg.count);
  for (std::uint32_t t = 0; t < T; ++t) grown[seg.chartOfTriangle[t]].push_back(t);

  // The footprint, now that the charts are known and before the heavy work: the caller's
  // statement, then the bake's policy (prt/core/limits.hpp).
  std::vector<std::size_t> chartSizes(seg.count);
  for (std::size_t c = 0; c < seg.count; ++c) chartSizes[c] = grown[c].size();
  const UnwrapFootprint footprint = unwrapFootprint(mesh, chartSizes, maxThreads());
  if (onFootprint) onFootprint(footprint);
  if (!fitsInMemory(footprint.bytes()))
    throw Error(mesh.source,
                "unwrap: needs about " + bytesText(footprint.bytes()) + " (" + std::to_string(T) +
                    " triangles, the largest chart " + std::to_string(footprint.largestChart) +
                    "); this machine has " + bytesText(physicalMemoryBytes()) +
                    " (fewer threads with -j, a smaller --max-chart-triangles or --max-cone, or a "
                    "simplified mesh)");

  // The plan of the rest, each phase's estimated cost: flattening (per chart, superlinear in its
  // size, the charts spread over the threads), packing, the vertex split, measuring.
  double flattenTotal = 0;
  for (std::size_t t : chartSizes) flattenTotal += flattenCost(t);
  const double threads = std::min<double>(maxThreads(), double(seg.count));
  const double largest = flattenCost(footprint.largestChart);
  const double flattenWall = std::max(flattenTotal / std::max(threads, 1.0), largest);
  const double packCost = packingCost(seg.count);
  const double grownCost = kGrowCost * double(T);
  phases.report(grownCost / (grownCost + flattenWall + packCost + (kSplitCost + kMeasureCost) * T));
  phases.plan({flattenWall, packCost, kSplitCost * double(T), kMeasureCost * double(T)});

  // Flatten the charts in parallel; each chart's pieces are kept in their own slot, so the
  // order of the result does not depend on the threads. Progress counts each chart's cost.
  const Flattener flattener(mesh, adj, settings.maxStretch);
  std::vector<std::vector<Piece>> pieces(seg.count);
  std::vector<std::size_t> cuts(seg.count, 0);
  {
    const ProgressFn flattenPhase = phases.phase();
    // Units of 1/4096 of the total cost (Progress counts integers).
    const double unit = std::max(flattenTotal / 4096.0, 1.0);
    std::size_t totalUnits = 0;
    std::vector<std::size_t> units(seg.count);
    for (std::size_t c = 0; c < seg.count; ++c)
      totalUnits += units[c] = std::size_t(std::ceil(flattenCost(chartSizes[c]) / unit));
    Progress prog(flattenPhase, totalUnits);
    // The largest charts first, so that the threads finish together; the result does not
    // depend on the order.
    std::vector<std::size_t> order(seg.count);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return chartSizes[a] > chartSizes[b]; });
    parallelFor(seg.count, 1, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        const std::size_t c = order[i];
        prog.check();
        cuts[c] = flattener.flatten(grown[c], pieces[c]);
        prog.advance(units[c]);
      }
    });
    prog.check();
    phases.finish(flattenPhase);
  }

  // One texel density: scale each piece to its surface area, then its bounding rectangle.
  std::vector<Piece> charts;
  for (auto& list : pieces)
    for (Piece& p : list) charts.push_back(std::move(p));
  double totalArea = 0;
  for (double a : adj.faceArea) totalArea += a;
  const double minSide = 1e-6 * std::sqrt(std::max(totalArea, 1e-300) / double(T));
  std::vector<Vec2f> sizes(charts.size());
  std::vector<ChartShape> shapes(charts.size());
  for (std::size_t c = 0; c < charts.size(); ++c) {
    Piece& p = charts[c];
    double area3 = 0, areaUv = 0;
    for (std::size_t i = 0; i < p.triangles.size(); ++i) {
      area3 += adj.faceArea[p.triangles[i]];
      const Uv2 &a = p.uv[p.local[i][0]], &b = p.uv[p.local[i][1]], &d = p.uv[p.local[i][2]];
      areaUv += 0.5 * std::abs((b[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (b[1] - a[1]));
    }
    const double scale = area3 > 0 && areaUv > 0 ? std::sqrt(area3 / areaUv) : 1.0;
    for (Uv2& q : p.uv) q = {q[0] * scale, q[1] * scale};
    const std::array<double, 2> size = placeOnBoundingRectangle(p.uv);
    sizes[c] = {float(std::max(size[0], minSide)), float(std::max(size[1], minSide))};
    shapes[c] = {p.uv, p.local, size[0], size[1]};
  }
  // The gutter: padding + 1 texels between rectangles leave at least `padding` texels that no
  // chart touches between any two (a chart's last touched texel and the next one's first are
  // floor(gutter) apart), and as many from the border.
  const double gutter = (settings.padding + 1 + 1e-3) / double(settings.resolution);
  const ProgressFn packPhase = phases.phase();
  ChartPacking packing;
  try {
    packing = packCharts(sizes, float(gutter));
  } catch (const Error& e) {
    throw Error(mesh.source, std::string("unwrap: ") + e.what() + " (" +
                                 std::to_string(charts.size()) + " charts at a resolution of " +
                                 std::to_string(settings.resolution) + " with a padding of " +
                                 std::to_string(settings.padding) +
                                 "; raise the resolution or lower the padding)");
  }

  // Then by their shapes (unwrap/atlas_packing.hpp), from the rectangles' scale up to the one at
  // which the charts would fill the square; the rectangles stand where the shapes do not fit.
  const double side = settings.resolution;
  AtlasPacking shaped;
  const bool byShape = packChartShapes(shapes, settings.resolution, settings.padding,
                                       double(packing.scale) * side, shaped, packPhase);
  phases.finish(packPhase);
  const ProgressFn splitPhase = phases.phase();
  const auto atlasUv = [&](std::size_t c, const Uv2& q) {
    if (byShape) {
      const Uv2 t = shaped.texelPosition(shapes, c, q);
      return Vec2f{std::clamp(float(t[0] / side), 0.0f, 1.0f),
                   std::clamp(float(t[1] / side), 0.0f, 1.0f)};
    }
    const Vec2f o = packing.offsets[c];
    return Vec2f{std::clamp(float(o.x + double(packing.scale) * q[0]), 0.0f, 1.0f),
                 std::clamp(float(o.y + double(packing.scale) * q[1]), 0.0f, 1.0f)};
  };

  // Corner UVs in the square, and each triangle's chart.
  UnwrapResult r;
  r.grownCharts = seg.count;
  r.packedByShape = byShape;
  for (std::size_t c : cuts) r.splitCharts += c;
  r.chartOfTriangle.assign(T, kNone);
  std::vector<std::array<Vec2f, 3>> cornerUv(T);
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const Piece& p = charts[c];
    for (std::size_t i = 0; i < p.triangles.size(); ++i) {
      const std::uint32_t t = p.triangles[i];
      r.chartOfTriangle[t] = std::uint32_t(c);
      for (int k = 0; k < 3; ++k) cornerUv[t][k] = atlasUv(c, p.uv[p.local[i][k]]);
    }
  }

  // Split vertices: one per (input vertex, chart using it), in input order; a vertex no
  // triangle uses is kept once, at (0, 0).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> uses;
  uses.reserve(3 * T + mesh.vertexCount());
  std::vector<std::uint8_t> used(mesh.vertexCount(), 0);
  for (std::uint32_t t = 0; t < T; ++t)
    for (std::uint32_t v : mesh.triangles[t]) {
      uses.push_back({v, r.chartOfTriangle[t]});
      used[v] = 1;
    }
  for (std::uint32_t v = 0; v < mesh.vertexCount(); ++v)
    if (!used[v]) uses.push_back({v, kNone});
  std::sort(uses.begin(), uses.end());
  uses.erase(std::unique(uses.begin(), uses.end()), uses.end());
  const auto indexOf = [&](std::uint32_t v, std::uint32_t c) {
    return std::uint32_t(std::lower_bound(uses.begin(), uses.end(), std::make_pair(v, c)) -
                         uses.begin());
  };
  Mesh& out = r.mesh;
  out.source = mesh.source;
  out.gloss = mesh.gloss;
  out.baseColour = mesh.baseColour;  // read at `uvs`, which each split vertex keeps
  const std::size_t V = uses.size();
  out.positions.resize(V);
  if (!mesh.normals.empty()) out.normals.resize(V);
  if (mesh.hasAlbedo()) out.albedo.resize(V);
  if (!mesh.uvs.empty()) out.uvs.resize(V);
  out.lightmapUvs.assign(V, Vec2f{0, 0});
  r.sourceVertex.resize(V);
  for (std::size_t i = 0; i < V; ++i) {
    const std::uint32_t v = uses[i].first;
    r.sourceVertex[i] = v;
    out.positions[i] = mesh.positions[v];
    if (v < mesh.normals.size()) out.normals[i] = mesh.normals[v];
    if (mesh.hasAlbedo()) out.albedo[i] = mesh.albedo[v];
    if (!mesh.uvs.empty()) out.uvs[i] = mesh.uvs[v];
  }
  out.triangles.resize(T);
  for (std::uint32_t t = 0; t < T; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = indexOf(mesh.triangles[t][k], r.chartOfTriangle[t]);
      out.triangles[t][k] = i;
      out.lightmapUvs[i] = cornerUv[t][k];
    }
  // Parts: the same triangles; their vertices are the copies of theirs, still contiguous.
  for (const MeshPart& p : mesh.parts) {
    MeshPart q = p;
    q.firstVertex = indexOf(p.firstVertex, 0);
    q.vertexCount = indexOf(p.firstVertex + p.vertexCount, 0) - q.firstVertex;
    out.parts.push_back(q);
  }
  phases.finish(splitPhase);
  const ProgressFn measurePhase = phases.phase();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.stats = measureAtlas(out, out.lightmapUvs, settings.resolution);
  phases.finish(measurePhase);
  r.stats.seconds = seconds;
  return r;
}

std::string describe(const UnwrapFootprint& f) {
  return "unwrap: " + std::to_string(f.triangles) + " triangles in " + std::to_string(f.charts) +
         " charts (the largest " + std::to_string(f.largestChart) + " triangles): about " +
         bytesText(f.bytes()) + " of memory at peak (" + bytesText(f.baseBytes) +
         " of meshes and tables + " + bytesText(f.solveBytes) +
         " for the conformal maps of the largest charts)";
}

}  // namespace prt
