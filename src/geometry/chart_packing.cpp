#include "prt/geometry/chart_packing.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "prt/core/error.hpp"

namespace prt {

namespace {

/// Shelf packing of `order` at `scale`: offsets into `out` and true if everything fits.
bool shelves(std::span<const Vec2f> sizes, const std::vector<std::size_t>& order, double scale,
             double gutter, std::vector<Vec2f>& out) {
  double x = gutter, y = gutter, rowHeight = 0;
  for (std::size_t k : order) {
    const double w = sizes[k].x * scale, h = sizes[k].y * scale;
    if (x + w + gutter > 1.0 && x > gutter) {  // next row
      y += rowHeight + gutter;
      x = gutter;
      rowHeight = 0;
    }
    if (x + w + gutter > 1.0 || y + h + gutter > 1.0) return false;
    out[k] = {float(x), float(y)};
    x += w + gutter;
    rowHeight = std::max(rowHeight, h);
  }
  return true;
}

}  // namespace

ChartPacking packCharts(std::span<const Vec2f> sizes, float gutter) {
  if (!(gutter >= 0 && gutter < 0.5f))
    throw Error("chart packing: a gutter of " + std::to_string(gutter) +
                " UV units leaves no room (0 <= gutter < 0.5)");
  double area = 0, longest = 0;
  for (const Vec2f& s : sizes) {
    if (!(std::isfinite(s.x) && std::isfinite(s.y) && s.x > 0 && s.y > 0))
      throw Error("chart packing: a chart of size " + std::to_string(s.x) + " x " +
                  std::to_string(s.y) + " (sizes must be positive and finite)");
    area += double(s.x) * s.y;
    longest = std::max({longest, double(s.x), double(s.y)});
  }
  ChartPacking p;
  p.offsets.assign(sizes.size(), Vec2f{});
  if (sizes.empty()) return p;
  // Tallest first, then widest, then by index: a fixed order.
  std::vector<std::size_t> order(sizes.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return sizes[a].y != sizes[b].y ? sizes[a].y > sizes[b].y : sizes[a].x > sizes[b].x;
  });
  // The scale lies between one that surely fits (every chart in a cell of a √n × √n grid) and
  // one that cannot (the charts' area would exceed the square's).
  const double room = 1.0 - 2.0 * gutter;
  const double cells = std::ceil(std::sqrt(double(sizes.size())));
  double lo = (room - (cells - 1) * gutter) / cells / longest;
  double hi = std::sqrt(1.0 / area);
  std::vector<Vec2f> offsets(sizes.size());
  if (!(lo > 0) || !shelves(sizes, order, lo, gutter, offsets))
    throw Error("chart packing: " + std::to_string(sizes.size()) + " charts do not fit with a " +
                "gutter of " + std::to_string(gutter) + " UV units");
  p.offsets = offsets;
  while (hi - lo > 1e-4 * lo) {
    const double mid = 0.5 * (lo + hi);
    if (shelves(sizes, order, mid, gutter, offsets)) {
      lo = mid;
      p.offsets = offsets;
    } else {
      hi = mid;
    }
  }
  p.scale = float(lo);
  p.usedArea = float(lo * lo * area);
  return p;
}

}  // namespace prt
