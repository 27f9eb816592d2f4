#include "prt/unwrap/atlas_packing.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <vector>

#include "prt/core/error.hpp"

namespace prt {

namespace {

/// Triangles touching a texel's border count as covering it, and coordinates are rounded to
/// float when they become UVs: a cell grows by this much (in cells) before the overlap test.
constexpr double kEps = 1e-3;
/// The chart sits this far (in cells) inside its raster on every side, so that nothing of it
/// comes within kEps of a texel outside the raster.
constexpr double kMargin = 2 * kEps;
/// The packing grid's side at most (in cells); larger atlases pack whole cells of texels.
constexpr int kMaxCells = 1024;
/// The search's rows and positions tried, at most, over all its passes.
/// (The bunny's 137 charts at 1024² take 7.7M over 9 passes, about 0.45 s; 4,061 charts of a
/// noisy sphere would take 2.8G, about 35 s: they keep the rectangles' packing.)
constexpr std::uint64_t kMaxSteps = 40'000'000;

/// The raster of a chart at k cells per unit: fw × fh cells, q at k·q + (kMargin, kMargin).
std::array<int, 2> rasterSize(const ChartShape& s, double k) {
  return {int(std::floor(k * s.width + 2 * kMargin)) + 1,
          int(std::floor(k * s.height + 2 * kMargin)) + 1};
}

/// q at k cells per unit in its raster of fw × fh cells turned `turns` quarter turns
/// counter-clockwise: the turned raster is the raster turned texel for texel (a point in texel
/// (i, j) lands in texel (fh − 1 − j, i) after one turn), so one rasterisation serves all four.
Uv2 turnedTexel(const Uv2& q, double k, int turns, int fw, int fh) {
  const double x = k * q[0] + kMargin, y = k * q[1] + kMargin;
  switch (turns & 3) {
    case 1:
      return {fh - y, x};
    case 2:
      return {fw - x, fh - y};
    case 3:
      return {y, fw - x};
    default:
      return {x, y};
  }
}

/// Row runs [a, b] (inclusive) of a bitmap.
struct Runs {
  std::vector<std::uint32_t> rowStart;  ///< row r's runs: runs[rowStart[r], rowStart[r + 1])
  std::vector<std::array<int, 2>> runs;
  std::vector<int> widest;  ///< per row, its longest run's length (0: none)
  void fromBitmap(const std::vector<std::uint8_t>& bits, int w, int h) {
    rowStart.assign(std::size_t(h) + 1, 0);
    widest.assign(std::size_t(h), 0);
    runs.clear();
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* row = &bits[std::size_t(y) * w];
      for (int x = 0; x < w;) {
        if (!row[x]) {
          ++x;
          continue;
        }
        const int a = x;
        while (x < w && row[x]) ++x;
        runs.push_back({a, x - 1});
        widest[y] = std::max(widest[y], x - a);
      }
      rowStart[y + 1] = std::uint32_t(runs.size());
    }
  }
};

/// A chart at one scale and turn: its texels (`cover`) and those grown by the padding
/// (`grown`), both in the grown mask's frame: the turned raster with `pad` texels around it.
struct Mask {
  int width = 0, height = 0;  ///< the grown mask's
  Runs cover, grown;
};

/// A triangle's three edge normals and its extent along each: the separating axes it adds to a
/// box's own two (the separating axis test), computed once for the texels of its bounding box.
struct EdgeAxes {
  double nx[3], ny[3], lo[3], hi[3];
  explicit EdgeAxes(const Uv2 t[3]) {
    for (int e = 0; e < 3; ++e) {
      const Uv2& a = t[e];
      const Uv2& b = t[(e + 1) % 3];
      nx[e] = b[1] - a[1], ny[e] = a[0] - b[0];
      lo[e] = HUGE_VAL, hi[e] = -HUGE_VAL;
      for (int k = 0; k < 3; ++k) {
        const double s = t[k][0] * nx[e] + t[k][1] * ny[e];
        lo[e] = std::min(lo[e], s), hi[e] = std::max(hi[e], s);
      }
    }
  }
  /// True unless an edge normal parts the triangle from the square of side `size` centred at
  /// (cx, cy) (the box's own axes are the caller's: its texels lie in the bounding box).
  bool touches(double cx, double cy, double size) const {
    for (int e = 0; e < 3; ++e) {
      const double c = cx * nx[e] + cy * ny[e];
      const double r = 0.5 * size * (std::abs(nx[e]) + std::abs(ny[e]));
      if (c + r < lo[e] || c - r > hi[e]) return false;
    }
    return true;
  }
};

/// The chart's four turned masks at k texels per unit: every texel a triangle touches (grown by
/// kEps), then those grown by `pad` (a square of side 2·pad + 1), each turned.
std::array<Mask, 4> rasterise(const ChartShape& s, double k, int pad) {
  const auto [fw, fh] = rasterSize(s, k);
  const int W = fw + 2 * pad, H = fh + 2 * pad;
  std::vector<std::uint8_t> cover(std::size_t(W) * H, 0);
  for (const auto& tri : s.triangles) {
    Uv2 p[3];
    for (int c = 0; c < 3; ++c) p[c] = turnedTexel(s.uv[tri[c]], k, 0, fw, fh);
    const double lx = std::min({p[0][0], p[1][0], p[2][0]}) - kEps;
    const double hx = std::max({p[0][0], p[1][0], p[2][0]}) + kEps;
    const double ly = std::min({p[0][1], p[1][1], p[2][1]}) - kEps;
    const double hy = std::max({p[0][1], p[1][1], p[2][1]}) + kEps;
    const int x0 = std::max(0, int(std::floor(lx))), x1 = std::min(fw - 1, int(std::floor(hx)));
    const int y0 = std::max(0, int(std::floor(ly))), y1 = std::min(fh - 1, int(std::floor(hy)));
    if (x0 == x1 && y0 == y1) {  // inside one texel
      cover[std::size_t(y0 + pad) * W + (x0 + pad)] = 1;
      continue;
    }
    const EdgeAxes axes(p);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        std::uint8_t& c = cover[std::size_t(y + pad) * W + (x + pad)];
        if (!c && axes.touches(x + 0.5, y + 0.5, 1 + 2 * kEps)) c = 1;
      }
  }
  // Grown: rows, then columns.
  std::vector<std::uint8_t> rows(cover.size(), 0), grown(cover.size(), 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (cover[std::size_t(y) * W + x])
        for (int u = std::max(0, x - pad); u <= std::min(W - 1, x + pad); ++u)
          rows[std::size_t(y) * W + u] = 1;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (rows[std::size_t(y) * W + x])
        for (int v = std::max(0, y - pad); v <= std::min(H - 1, y + pad); ++v)
          grown[std::size_t(v) * W + x] = 1;
  std::array<Mask, 4> out;
  std::vector<std::uint8_t> a, b;
  for (int t = 0; t < 4; ++t) {
    Mask& m = out[t];
    m.width = t % 2 ? H : W;
    m.height = t % 2 ? W : H;
    a.assign(cover.size(), 0);
    b.assign(cover.size(), 0);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        // Texel (x, y) of the unturned frame, turned (the frame's padding is symmetric).
        const int u = t == 0 ? x : t == 1 ? H - 1 - y : t == 2 ? W - 1 - x : y;
        const int v = t == 0 ? y : t == 1 ? x : t == 2 ? H - 1 - y : W - 1 - x;
        const std::size_t from = std::size_t(y) * W + x, to = std::size_t(v) * m.width + u;
        a[to] = cover[from];
        b[to] = grown[from];
      }
    m.cover.fromBitmap(a, m.width, m.height);
    m.grown.fromBitmap(b, m.width, m.height);
  }
  return out;
}

/// The atlas's occupied texels, row by row as run lengths: run[y][x] > 0 is the number of free
/// texels from x on (to the next occupied one or the edge), < 0 minus the number of occupied
/// ones from x on.
class Occupancy {
 public:
  explicit Occupancy(int side)
      : side_(side), run_(std::size_t(side) * side), maxFree_(std::size_t(side)) {
    for (int y = 0; y < side; ++y) recount(y, nullptr);
  }

  /// The first position (lowest y, then lowest x) of mask m's grown lower corner at which its
  /// grown texels meet no occupied texel, inside the atlas, with y + m.height < stopTop; false
  /// if none. `steps` counts the rows and positions tried.
  bool firstFit(const Mask& m, int stopTop, int& gx, int& gy, std::uint64_t& steps) const {
    const int rows = m.height, cols = m.width;
    int hint = 0;  // the row that collided last: likely to collide again
    for (int y = 0; y + rows <= side_ && y + rows < stopTop; ++y) {
      ++steps;
      // A row whose longest free run is shorter than the mask's row there rules y out.
      bool room = true;
      for (int r = 0; r < rows && room; ++r) room = maxFree_[y + r] >= m.grown.widest[r];
      if (!room) continue;
      int x = 0;
      while (x + cols <= side_) {
        ++steps;
        int next = x;
        for (int i = 0; i < rows && next == x; ++i) {
          const int r = (hint + i) % rows;
          const std::int32_t* row = &run_[std::size_t(y + r) * side_];
          for (std::uint32_t j = m.grown.rowStart[r]; j < m.grown.rowStart[r + 1]; ++j) {
            const auto [a, b] = m.grown.runs[j];
            const int at = x + a;
            const std::int32_t v = row[at];
            if (v > b - a) continue;  // free from a to b
            // Occupied at `o`: every x' up to the end of that occupied run minus a collides.
            const int o = v > 0 ? at + v : at;
            next = o - row[o] - a;
            hint = r;
            break;
          }
        }
        if (next == x) {
          gx = x, gy = y;
          return true;
        }
        x = next;
      }
    }
    return false;
  }

  /// Marks mask m's (ungrown) texels occupied with its grown lower corner at (gx, gy).
  void place(const Mask& m, int gx, int gy) {
    for (int r = 0; r < m.height; ++r) {
      const std::uint32_t b = m.cover.rowStart[r], e = m.cover.rowStart[r + 1];
      if (b == e) continue;
      std::vector<std::uint8_t>& row = scratch_;
      row.assign(std::size_t(side_), 0);
      const std::int32_t* cur = &run_[std::size_t(gy + r) * side_];
      for (int x = 0; x < side_; ++x) row[x] = cur[x] < 0;
      for (std::uint32_t j = b; j < e; ++j)
        for (int x = m.cover.runs[j][0]; x <= m.cover.runs[j][1]; ++x) row[gx + x] = 1;
      recount(gy + r, row.data());
    }
  }

 private:
  void recount(int y, const std::uint8_t* occupied) {
    std::int32_t* row = &run_[std::size_t(y) * side_];
    std::int32_t free = 0, used = 0, widest = 0;
    for (int x = side_ - 1; x >= 0; --x) {
      if (occupied && occupied[x]) {
        free = 0;
        row[x] = -(++used);
      } else {
        used = 0;
        row[x] = ++free;
        widest = std::max(widest, free);
      }
    }
    maxFree_[y] = widest;
  }

  int side_;
  std::vector<std::int32_t> run_;
  std::vector<int> maxFree_;  ///< per row, its longest free run
  std::vector<std::uint8_t> scratch_;
};

enum class Packed { Yes, NoRoom, OutOfSteps };

/// Greedy placement in `side` × `side` cells at k cells per unit of the charts in `order`
/// (largest first), each at the turn whose first fit reaches least high (then lowest, then
/// leftmost, then fewest turns). Stops as soon as a chart finds no place, or `steps` (the search's,
/// counted on) reaches `maxSteps`.
Packed packAt(const std::vector<ChartShape>& charts, const std::vector<std::size_t>& order,
              int side, int pad, double k, std::uint64_t& steps, std::uint64_t maxSteps,
              AtlasPacking& out) {
  Occupancy atlas(side);
  out.texelsPerUnit = k * out.cell;
  out.charts.assign(charts.size(), {});
  out.rowsUsed = 0;
  for (std::size_t c : order) {
    const std::array<Mask, 4> masks = rasterise(charts[c], k, pad);
    int bestTop = side + 1, bestTurn = -1, bx = 0, by = 0;
    for (int t = 0; t < 4; ++t) {
      int gx, gy;
      if (!atlas.firstFit(masks[t], bestTop + 1, gx, gy, steps)) continue;
      const int top = gy + masks[t].height;
      if (bestTurn >= 0 && std::tie(top, gy, gx) >= std::tie(bestTop, by, bx)) continue;
      bestTop = top, bestTurn = t, bx = gx, by = gy;
    }
    if (steps >= maxSteps) return Packed::OutOfSteps;
    if (bestTurn < 0) return Packed::NoRoom;
    atlas.place(masks[bestTurn], bx, by);
    out.charts[c] = {bx + pad, by + pad, bestTurn};
    out.rowsUsed = std::max(out.rowsUsed, bestTop * out.cell);
  }
  return Packed::Yes;
}

}  // namespace

Uv2 AtlasPacking::texelPosition(const std::vector<ChartShape>& shapes, std::size_t c,
                                const Uv2& q) const {
  const Placement& p = charts[c];
  const double k = texelsPerUnit / cell;
  const auto [fw, fh] = rasterSize(shapes[c], k);
  const Uv2 t = turnedTexel(q, k, p.quarterTurns, fw, fh);
  return {(p.x + t[0]) * cell, (p.y + t[1]) * cell};
}

bool packChartShapes(const std::vector<ChartShape>& charts, int side, int padding,
                     double minTexelsPerUnit, AtlasPacking& out, const ProgressFn& progress) {
  // Largest area first (ties by index): a fixed order.
  std::vector<double> area(charts.size(), 0.0);
  double totalArea = 0;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    for (const auto& t : charts[c].triangles) {
      const Uv2 &a = charts[c].uv[t[0]], &b = charts[c].uv[t[1]], &d = charts[c].uv[t[2]];
      area[c] += 0.5 * std::abs((b[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (b[1] - a[1]));
    }
    totalArea += area[c];
  }
  const double maxTexelsPerUnit = side / std::sqrt(std::max(totalArea, 1e-300));
  std::vector<std::size_t> order(charts.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return area[a] > area[b]; });
  // Cells of `cell` × `cell` texels, at most kMaxCells a side: the search costs about the
  // square of the side, and a gutter of whole cells is at least `padding` texels.
  AtlasPacking best, trial;
  best.cell = trial.cell = (side + kMaxCells - 1) / kMaxCells;
  const int cells = side / best.cell, pad = (padding + best.cell - 1) / best.cell;
  double lo = minTexelsPerUnit / best.cell;
  double hi = std::max(maxTexelsPerUnit / best.cell, lo);
  std::uint64_t steps = 0;
  // The bisection's passes: the first, then one per halving of log(hi / lo) down to 0.2%.
  const double passes =
      2 + std::ceil(std::log2(std::max(std::log(hi / std::max(lo, 1e-300)) / std::log(1.002), 1.0)));
  int pass = 0;
  const auto report = [&] {
    ++pass;
    const double f = std::max(pass / passes, double(steps) / double(kMaxSteps));
    if (progress && !progress(std::min(f, 1.0))) throw Cancelled();
  };
  if (!(lo > 0) || packAt(charts, order, cells, pad, lo, steps, kMaxSteps, best) != Packed::Yes)
    return false;
  report();
  while (hi > lo * 1.002) {
    const double mid = std::sqrt(lo * hi);
    const Packed p = packAt(charts, order, cells, pad, mid, steps, kMaxSteps, trial);
    report();
    if (p == Packed::OutOfSteps) break;  // the best so far stands
    if (p == Packed::Yes) {
      lo = mid;
      std::swap(best, trial);
    } else {
      hi = mid;
    }
  }
  out = std::move(best);
  return true;
}

}  // namespace prt
