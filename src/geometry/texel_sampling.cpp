#include "prt/geometry/texel_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "prt/core/error.hpp"

namespace prt {

namespace {

struct P2 {
  double x, y;
};
P2 operator-(P2 a, P2 b) {
  return {a.x - b.x, a.y - b.y};
}
P2 operator+(P2 a, P2 b) {
  return {a.x + b.x, a.y + b.y};
}
P2 operator*(double s, P2 a) {
  return {s * a.x, s * a.y};
}
double dot(P2 a, P2 b) {
  return a.x * b.x + a.y * b.y;
}
double cross(P2 a, P2 b) {
  return a.x * b.y - a.y * b.x;
}

void checkSize(int width, int height, const std::string& source) {
  if (width < 1 || height < 1 || width > kMaxLightmapSide || height > kMaxLightmapSide)
    throw Error(source, "a lightmap of " + std::to_string(width) + " x " + std::to_string(height) +
                            " texels is outside 1.." + std::to_string(kMaxLightmapSide) +
                            " per side");
}

void checkUvCount(const Mesh& mesh, std::span<const Vec2f> uvs, const std::string& what) {
  if (uvs.size() != mesh.vertexCount())
    throw Error(mesh.source, what + " has " + std::to_string(uvs.size()) + " coordinates for " +
                                 std::to_string(mesh.vertexCount()) + " vertices");
}

/// The part of triangle p[0..2] inside the texel square [x, x+1] × [y, y+1] (texel units), as a
/// convex polygon (Sutherland–Hodgman against the square's four sides); empty where they meet in
/// an edge or a corner only.
std::vector<P2> clipToTexel(int x, int y, const P2 p[3]) {
  std::vector<P2> poly(p, p + 3), next;
  const auto clip = [&](auto inside, auto cut) {
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const P2 a = poly[i], b = poly[(i + 1) % poly.size()];
      const bool ia = inside(a), ib = inside(b);
      if (ia) next.push_back(a);
      if (ia != ib) next.push_back(cut(a, b));
    }
    poly.swap(next);
  };
  const auto onX = [](double X) {
    return [X](P2 a, P2 b) {
      const double t = (X - a.x) / (b.x - a.x);
      return P2{X, a.y + t * (b.y - a.y)};
    };
  };
  const auto onY = [](double Y) {
    return [Y](P2 a, P2 b) {
      const double t = (Y - a.y) / (b.y - a.y);
      return P2{a.x + t * (b.x - a.x), Y};
    };
  };
  clip([&](P2 q) { return q.x >= x; }, onX(x));
  if (!poly.empty()) clip([&](P2 q) { return q.x <= x + 1.0; }, onX(x + 1.0));
  if (!poly.empty()) clip([&](P2 q) { return q.y >= y; }, onY(y));
  if (!poly.empty()) clip([&](P2 q) { return q.y <= y + 1.0; }, onY(y + 1.0));
  double area2 = 0;
  for (std::size_t i = 0; i < poly.size(); ++i)
    area2 += cross(poly[i], poly[(i + 1) % poly.size()]);
  if (!(std::abs(area2) > 1e-12)) poly.clear();
  return poly;
}

/// The point of convex polygon `poly` nearest to c, which lies outside it: the nearest point of
/// its boundary.
P2 nearestOnPolygon(const std::vector<P2>& poly, P2 c) {
  P2 best = poly[0];
  double bestD = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P2 a = poly[i], b = poly[(i + 1) % poly.size()], ab = b - a;
    const double len2 = dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(dot(c - a, ab) / len2, 0.0, 1.0) : 0.0;
    const P2 q = a + t * ab;
    const double d = dot(q - c, q - c);
    if (d < bestD) bestD = d, best = q;
  }
  return best;
}

/// Triangle t in texel units (its UVs times W, H) and the texels its bounding box spans; `area2`
/// is twice its signed area, 0 for a triangle without UV area (which covers nothing).
struct UvTriangle {
  P2 p[3];
  double area2 = 0;
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;
};

UvTriangle uvTriangle(const Mesh& mesh, std::span<const Vec2f> uvs, std::size_t t, int W, int H) {
  UvTriangle u;
  const auto& tri = mesh.triangles[t];
  for (int k = 0; k < 3; ++k) u.p[k] = {double(uvs[tri[k]].x) * W, double(uvs[tri[k]].y) * H};
  const P2* p = u.p;
  const double area2 = cross(p[1] - p[0], p[2] - p[0]);
  if (!(std::abs(area2) > 1e-12)) return u;
  u.area2 = area2;
  const double lox = std::min({p[0].x, p[1].x, p[2].x}), hix = std::max({p[0].x, p[1].x, p[2].x});
  const double loy = std::min({p[0].y, p[1].y, p[2].y}), hiy = std::max({p[0].y, p[1].y, p[2].y});
  // Clamped in double before the conversion: a UV far outside [0, 1]² (a corrupt file) must not
  // overflow int and sweep a range of texels that does not exist.
  const auto cell = [](double v, int n) { return int(std::clamp(v, -1.0, double(n))); };
  u.x0 = std::max(0, cell(std::floor(lox), W)), u.x1 = std::min(W - 1, cell(std::ceil(hix), W) - 1);
  u.y0 = std::max(0, cell(std::floor(loy), H)), u.y1 = std::min(H - 1, cell(std::ceil(hiy), H) - 1);
  return u;
}

/// Calls f(texel, λ, centreInside, strictlyInside, distance) if triangle `u` covers texel (x, y)
/// of a lightmap W texels wide (λ: barycentric weights of the sample point: the centre, or the
/// nearest point of the triangle to it). The one test of a texel against a triangle, whichever
/// texels are asked (all of a triangle's, or a few: sampleTexelsAt), so their answers agree.
template <typename F>
void coverTexel(const UvTriangle& u, int x, int y, int W, F&& f) {
  const P2* p = u.p;
  const double area2 = u.area2;
  const P2 c{x + 0.5, y + 0.5};
  // Edge functions: λ_k is the signed area opposite vertex k over the whole.
  const double l0 = cross(p[2] - p[1], c - p[1]) / area2;
  const double l1 = cross(p[0] - p[2], c - p[2]) / area2;
  const double l2 = 1 - l0 - l1;
  const std::size_t texel = std::size_t(y) * W + x;
  if (l0 >= -1e-9 && l1 >= -1e-9 && l2 >= -1e-9) {
    const double s = std::max(l0, 0.0) + std::max(l1, 0.0) + std::max(l2, 0.0);
    f(texel,
      Vec3f(float(std::max(l0, 0.0) / s), float(std::max(l1, 0.0) / s),
            float(std::max(l2, 0.0) / s)),
      true, l0 > 1e-6 && l1 > 1e-6 && l2 > 1e-6, 0.0);
  } else if (const std::vector<P2> part = clipToTexel(x, y, p); !part.empty()) {
    // Partly covered: the point of the triangle inside the texel nearest to its centre.
    const P2 q = nearestOnPolygon(part, c);
    const double m0 = std::max(cross(p[2] - p[1], q - p[1]) / area2, 0.0);
    const double m1 = std::max(cross(p[0] - p[2], q - p[2]) / area2, 0.0);
    const double m2 = std::max(1 - m0 - m1, 0.0), s = m0 + m1 + m2;
    f(texel, Vec3f(float(m0 / s), float(m1 / s), float(m2 / s)), false, false,
      std::sqrt(dot(q - c, q - c)));
  }
}

/// True when one of triangle `u`'s edges has the four corners of texel (x, y) beyond it by more
/// than 10⁻⁶ texel: they cannot meet, and coverTexel would clip the texel to nothing. The
/// margin is a million times the rounding of the clipping (UVs inside [0, 1]², as a lightmap's
/// are: coordinates below 2¹³ texels, in double), so no texel that coverTexel covers is ever
/// rejected; those it rejects cost three edge tests here instead of a polygon clipping.
bool separated(const UvTriangle& u, int x, int y) {
  const P2* p = u.p;
  const double orientation = u.area2 > 0 ? 1.0 : -1.0;
  for (int k = 0; k < 3; ++k) {
    const P2 a = p[k], b = p[(k + 1) % 3], ab = b - a;
    const double margin = 1e-6 * std::sqrt(dot(ab, ab));  // distance times |ab|
    bool allOutside = true;
    for (int corner = 0; corner < 4 && allOutside; ++corner) {
      const P2 q{double(x + (corner & 1)), double(y + (corner >> 1))};
      allOutside = orientation * cross(ab, q - a) < -margin;
    }
    if (allOutside) return true;
  }
  return false;
}

/// Calls coverTexel's f for every texel triangle t covers in a W × H lightmap. Triangles without
/// UV area call nothing.
template <typename F>
void forEachCoveredTexel(const Mesh& mesh, std::span<const Vec2f> uvs, std::size_t t, int W, int H,
                         F&& f) {
  const UvTriangle u = uvTriangle(mesh, uvs, t, W, H);
  if (u.area2 == 0) return;
  for (int y = u.y0; y <= u.y1; ++y)
    for (int x = u.x0; x <= u.x1; ++x) coverTexel(u, x, y, W, f);
}

/// The sample a texel keeps among the triangles that cover it, offered in index order: strictly
/// nearer wins, so a tie keeps the lower index (a centre inside is at distance 0) — sampleTexels'
/// rule, for the few texels sampleTexelsAt holds.
struct BestSample {
  double distance = std::numeric_limits<double>::infinity();
  std::int32_t triangle = -1;
  Vec3f weights{0.0f};
  bool centre = false;
  void offer(std::size_t t, Vec3f w, bool inside, double d) {
    if (d < distance) {
      distance = d;
      triangle = static_cast<std::int32_t>(t);
      weights = w;
      centre = inside;
    }
  }
};

}  // namespace

void checkLightmapUvs(const Mesh& mesh, std::span<const Vec2f> uvs, int width, int height,
                      const std::string& what) {
  checkSize(width, height, mesh.source);
  checkUvCount(mesh, uvs, what);
  checkUvsInside(mesh, uvs, what);
  std::vector<std::int32_t> owner(std::size_t(width) * height, -1);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    forEachCoveredTexel(
        mesh, uvs, t, width, height, [&](std::size_t texel, Vec3f, bool, bool strictly, double) {
          if (!strictly) return;
          if (owner[texel] >= 0)
            throw Error(mesh.source,
                        what + ": triangles " + std::to_string(owner[texel]) + " and " +
                            std::to_string(t) + " overlap in UV space (both cover texel (" +
                            std::to_string(texel % width) + ", " + std::to_string(texel / width) +
                            ") of " + std::to_string(width) + " x " + std::to_string(height) +
                            "); a lightmap needs a UV set without overlaps");
          owner[texel] = static_cast<std::int32_t>(t);
        });
}

std::optional<std::size_t> firstUvOutside(std::span<const Vec2f> uvs) {
  for (std::size_t v = 0; v < uvs.size(); ++v) {
    const Vec2f t = uvs[v];
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || t.x < -1e-6f || t.x > 1 + 1e-6f ||
        t.y < -1e-6f || t.y > 1 + 1e-6f)
      return v;
  }
  return std::nullopt;
}

void checkUvsInside(const Mesh& mesh, std::span<const Vec2f> uvs, const std::string& what) {
  if (const auto v = firstUvOutside(uvs))
    throw Error(mesh.source, what + " of vertex " + std::to_string(*v) + " is (" +
                                 std::to_string(uvs[*v].x) + ", " + std::to_string(uvs[*v].y) +
                                 "), outside [0, 1]^2: a lightmap needs every chart inside it");
}

TexelSamples sampleTexels(const Mesh& mesh, std::span<const Vec2f> uvs, int width, int height) {
  checkSize(width, height, mesh.source);
  checkUvCount(mesh, uvs, "the UV set");
  const std::size_t n = std::size_t(width) * height;
  // BestSample's rule in four arrays (25 bytes a texel rather than its padded 32: the whole
  // lightmap's worth is held here).
  std::vector<std::int32_t> best(n, -1);
  std::vector<double> bestDistance(n, std::numeric_limits<double>::infinity());
  std::vector<Vec3f> bestWeights(n);
  std::vector<std::uint8_t> inside(n, 0);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    forEachCoveredTexel(mesh, uvs, t, width, height,
                        [&](std::size_t texel, Vec3f w, bool centre, bool, double distance) {
                          // Strictly nearer wins: triangles come in index order, so a tie keeps
                          // the lower index.
                          if (distance < bestDistance[texel]) {
                            bestDistance[texel] = distance;
                            best[texel] = static_cast<std::int32_t>(t);
                            bestWeights[texel] = w;
                            inside[texel] = centre;
                          }
                        });
  TexelSamples out;
  out.width = width;
  out.height = height;
  out.sampleOfTexel.assign(n, -1);
  for (std::size_t texel = 0; texel < n; ++texel) {
    if (best[texel] < 0) continue;
    out.sampleOfTexel[texel] = static_cast<std::int32_t>(out.samples.size());
    out.samples.push_back({static_cast<std::uint32_t>(texel),
                           static_cast<std::uint32_t>(best[texel]), bestWeights[texel],
                           inside[texel] != 0});
  }
  return out;
}

TexelCoverage coverTexels(const Mesh& mesh, std::span<const Vec2f> uvs, int width, int height) {
  checkSize(width, height, mesh.source);
  checkUvCount(mesh, uvs, "the UV set");
  TexelCoverage out(width, height);
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const UvTriangle u = uvTriangle(mesh, uvs, t, width, height);
    if (u.area2 == 0) continue;
    for (int y = u.y0; y <= u.y1; ++y)
      for (int x = u.x0; x <= u.x1; ++x) {
        const std::size_t texel = std::size_t(y) * width + x;
        // Covered once is covered: the clipping of a texel another triangle covered is skipped,
        // and so is a texel the triangle's edges keep clear of.
        if (!out.covered(texel) && !separated(u, x, y))
          coverTexel(u, x, y, width,
                     [&](std::size_t, Vec3f, bool, bool, double) { out.cover(texel); });
      }
  }
  out.index();
  return out;
}

std::vector<TexelSample> sampleTexelsAt(const Mesh& mesh, std::span<const Vec2f> uvs, int width,
                                        int height, std::span<const std::uint32_t> texels) {
  checkSize(width, height, mesh.source);
  checkUvCount(mesh, uvs, "the UV set");
  const std::size_t n = std::size_t(width) * height;
  for (std::size_t i = 0; i < texels.size(); ++i)
    PRT_CHECK(texels[i] < n && (i == 0 || texels[i - 1] < texels[i]),
              "sampleTexelsAt: the texels are distinct, ascending and inside the lightmap");
  std::vector<BestSample> best(texels.size());
  const auto offer = [&](std::size_t t, const UvTriangle& u, std::size_t i) {
    const int x = int(texels[i] % std::uint32_t(width)), y = int(texels[i] / std::uint32_t(width));
    if (x < u.x0 || x > u.x1 || y < u.y0 || y > u.y1) return;
    coverTexel(u, x, y, width, [&](std::size_t, Vec3f w, bool centre, bool, double distance) {
      best[i].offer(t, w, centre, distance);
    });
  };
  // Triangles in index order, as sampleTexels offers them, so each texel keeps the same one.
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const UvTriangle u = uvTriangle(mesh, uvs, t, width, height);
    if (u.area2 == 0 || u.x1 < u.x0 || u.y1 < u.y0) continue;
    const std::size_t rows = std::size_t(u.y1 - u.y0 + 1);
    if (rows >= texels.size()) {
      // A triangle spanning more rows than there are texels asked: test each of them.
      for (std::size_t i = 0; i < texels.size(); ++i) offer(t, u, i);
      continue;
    }
    // Else the texels asked in each row the triangle spans, found by bisection (ascending).
    for (int y = u.y0; y <= u.y1; ++y) {
      const std::uint32_t lo = std::uint32_t(std::size_t(y) * width + u.x0);
      const std::uint32_t hi = std::uint32_t(std::size_t(y) * width + u.x1);
      for (auto it = std::lower_bound(texels.begin(), texels.end(), lo);
           it != texels.end() && *it <= hi; ++it)
        offer(t, u, std::size_t(it - texels.begin()));
    }
  }
  std::vector<TexelSample> out;
  for (std::size_t i = 0; i < texels.size(); ++i)
    if (best[i].triangle >= 0)
      out.push_back({texels[i], static_cast<std::uint32_t>(best[i].triangle), best[i].weights,
                     best[i].centre});
  return out;
}

Vec3f samplePosition(const Mesh& mesh, const TexelSample& s) {
  const auto& t = mesh.triangles[s.triangle];
  const Vec3f& b = s.barycentric;
  return mesh.positions[t[0]] * b.x + mesh.positions[t[1]] * b.y + mesh.positions[t[2]] * b.z;
}

Vec3f sampleNormal(const Mesh& mesh, const TexelSample& s) {
  const auto& t = mesh.triangles[s.triangle];
  const Vec3f& b = s.barycentric;
  const Vec3f n = mesh.normals[t[0]] * b.x + mesh.normals[t[1]] * b.y + mesh.normals[t[2]] * b.z;
  if (length(n) > 1e-12f) return normalize(n);
  return normalize(cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                         mesh.positions[t[2]] - mesh.positions[t[0]]));
}

void dilateTexels(std::span<float> values, int stride, std::vector<std::uint8_t>& filled, int width,
                  int height, int padding, TexelDilation how) {
  const std::size_t n = std::size_t(width) * height;
  PRT_CHECK(values.size() == n * std::size_t(stride) && filled.size() == n,
            "dilateTexels: buffers do not match the lightmap");
  std::vector<std::uint8_t> before;
  std::vector<double> sum(static_cast<std::size_t>(stride));
  for (int ring = 0; ring < padding; ++ring) {
    before = filled;  // each ring reads the texels filled before it
    bool any = false;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t texel = std::size_t(y) * width + x;
        if (before[texel]) continue;
        int count = 0;
        std::fill(sum.begin(), sum.end(), 0.0);
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            const std::size_t o = std::size_t(ny) * width + nx;
            if (!before[o]) continue;
            if (how == TexelDilation::CopyFirst) {
              if (count++ == 0)
                std::copy_n(values.begin() + std::ptrdiff_t(o * stride), stride,
                            values.begin() + std::ptrdiff_t(texel * stride));
              continue;
            }
            ++count;
            for (int c = 0; c < stride; ++c) sum[c] += values[o * stride + c];
          }
        if (count == 0) continue;
        if (how == TexelDilation::Mean)
          for (int c = 0; c < stride; ++c) values[texel * stride + c] = float(sum[c] / count);
        filled[texel] = 1;
        any = true;
      }
    if (!any) break;
  }
}

}  // namespace prt
