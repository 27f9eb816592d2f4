#include "probe_domain.hpp"

#include <algorithm>

#include "prt/transport/texel_validity.hpp"

namespace prt::bakedetail {

std::size_t ProbeDomain::reach() const {
  const std::size_t nx = std::size_t(grid.count[0]), ny = std::size_t(grid.count[1]);
  return nx * ny + nx + 1;
}

RowRange ProbeDomain::widen(RowRange range) const {
  const std::size_t r = kProbeRefillRings * reach();
  const std::size_t lo = range.first > r ? range.first - r : 0;
  const std::size_t hi = std::min(grid.probes(), range.end() + r);
  return {lo, hi - lo};
}

void ProbeDomain::refill(float* values, RowRange rows, std::size_t stride) const {
  if (invalid.empty()) return;
  // good[r]: row r holds a value a neighbour may take (outside geometry, or refilled in an
  // earlier ring).
  std::vector<std::uint8_t> good(rows.count, 1);
  for (std::uint32_t r : invalid)
    if (r >= rows.first && r < rows.end()) good[r - rows.first] = 0;
  std::vector<double> sum(stride);
  for (int ring = 0; ring < kProbeRefillRings; ++ring) {
    std::vector<std::pair<std::size_t, std::vector<float>>> filled;
    for (std::uint32_t r : invalid) {
      if (r < rows.first || r >= rows.end() || good[r - rows.first]) continue;
      const auto c = grid.cell(r);
      std::fill(sum.begin(), sum.end(), 0.0);
      int n = 0;
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
            if ((dx | dy | dz) == 0 || x < 0 || y < 0 || z < 0 || x >= grid.count[0] ||
                y >= grid.count[1] || z >= grid.count[2])
              continue;
            const std::size_t q = grid.row(x, y, z);
            if (q < rows.first || q >= rows.end() || !good[q - rows.first]) continue;
            const float* v = values + (q - rows.first) * stride;
            for (std::size_t i = 0; i < stride; ++i) sum[i] += v[i];
            ++n;
          }
      if (n == 0) continue;
      std::vector<float> mean(stride);
      for (std::size_t i = 0; i < stride; ++i) mean[i] = float(sum[i] / n);
      filled.emplace_back(r, std::move(mean));
    }
    if (filled.empty()) break;
    for (auto& [r, mean] : filled) {
      std::copy(mean.begin(), mean.end(), values + (r - rows.first) * stride);
      good[r - rows.first] = 1;
    }
  }
}

ProbeDomain makeProbeDomain(const Mesh& mesh, const Occluder& occluder, const ProbeGrid& grid,
                            RowRange keep) {
  ProbeDomain d;
  d.grid = grid;
  d.kept = keep;
  std::vector<Vec3f> positions(keep.count);
  d.points.resize(keep.count);
  for (std::size_t i = 0; i < keep.count; ++i) {
    const std::size_t r = keep.first + i;
    positions[i] = grid.position(r);
    d.points[i] = RowPoint{positions[i], Vec3f(0.0f), r};
  }
  d.inside = insideGeometryAllAround(mesh, occluder, positions);
  for (std::size_t i = 0; i < keep.count; ++i) {
    if (d.inside[i]) d.invalid.push_back(static_cast<std::uint32_t>(keep.first + i));
  }
  return d;
}

}  // namespace prt::bakedetail
