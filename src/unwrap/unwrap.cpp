#include "prt/unwrap/unwrap.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
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
    std::vector<Vec3d> centroid(triangles.size());
    Vec3d lo(HUGE_VAL), hi(-HUGE_VAL);
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      const auto& tri = mesh_.triangles[triangles[i]];
      centroid[i] = (Vec3d(mesh_.positions[tri[0]]) + Vec3d(mesh_.positions[tri[1]]) +
                     Vec3d(mesh_.positions[tri[2]])) /
                    3.0;
      lo = min(lo, centroid[i]);
      hi = max(hi, centroid[i]);
    }
    const Vec3d ext = hi - lo;
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
    std::vector<std::pair<double, std::uint32_t>> key(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i) key[i] = {centroid[i][axis], triangles[i]};
    std::sort(key.begin(), key.end());
    const std::size_t half = key.size() / 2;
    std::size_t cuts = 1;
    for (int side = 0; side < 2; ++side) {
      std::vector<std::uint32_t> part;
      for (std::size_t i = side == 0 ? 0 : half; i < (side == 0 ? half : key.size()); ++i)
        part.push_back(key[i].second);
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

UnwrapResult unwrap(const Mesh& mesh, const UnwrapSettings& settings, const ProgressFn& progress) {
  checkSettings(mesh, settings);
  const auto start = std::chrono::steady_clock::now();
  const std::size_t T = mesh.triangleCount();
  const TriangleAdjacency adj = buildAdjacency(mesh);
  const ChartSegmentation seg =
      growCharts(adj, settings.maxConeDegrees * M_PI / 180.0, settings.minChartTriangles);
  std::vector<std::vector<std::uint32_t>> grown(seg.count);
  for (std::uint32_t t = 0; t < T; ++t) grown[seg.chartOfTriangle[t]].push_back(t);

  // Flatten the charts in parallel; each chart's pieces are kept in their own slot, so the
  // order of the result does not depend on the threads.
  const Flattener flattener(mesh, adj, settings.maxStretch);
  std::vector<std::vector<Piece>> pieces(seg.count);
  std::vector<std::size_t> cuts(seg.count, 0);
  Progress prog(progress, seg.count);
  parallelFor(seg.count, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = b; c < e; ++c) {
      prog.check();
      cuts[c] = flattener.flatten(grown[c], pieces[c]);
      prog.advance(1);
    }
  });
  prog.check();

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
                                       double(packing.scale) * side, shaped);
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
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.stats = measureAtlas(out, out.lightmapUvs, settings.resolution);
  r.stats.seconds = seconds;
  return r;
}

}  // namespace prt
