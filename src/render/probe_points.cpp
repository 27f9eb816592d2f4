#include "prt/render/probe_points.hpp"

#include <algorithm>
#include <vector>

#include "prt/render/validate.hpp"
#include "prt/transport/texel_validity.hpp"

namespace prt::render {

Vec3f probeNormal(int axis) {
  Vec3f n(0.0f);
  n[axis / 2] = axis % 2 == 0 ? 1.0f : -1.0f;
  return n;
}

RowPoints drawProbePoints(const Mesh& mesh, const Occluder& occluder, const ProbeGrid& grid,
                          std::size_t count, std::uint64_t seed) {
  const std::size_t n = grid.probes();
  const bool all = count == 0 || count >= n;
  const std::size_t want = all ? n : count;
  RandomOrder order = subsetOrder(all ? 0 : n, seed);
  std::size_t next = 0;  // every probe in row order, when `all`
  std::vector<std::uint32_t> kept;
  while (kept.size() < want && (all ? next < n : !order.done())) {
    // A few more than are missing, since some may lie inside geometry; extras are dropped in the
    // order drawn, so the probes kept do not depend on the batches.
    const std::size_t missing = want - kept.size();
    const std::size_t batch = all ? n : std::min(n - order.drawn(), missing + missing / 8 + 16);
    std::vector<std::uint32_t> drawn(batch);
    std::vector<Vec3f> positions(batch);
    for (std::size_t i = 0; i < batch; ++i) {
      drawn[i] = static_cast<std::uint32_t>(all ? next++ : order.next());
      positions[i] = grid.position(drawn[i]);
    }
    const std::vector<std::uint8_t> inside = insideGeometryAllAround(mesh, occluder, positions);
    for (std::size_t i = 0; i < batch && kept.size() < want; ++i)
      if (!inside[i]) kept.push_back(drawn[i]);
  }
  std::sort(kept.begin(), kept.end());
  RowPoints out;
  for (std::uint32_t p : kept)
    for (int a = 0; a < kProbeNormals; ++a) {
      out.rows.push_back(static_cast<std::uint32_t>(probeNormalRow(p, a)));
      out.positions.push_back(grid.position(p));
      out.normals.push_back(probeNormal(a));
    }
  out.valid = out.rows;
  return out;
}

}  // namespace prt::render
