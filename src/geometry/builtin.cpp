#include "prt/geometry/builtin.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <set>
#include <utility>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"
#include "prt/core/spec.hpp"
#include "prt/geometry/chart_packing.hpp"

namespace prt {

namespace {

constexpr const char* kPrefix = "builtin:";

/// Appends `part` (its own vertex and triangle numbering) to `scene` as a new MeshPart.
void append(Mesh& scene, const Mesh& part, const std::string& name) {
  MeshPart p;
  p.name = name;
  p.firstVertex = static_cast<std::uint32_t>(scene.positions.size());
  p.vertexCount = static_cast<std::uint32_t>(part.positions.size());
  p.firstTriangle = static_cast<std::uint32_t>(scene.triangles.size());
  p.triangleCount = static_cast<std::uint32_t>(part.triangles.size());
  scene.positions.insert(scene.positions.end(), part.positions.begin(), part.positions.end());
  scene.normals.insert(scene.normals.end(), part.normals.begin(), part.normals.end());
  scene.albedo.insert(scene.albedo.end(), part.albedo.begin(), part.albedo.end());
  scene.lightmapUvs.insert(scene.lightmapUvs.end(), part.lightmapUvs.begin(),
                           part.lightmapUvs.end());
  for (const auto& t : part.triangles)
    scene.triangles.push_back({t[0] + p.firstVertex, t[1] + p.firstVertex, t[2] + p.firstVertex});
  scene.parts.push_back(p);
}

/// The builtin scenes' lightmap UVs: every grid (a plane, a wall, a block's face) is one chart,
/// its vertices' lightmapUvs holding their place in it in world units (grid() writes them);
/// the charts are packed into [0, 1]² at one texel density with a gutter of 4 texels at 512²
/// (2 at 256²). `charts` lists each chart's vertex count, in vertex order.
void packLightmap(Mesh& scene, const std::vector<std::uint32_t>& charts) {
  constexpr float kGutter = 4.0f / 512.0f;
  std::vector<Vec2f> sizes;
  std::uint32_t first = 0;
  for (std::uint32_t count : charts) {
    Vec2f size{0, 0};
    for (std::uint32_t v = first; v < first + count; ++v)
      size = {std::max(size.x, scene.lightmapUvs[v].x), std::max(size.y, scene.lightmapUvs[v].y)};
    sizes.push_back(size);
    first += count;
  }
  PRT_CHECK(first == scene.lightmapUvs.size(), "builtin: the charts do not cover the vertices");
  const ChartPacking p = packCharts(sizes, kGutter);
  first = 0;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    for (std::uint32_t v = first; v < first + charts[c]; ++v) {
      Vec2f& t = scene.lightmapUvs[v];
      t = {p.offsets[c].x + p.scale * t.x, p.offsets[c].y + p.scale * t.y};
    }
    first += charts[c];
  }
}

/// Icosphere: the icosahedron with each triangle split into 4 `subdiv` times, vertices pushed
/// onto the sphere. Edge midpoints are shared through a map, so the mesh is closed (watertight).
Mesh icosphere(int subdiv, float radius, Vec3f centre, Rgb albedo) {
  const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
  std::vector<Vec3f> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p = normalize(p);
  std::vector<std::array<std::uint32_t, 3>> f = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < subdiv; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(normalize(v[a] + v[b]));
      return mid[key] = static_cast<std::uint32_t>(v.size() - 1);
    };
    std::vector<std::array<std::uint32_t, 3>> g;
    g.reserve(f.size() * 4);
    for (const auto& tri : f) {
      const std::uint32_t a = midpoint(tri[0], tri[1]);
      const std::uint32_t b = midpoint(tri[1], tri[2]);
      const std::uint32_t c = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], c, b});
      g.push_back({a, b, c});
    }
    f.swap(g);
  }
  Mesh m;
  m.normals = v;
  m.positions.reserve(v.size());
  for (const auto& n : v) m.positions.push_back(centre + n * radius);
  m.albedo.assign(v.size(), albedo);
  m.triangles = std::move(f);
  return m;
}

/// A planar grid of n x n quads spanning origin + [0,1]^2 in (du, dv), normal = cross(du, dv)
/// normalised (so the quads are counter-clockwise seen from the normal side).
Mesh grid(Vec3f origin, Vec3f du, Vec3f dv, int n, Rgb albedo) {
  Mesh m;
  const Vec3f normal = normalize(cross(du, dv));
  const float lu = length(du), lv = length(dv);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m.positions.push_back(origin + du * (float(i) / float(n)) + dv * (float(j) / float(n)));
      m.normals.push_back(normal);
      m.albedo.push_back(albedo);
      m.lightmapUvs.push_back(
          {lu * float(i) / float(n), lv * float(j) / float(n)});  // packLightmap
    }
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

/// An axis-aligned box [-hx,hx] x [0,hy] x [-hz,hz] rotated by `angle` about Y and moved to
/// (cx, 0, cz); each face a grid of n x n quads with its own vertices (flat normals).
Mesh block(float hx, float hy, float hz, float angle, float cx, float cz, int n, Rgb albedo) {
  const float c = std::cos(angle), s = std::sin(angle);
  const auto xf = [&](Vec3f p) {
    return Vec3f{c * p.x + s * p.z + cx, p.y, -s * p.x + c * p.z + cz};
  };
  const auto xv = [&](Vec3f d) { return Vec3f{c * d.x + s * d.z, d.y, -s * d.x + c * d.z}; };
  Mesh out;
  // Faces as (corner, du, dv); each is flipped below so that cross(du, dv) points outward.
  const Vec3f X{2 * hx, 0, 0}, Y{0, hy, 0}, Z{0, 0, 2 * hz};
  const Vec3f lo{-hx, 0, -hz};
  const std::array<std::array<Vec3f, 3>, 6> faces = {{
      {lo, X, Z},
      {Vec3f{-hx, hy, -hz}, X, Z},  // bottom, top
      {lo, X, Y},
      {Vec3f{-hx, 0, hz}, X, Y},  // back, front
      {lo, Y, Z},
      {Vec3f{hx, 0, -hz}, Y, Z},  // left, right
  }};
  for (auto face : faces) {
    Vec3f o = face[0], du = face[1], dv = face[2];
    const Vec3f centre = o + (du + dv) * 0.5f;
    const Vec3f boxCentre{0, hy * 0.5f, 0};
    if (dot(cross(du, dv), centre - boxCentre) < 0) std::swap(du, dv);  // make it face outward
    Mesh g = grid(xf(o), xv(du), xv(dv), n, albedo);
    const std::uint32_t base = static_cast<std::uint32_t>(out.positions.size());
    out.positions.insert(out.positions.end(), g.positions.begin(), g.positions.end());
    out.normals.insert(out.normals.end(), g.normals.begin(), g.normals.end());
    out.albedo.insert(out.albedo.end(), g.albedo.begin(), g.albedo.end());
    out.lightmapUvs.insert(out.lightmapUvs.end(), g.lightmapUvs.begin(), g.lightmapUvs.end());
    for (const auto& t : g.triangles)
      out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return out;
}

/// Vertex and triangle counts of the pieces, known before building them.
struct Size {
  std::uint64_t vertices = 0, triangles = 0;
  Size operator+(Size o) const { return {vertices + o.vertices, triangles + o.triangles}; }
  Size operator*(std::uint64_t k) const { return {vertices * k, triangles * k}; }
};
Size icosphereSize(int subdiv) {
  const std::uint64_t f = std::uint64_t(1) << (2 * subdiv);  // 4^subdiv
  return {10 * f + 2, 20 * f};
}
Size gridSize(int n) {
  return {std::uint64_t(n + 1) * std::uint64_t(n + 1), 2 * std::uint64_t(n) * std::uint64_t(n)};
}
/// The resource policy (PRT_MAX_VERTICES, PRT_MAX_TRIANGLES) for a scene of `size`, before it
/// is built, as every file loader applies it.
void checkSize(const std::string& label, Size size) {
  checkLimit(label, "vertex count", size.vertices, limits().maxVertices, "PRT_MAX_VERTICES");
  checkLimit(label, "triangle count", size.triangles, limits().maxTriangles, "PRT_MAX_TRIANGLES");
}

Mesh makeSphere(Spec& p, const std::string& full) {
  const int subdiv = p.integer("subdiv", 5, 0, 7);
  const double r = p.number("r", 1.0, 1e-6, 1e6);
  const double a = p.number("albedo", 0.8, 0.0, 1.0);
  p.finish();
  checkSize(full, icosphereSize(subdiv));
  Mesh scene;
  append(scene, icosphere(subdiv, float(r), Vec3f{0.0f}, Rgb(float(a))), "sphere");
  return scene;
}

Mesh makeSpherePlane(Spec& p, const std::string& full) {
  const double r = p.number("r", 0.5, 1e-6, 1e6);
  const double h = p.number("h", 1.0, -1e6, 1e6);
  const double size = p.number("size", 4.0, 1e-6, 1e6);
  const int n = p.integer("grid", 96, 1, 1000);
  const int subdiv = p.integer("subdiv", 4, 0, 7);
  const double a = p.number("albedo", 0.8, 0.0, 1.0);
  p.finish();
  if (!(h > r)) throw Error(full, "the sphere must lie above the plane (h > r)");
  checkSize(full, gridSize(n) + icosphereSize(subdiv));
  Mesh scene;
  const float s = float(size);
  // du = +X, dv = -Z so that cross(du, dv) = +Y.
  append(scene, grid({-s, 0, s}, {2 * s, 0, 0}, {0, 0, -2 * s}, n, Rgb(float(a))), "plane");
  append(scene, icosphere(subdiv, float(r), {0, float(h), 0}, Rgb(float(a))), "sphere");
  // No lightmap UVs: the icosphere shares every vertex across the sphere (no seams to cut
  // charts along).
  scene.lightmapUvs.clear();
  return scene;
}

Mesh makePlane(Spec& p, const std::string& full) {
  const double y = p.number("y", 0.0, -1e6, 1e6);
  const double size = p.number("size", 4.0, 1e-6, 1e6);
  const int n = p.integer("grid", 96, 1, 2000);
  const double a = p.number("albedo", 0.8, 0.0, 1.0);
  p.finish();
  checkSize(full, gridSize(n));
  Mesh scene;
  const float s = float(size), h = float(y);
  append(scene, grid({-s, h, s}, {2 * s, 0, 0}, {0, 0, -2 * s}, n, Rgb(float(a))), "plane");
  packLightmap(scene, {std::uint32_t(gridSize(n).vertices)});
  return scene;
}

Mesh makeCornell(Spec& p, const std::string& full) {
  const int n = p.integer("grid", 40, 1, 400);
  p.finish();
  checkSize(full, gridSize(n) * 5 + gridSize(std::max(2, n / 5)) * 12);  // walls, two blocks
  const Rgb white{0.73f, 0.73f, 0.73f}, red{0.63f, 0.065f, 0.05f}, green{0.14f, 0.45f, 0.091f};
  Mesh scene;
  // Walls face inward. The box is [-1,1] x [0,2] x [-1,1], open at z = +1.
  append(scene, grid({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, n, white), "floor");      // +Y
  append(scene, grid({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, n, white), "ceiling");    // -Y
  append(scene, grid({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, n, white), "back-wall");  // +Z
  append(scene, grid({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, n, red), "left-wall");    // +X
  append(scene, grid({1, 0, -1}, {0, 0, 2}, {0, 2, 0}, n, green), "right-wall");  // -X
  const int nb = std::max(2, n / 5);
  append(scene, block(0.3f, 1.2f, 0.3f, 0.3f, -0.35f, -0.35f, nb, white), "tall-block");
  append(scene, block(0.3f, 0.6f, 0.3f, -0.3f, 0.4f, 0.35f, nb, white), "short-block");
  std::vector<std::uint32_t> charts(5, std::uint32_t(gridSize(n).vertices));  // the walls
  charts.insert(charts.end(), 12, std::uint32_t(gridSize(nb).vertices));      // the faces
  packLightmap(scene, charts);
  return scene;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  return {"sphere", "sphere-plane", "plane", "cornell"};
}

bool isBuiltinScene(const std::string& path) {
  return path.rfind(kPrefix, 0) == 0;
}

Mesh builtinScene(const std::string& full) {
  Spec p(full, kPrefix);
  const std::string& name = p.name();
  const std::string label = isBuiltinScene(full) ? full : std::string(kPrefix) + full;
  Mesh m;
  if (name == "sphere")
    m = makeSphere(p, label);
  else if (name == "sphere-plane")
    m = makeSpherePlane(p, label);
  else if (name == "plane")
    m = makePlane(p, label);
  else if (name == "cornell")
    m = makeCornell(p, label);
  else {
    std::string list;
    for (const auto& n : builtinSceneNames()) list += (list.empty() ? "" : ", ") + n;
    throw Error(label, "unknown builtin scene '" + name + "' (known: " + list + ")");
  }
  m.source = label;
  return m;
}

}  // namespace prt
