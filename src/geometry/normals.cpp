#include "prt/geometry/normals.hpp"

#include <algorithm>
#include <cmath>

namespace prt {

bool isDegenerateTriangle(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2) {
  const Vec3d a(p0), b(p1), c(p2);
  const Vec3d e1 = b - a, e2 = c - a, e3 = c - b;
  const double longest = std::max({dot(e1, e1), dot(e2, e2), dot(e3, e3)});
  const double area2 = length(cross(e1, e2));  // twice the area
  return !(area2 > 1e-7 * longest);
}

std::size_t removeDegenerateTriangles(Mesh& mesh) {
  std::vector<std::uint8_t> keep(mesh.triangles.size(), 1);
  std::size_t removed = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] ||
        isDegenerateTriangle(mesh.positions[tri[0]], mesh.positions[tri[1]],
                             mesh.positions[tri[2]])) {
      keep[t] = 0;
      ++removed;
    }
  }
  if (removed == 0) return 0;
  // Compact, and recount each part's triangle range.
  std::vector<std::uint32_t> keptBefore(mesh.triangles.size() + 1, 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    keptBefore[t + 1] = keptBefore[t] + keep[t];
  for (MeshPart& p : mesh.parts) {
    const std::uint32_t first = keptBefore[p.firstTriangle];
    const std::uint32_t last = keptBefore[p.firstTriangle + p.triangleCount];
    p.firstTriangle = first;
    p.triangleCount = last - first;
  }
  std::size_t w = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    if (keep[t]) mesh.triangles[w++] = mesh.triangles[t];
  mesh.triangles.resize(w);
  return removed;
}

namespace {

/// Σ_f α_f(v) n_f per vertex, in double.
std::vector<Vec3d> angleWeightedSums(const Mesh& mesh) {
  std::vector<Vec3d> sum(mesh.positions.size(), Vec3d(0.0));
  for (const auto& tri : mesh.triangles) {
    const Vec3d p[3] = {Vec3d(mesh.positions[tri[0]]), Vec3d(mesh.positions[tri[1]]),
                        Vec3d(mesh.positions[tri[2]])};
    const Vec3d fn = cross(p[1] - p[0], p[2] - p[0]);
    const double len = length(fn);
    if (!(len > 0)) continue;
    const Vec3d n = fn / len;
    for (int k = 0; k < 3; ++k) {
      const Vec3d a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      const double la = length(a), lb = length(b);
      if (!(la > 0 && lb > 0)) continue;
      // Interior angle by atan2(|a×b|, a·b): accurate for small and obtuse angles alike.
      const double angle = std::atan2(length(cross(a, b)), dot(a, b));
      sum[tri[k]] += n * angle;
    }
  }
  return sum;
}

}  // namespace

std::size_t computeVertexNormals(Mesh& mesh) {
  const std::vector<Vec3d> sum = angleWeightedSums(mesh);
  mesh.normals.resize(mesh.positions.size());
  std::size_t isolated = 0;
  for (std::size_t v = 0; v < sum.size(); ++v) {
    const double len = length(sum[v]);
    if (len > 0) {
      mesh.normals[v] = Vec3f(sum[v] / len);
    } else {
      // On no triangle, or on triangles whose weighted normals cancel (a vertex where two
      // opposite-facing sheets meet): +Y is as good as any.
      mesh.normals[v] = Vec3f{0, 1, 0};
      ++isolated;
    }
  }
  return isolated;
}

std::size_t repairNormals(Mesh& mesh) {
  if (mesh.normals.size() != mesh.positions.size()) {
    computeVertexNormals(mesh);
    return mesh.positions.size();
  }
  std::vector<std::size_t> bad;
  for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
    const Vec3f n = mesh.normals[v];
    const float len = length(n);
    if (isFinite(n) && len > 1e-20f && std::isfinite(len))
      mesh.normals[v] = n / len;
    else
      bad.push_back(v);
  }
  if (bad.empty()) return 0;
  const std::vector<Vec3d> sum = angleWeightedSums(mesh);
  for (std::size_t v : bad) {
    const double len = length(sum[v]);
    mesh.normals[v] = len > 0 ? Vec3f(sum[v] / len) : Vec3f{0, 1, 0};
  }
  return bad.size();
}

}  // namespace prt
