#include "prt/unwrap/chart_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prt {

namespace {

double cross2(const Uv2& o, const Uv2& a, const Uv2& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/// True when the interiors of triangles p and q overlap by more than `tol` along every
/// separating-axis candidate (the six edge normals).
bool interiorsOverlap(const Uv2 p[3], const Uv2 q[3], double tol) {
  for (int side = 0; side < 2; ++side) {
    const Uv2* e = side == 0 ? p : q;
    for (int k = 0; k < 3; ++k) {
      const Uv2& a = e[k];
      const Uv2& b = e[(k + 1) % 3];
      const double nx = b[1] - a[1], ny = a[0] - b[0];
      const double len = std::hypot(nx, ny);
      if (!(len > 0)) continue;
      double pmin = HUGE_VAL, pmax = -HUGE_VAL, qmin = HUGE_VAL, qmax = -HUGE_VAL;
      for (int j = 0; j < 3; ++j) {
        const double s = (p[j][0] * nx + p[j][1] * ny) / len;
        const double t = (q[j][0] * nx + q[j][1] * ny) / len;
        pmin = std::min(pmin, s), pmax = std::max(pmax, s);
        qmin = std::min(qmin, t), qmax = std::max(qmax, t);
      }
      if (pmax <= qmin + tol || qmax <= pmin + tol) return false;
    }
  }
  return true;
}

}  // namespace

LayoutFault checkChartLayout(std::span<const Uv2> uv,
                             std::span<const std::array<std::uint32_t, 3>> triangles,
                             std::span<const double> area3d) {
  const std::size_t T = triangles.size();
  if (T == 0) return LayoutFault::None;
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  for (const Uv2& q : uv)
    for (int d = 0; d < 2; ++d) lo[d] = std::min(lo[d], q[d]), hi[d] = std::max(hi[d], q[d]);
  const double diag = std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
  if (!std::isfinite(diag)) return LayoutFault::Flipped;
  // Signed areas: a triangle with area in 3D must keep a clearly positive one.
  std::vector<double> area2(T);
  double total = 0;
  for (std::size_t t = 0; t < T; ++t) {
    const auto& tri = triangles[t];
    area2[t] = cross2(uv[tri[0]], uv[tri[1]], uv[tri[2]]);
    total += std::abs(area2[t]);
  }
  const double tiny = 1e-12 * (total > 0 ? total : diag * diag);
  for (std::size_t t = 0; t < T; ++t)
    if ((area3d[t] > 0 && !(area2[t] > tiny)) || area2[t] < -tiny) return LayoutFault::Flipped;
  if (T == 1) return LayoutFault::None;
  // Pairs through a grid of about one cell per triangle.
  const double w = std::max(hi[0] - lo[0], 1e-300), h = std::max(hi[1] - lo[1], 1e-300);
  const double cell = std::sqrt(w * h / double(T));
  const int nx = std::clamp(int(std::ceil(w / cell)), 1, 4096);
  const int ny = std::clamp(int(std::ceil(h / cell)), 1, 4096);
  const double cx = nx / w, cy = ny / h;
  const auto cellOf = [&](double v, double o, double c, int n) {
    return std::clamp(int((v - o) * c), 0, n - 1);
  };
  std::vector<std::uint32_t> start(std::size_t(nx) * ny + 1, 0);
  struct Box {
    int x0, x1, y0, y1;
  };
  std::vector<Box> box(T);
  for (std::size_t t = 0; t < T; ++t) {
    const auto& tri = triangles[t];
    double bl[2] = {HUGE_VAL, HUGE_VAL}, bh[2] = {-HUGE_VAL, -HUGE_VAL};
    for (std::uint32_t v : tri)
      for (int d = 0; d < 2; ++d)
        bl[d] = std::min(bl[d], uv[v][d]), bh[d] = std::max(bh[d], uv[v][d]);
    box[t] = {cellOf(bl[0], lo[0], cx, nx), cellOf(bh[0], lo[0], cx, nx),
              cellOf(bl[1], lo[1], cy, ny), cellOf(bh[1], lo[1], cy, ny)};
    for (int y = box[t].y0; y <= box[t].y1; ++y)
      for (int x = box[t].x0; x <= box[t].x1; ++x) ++start[std::size_t(y) * nx + x + 1];
  }
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<std::uint32_t> items(start.back());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < T; ++t)
    for (int y = box[t].y0; y <= box[t].y1; ++y)
      for (int x = box[t].x0; x <= box[t].x1; ++x)
        items[fill[std::size_t(y) * nx + x]++] = std::uint32_t(t);
  const double tol = 1e-9 * diag;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const std::size_t c = std::size_t(y) * nx + x;
      for (std::uint32_t i = start[c]; i < start[c + 1]; ++i)
        for (std::uint32_t j = i + 1; j < start[c + 1]; ++j) {
          const std::uint32_t s = items[i], t = items[j];
          // Test each pair once: in the first cell both boxes share.
          if (std::max(box[s].x0, box[t].x0) != x || std::max(box[s].y0, box[t].y0) != y) continue;
          if (std::abs(area2[s]) <= tiny || std::abs(area2[t]) <= tiny) continue;
          const Uv2 p[3] = {uv[triangles[s][0]], uv[triangles[s][1]], uv[triangles[s][2]]};
          const Uv2 q[3] = {uv[triangles[t][0]], uv[triangles[t][1]], uv[triangles[t][2]]};
          if (interiorsOverlap(p, q, tol)) return LayoutFault::Overlap;
        }
    }
  return LayoutFault::None;
}

std::array<double, 2> placeOnBoundingRectangle(std::span<Uv2> uv) {
  if (uv.empty()) return {0, 0};
  // Convex hull (Andrew's monotone chain), counter-clockwise.
  std::vector<Uv2> pts(uv.begin(), uv.end());
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  std::vector<Uv2> hull;
  if (pts.size() < 3) {
    hull = pts;
  } else {
    hull.resize(2 * pts.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      while (k >= 2 && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
      hull[k++] = pts[i];
    }
    for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
      while (k >= t && cross2(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) --k;
      hull[k++] = pts[i - 1];
    }
    hull.resize(k - 1);
  }
  // The rectangle with a side along each hull edge; the smallest area wins (first on ties).
  double bestArea = HUGE_VAL, bestC = 1, bestS = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Uv2& a = hull[i];
    const Uv2& b = hull[(i + 1) % hull.size()];
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (!(len > 0)) continue;
    const double c = (b[0] - a[0]) / len, s = (b[1] - a[1]) / len;
    double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
    for (const Uv2& q : hull) {
      const double x = c * q[0] + s * q[1], y = -s * q[0] + c * q[1];
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    const double area = (x1 - x0) * (y1 - y0);
    if (area < bestArea * (1 - 1e-12)) bestArea = area, bestC = c, bestS = s;
  }
  // Rotate by −θ (the edge onto the u axis), then a quarter turn if it stands taller than wide.
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (Uv2& q : uv) {
    q = {bestC * q[0] + bestS * q[1], -bestS * q[0] + bestC * q[1]};
    x0 = std::min(x0, q[0]), x1 = std::max(x1, q[0]), y0 = std::min(y0, q[1]),
    y1 = std::max(y1, q[1]);
  }
  const bool turn = y1 - y0 > x1 - x0;
  for (Uv2& q : uv) {
    const double x = q[0] - x0, y = q[1] - y0;
    q = turn ? Uv2{y1 - y0 - y, x} : Uv2{x, y};
  }
  return turn ? std::array<double, 2>{y1 - y0, x1 - x0} : std::array<double, 2>{x1 - x0, y1 - y0};
}

}  // namespace prt
