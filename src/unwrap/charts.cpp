#include "prt/unwrap/charts.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <tuple>
#include <utility>

namespace prt {

namespace {

constexpr std::uint32_t kNone = TriangleAdjacency::kNone;

/// Relabels the charts (labels below `labels`) in order of each chart's first triangle.
void renumberByFirstTriangle(ChartSegmentation& seg, std::uint32_t labels) {
  std::vector<std::uint32_t> renumber(labels, kNone);
  std::uint32_t next = 0;
  for (std::uint32_t& chart : seg.chartOfTriangle) {
    std::uint32_t& r = renumber[chart];
    if (r == kNone) r = next++;
    chart = r;
  }
  seg.count = next;
}

/// Part index of every vertex (one part for a mesh without parts).
std::vector<std::uint32_t> partOfVertex(const Mesh& mesh) {
  std::vector<std::uint32_t> part(mesh.vertexCount(), 0);
  for (std::size_t p = 0; p < mesh.parts.size(); ++p)
    for (std::uint32_t v = mesh.parts[p].firstVertex;
         v < mesh.parts[p].firstVertex + mesh.parts[p].vertexCount && v < part.size(); ++v)
      part[v] = std::uint32_t(p);
  return part;
}

}  // namespace

TriangleAdjacency buildAdjacency(const Mesh& mesh) {
  const std::size_t V = mesh.vertexCount(), T = mesh.triangleCount();
  TriangleAdjacency adj;
  // Weld by exact position within a part: sort by (part, x, y, z), the lowest index represents.
  const std::vector<std::uint32_t> part = partOfVertex(mesh);
  std::vector<std::uint32_t> order(V);
  std::iota(order.begin(), order.end(), 0u);
  const auto key = [&](std::uint32_t v) {
    const Vec3f& p = mesh.positions[v];
    return std::make_tuple(part[v], p.x, p.y, p.z);
  };
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const auto ka = key(a), kb = key(b);
    return ka != kb ? ka < kb : a < b;
  });
  adj.weldedVertex.resize(V);
  for (std::size_t i = 0; i < V;) {
    std::size_t j = i;
    while (j < V && key(order[j]) == key(order[i])) ++j;
    for (std::size_t k = i; k < j; ++k) adj.weldedVertex[order[k]] = order[i];
    i = j;
  }
  // Face normals and areas, in double.
  adj.faceNormal.resize(T);
  adj.faceArea.resize(T);
  for (std::size_t t = 0; t < T; ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3d a(mesh.positions[tri[0]]), b(mesh.positions[tri[1]]), c(mesh.positions[tri[2]]);
    const Vec3d n = cross(b - a, c - a);
    const double len = length(n);
    adj.faceArea[t] = 0.5 * len;
    adj.faceNormal[t] = len > 0 && std::isfinite(len) ? n / len : Vec3d(0.0);
  }
  // Edges: (lower, upper welded vertex, triangle, corner); two uses in opposite directions make
  // an interior edge, anything else a boundary.
  struct EdgeUse {
    std::uint32_t lo, hi, t, k;
    bool forward;
  };
  std::vector<EdgeUse> uses;
  uses.reserve(3 * T);
  for (std::uint32_t t = 0; t < T; ++t)
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t a = adj.weldedVertex[mesh.triangles[t][k]];
      const std::uint32_t b = adj.weldedVertex[mesh.triangles[t][(k + 1) % 3]];
      if (a == b) continue;
      uses.push_back({std::min(a, b), std::max(a, b), t, k, a < b});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.lo, x.hi, x.t, x.k) < std::tie(y.lo, y.hi, y.t, y.k);
  });
  adj.neighbour.assign(T, {kNone, kNone, kNone});
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
    if (j - i == 2 && uses[i].t != uses[i + 1].t && uses[i].forward != uses[i + 1].forward) {
      adj.neighbour[uses[i].t][uses[i].k] = uses[i + 1].t;
      adj.neighbour[uses[i + 1].t][uses[i + 1].k] = uses[i].t;
    }
    i = j;
  }
  return adj;
}

ChartSegmentation growCharts(const TriangleAdjacency& adj, double maxConeRadians,
                             std::uint32_t minTriangles) {
  const std::size_t T = adj.neighbour.size();
  const double cosMax = std::cos(maxConeRadians);
  ChartSegmentation seg;
  seg.chartOfTriangle.assign(T, kNone);
  std::vector<Vec3d> sum;  // per chart: Σ area · normal
  const auto direction = [](const Vec3d& s, const Vec3d& fallback) {
    const double len = length(s);
    return len > 0 ? s / len : fallback;
  };
  // Lowest cost first; ties by triangle index.
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  for (std::uint32_t seed = 0; seed < T; ++seed) {
    if (seg.chartOfTriangle[seed] != kNone) continue;
    const std::uint32_t c = seg.count++;
    Vec3d s(0.0);
    heap.push({0.0, seed});
    while (!heap.empty()) {
      const std::uint32_t t = heap.top().second;
      heap.pop();
      if (seg.chartOfTriangle[t] != kNone) continue;
      const Vec3d& n = adj.faceNormal[t];
      const bool hasArea = adj.faceArea[t] > 0 && dot(n, n) > 0;
      if (hasArea && dot(s, s) > 0 && dot(n, direction(s, n)) < cosMax) continue;
      seg.chartOfTriangle[t] = c;
      if (hasArea) s += n * adj.faceArea[t];
      const Vec3d mean = direction(s, n);
      for (std::uint32_t u : adj.neighbour[t])
        if (u != kNone && seg.chartOfTriangle[u] == kNone)
          heap.push({1.0 - dot(adj.faceNormal[u], mean), u});
    }
    sum.push_back(s);
  }
  if (minTriangles <= 1 || seg.count <= 1) return seg;

  // Merge small charts: smallest first (ties by chart index) into the neighbour chart sharing
  // the most edges, when every triangle of the small chart is within the widened cone of the
  // neighbour's mean normal.
  const double cosMerge = std::cos(std::min(1.5 * maxConeRadians, 85.0 * M_PI / 180.0));
  std::vector<std::vector<std::uint32_t>> members(seg.count);
  for (std::uint32_t t = 0; t < T; ++t) members[seg.chartOfTriangle[t]].push_back(t);
  std::vector<std::uint32_t> small;
  for (std::uint32_t c = 0; c < seg.count; ++c)
    if (members[c].size() < minTriangles) small.push_back(c);
  std::stable_sort(small.begin(), small.end(), [&](std::uint32_t a, std::uint32_t b) {
    return members[a].size() < members[b].size();
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> shared;  // (chart, edges)
  for (std::uint32_t c : small) {
    if (members[c].empty() || members[c].size() >= minTriangles) continue;
    shared.clear();
    for (std::uint32_t t : members[c])
      for (std::uint32_t u : adj.neighbour[t]) {
        if (u == kNone) continue;
        const std::uint32_t d = seg.chartOfTriangle[u];
        if (d == c) continue;
        auto it =
            std::find_if(shared.begin(), shared.end(), [d](const auto& e) { return e.first == d; });
        if (it == shared.end())
          shared.push_back({d, 1});
        else
          ++it->second;
      }
    std::stable_sort(shared.begin(), shared.end(), [](const auto& a, const auto& b) {
      return a.second != b.second ? a.second > b.second : a.first < b.first;
    });
    for (const auto& [d, edges] : shared) {
      const Vec3d mean = direction(sum[d], Vec3d(0.0));
      const bool fits = std::all_of(members[c].begin(), members[c].end(), [&](std::uint32_t t) {
        return !(adj.faceArea[t] > 0) || dot(adj.faceNormal[t], mean) >= cosMerge;
      });
      if (!fits) continue;
      for (std::uint32_t t : members[c]) seg.chartOfTriangle[t] = d;
      members[d].insert(members[d].end(), members[c].begin(), members[c].end());
      members[c].clear();
      sum[d] += sum[c];
      break;
    }
  }
  renumberByFirstTriangle(seg, seg.count);
  return seg;
}

std::vector<std::uint32_t> orderAcrossLongestExtent(const Mesh& mesh,
                                                    std::span<const std::uint32_t> triangles) {
  std::vector<Vec3d> centroid(triangles.size());
  Vec3d lo(HUGE_VAL), hi(-HUGE_VAL);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& tri = mesh.triangles[triangles[i]];
    centroid[i] = (Vec3d(mesh.positions[tri[0]]) + Vec3d(mesh.positions[tri[1]]) +
                   Vec3d(mesh.positions[tri[2]])) /
                  3.0;
    lo = min(lo, centroid[i]);
    hi = max(hi, centroid[i]);
  }
  const Vec3d ext = hi - lo;
  const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
  std::vector<std::pair<double, std::uint32_t>> key(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) key[i] = {centroid[i][axis], triangles[i]};
  std::sort(key.begin(), key.end());
  std::vector<std::uint32_t> order(key.size());
  for (std::size_t i = 0; i < key.size(); ++i) order[i] = key[i].second;
  return order;
}

ChartSegmentation boundCharts(const Mesh& mesh, const TriangleAdjacency& adj, ChartSegmentation seg,
                              std::uint32_t maxTriangles) {
  const std::size_t T = seg.chartOfTriangle.size();
  if (maxTriangles == 0) return seg;
  std::vector<std::vector<std::uint32_t>> members(seg.count);
  for (std::uint32_t t = 0; t < T; ++t) members[seg.chartOfTriangle[t]].push_back(t);
  if (std::none_of(members.begin(), members.end(),
                   [&](const auto& m) { return m.size() > maxTriangles; }))
    return seg;
  // Cut the oversized charts, each part relabelled past the existing charts; a stack keeps the
  // work depth-first without recursion.
  std::vector<std::vector<std::uint32_t>> stack;
  for (auto& m : members)
    if (m.size() > maxTriangles) stack.push_back(std::move(m));
  std::uint32_t next = seg.count;
  while (!stack.empty()) {
    std::vector<std::uint32_t> tris = std::move(stack.back());
    stack.pop_back();
    if (tris.size() <= maxTriangles) {
      for (std::uint32_t t : tris) seg.chartOfTriangle[t] = next;
      ++next;
      continue;
    }
    const std::vector<std::uint32_t> order = orderAcrossLongestExtent(mesh, tris);
    const std::size_t k = (tris.size() + maxTriangles - 1) / maxTriangles;  // ≥ 2
    const std::size_t split = std::size_t(double(tris.size()) * double(k / 2) / double(k));
    for (int side = 1; side >= 0; --side) {  // the lower side on top of the stack
      const auto cut = order.begin() + std::ptrdiff_t(split);
      const std::vector<std::uint32_t> part = side == 0
                                                  ? std::vector<std::uint32_t>(order.begin(), cut)
                                                  : std::vector<std::uint32_t>(cut, order.end());
      auto parts = connectedComponents(adj, part);
      for (auto it = parts.rbegin(); it != parts.rend(); ++it) stack.push_back(std::move(*it));
    }
  }
  renumberByFirstTriangle(seg, next);
  return seg;
}

std::vector<std::vector<std::uint32_t>> connectedComponents(
    const TriangleAdjacency& adj, std::span<const std::uint32_t> triangles) {
  std::vector<std::uint32_t> sorted(triangles.begin(), triangles.end());
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::uint8_t> seen(sorted.size(), 0);
  const auto indexOf = [&](std::uint32_t t) -> std::size_t {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), t);
    return it != sorted.end() && *it == t ? std::size_t(it - sorted.begin()) : sorted.size();
  };
  std::vector<std::vector<std::uint32_t>> out;
  std::vector<std::uint32_t> stack;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (seen[i]) continue;
    std::vector<std::uint32_t> comp;
    seen[i] = 1;
    stack.push_back(sorted[i]);
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      comp.push_back(t);
      for (std::uint32_t u : adj.neighbour[t]) {
        if (u == kNone) continue;
        const std::size_t j = indexOf(u);
        if (j < sorted.size() && !seen[j]) {
          seen[j] = 1;
          stack.push_back(u);
        }
      }
    }
    std::sort(comp.begin(), comp.end());
    out.push_back(std::move(comp));
  }
  return out;
}

}  // namespace prt
