#include "prt/transfer/probe_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "prt/core/error.hpp"

namespace prt {

namespace {

std::string number(float x) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", double(x));
  return b;
}

}  // namespace

std::string ProbeGrid::describe() const {
  std::string s = std::to_string(count[0]) + " x " + std::to_string(count[1]) + " x " +
                  std::to_string(count[2]) + " probes, ";
  if (spacing.x == spacing.y && spacing.y == spacing.z) return s + number(spacing.x) + " apart";
  return s + number(spacing.x) + " x " + number(spacing.y) + " x " + number(spacing.z) + " apart";
}

ProbeGrid makeProbeGrid(const Vec3f& lo, const Vec3f& hi, std::array<int, 3> counts,
                        const std::string& what) {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || !(hi[a] >= lo[a]))
      throw Error(what, "the probe bounds (" + number(lo.x) + "," + number(lo.y) + "," +
                            number(lo.z) + " to " + number(hi.x) + "," + number(hi.y) + "," +
                            number(hi.z) + ") are not a box (finite, low <= high)");
    if (counts[a] < 0 || counts[a] > kMaxProbeSide)
      throw Error(what, "a probe grid has 1.." + std::to_string(kMaxProbeSide) +
                            " probes along each axis (got " + std::to_string(counts[a]) + ")");
  }
  const Vec3f extent = hi - lo;
  const float longest = std::max({extent.x, extent.y, extent.z});
  ProbeGrid g;
  for (int a = 0; a < 3; ++a) {
    int n = counts[a];
    if (n == 0)
      n = longest > 0 ? std::clamp(int(std::ceil(extent[a] / longest * kAutoProbeCells - 1e-3f)),
                                   1, kAutoProbeCells)
                      : 1;
    g.count[a] = n;
    // A flat side (extent 0) keeps a spacing that is positive: the one of the longest side.
    const float cell = extent[a] > 0 ? extent[a] / float(n) : (longest > 0 ? longest / 16 : 1.0f);
    g.spacing[a] = cell;
    g.origin[a] = extent[a] > 0 ? lo[a] + 0.5f * cell : lo[a];
  }
  checkProbeGrid(g, what);
  return g;
}

void checkProbeGrid(const ProbeGrid& g, const std::string& what) {
  for (int a = 0; a < 3; ++a) {
    if (g.count[a] < 1 || g.count[a] > kMaxProbeSide)
      throw Error(what, "a probe grid has 1.." + std::to_string(kMaxProbeSide) +
                            " probes along each axis (got " + std::to_string(g.count[0]) + " x " +
                            std::to_string(g.count[1]) + " x " + std::to_string(g.count[2]) + ")");
    if (!std::isfinite(g.origin[a]) || !std::isfinite(g.spacing[a]) || !(g.spacing[a] > 0))
      throw Error(what, "the probe grid's origin and spacing must be finite, its spacing > 0");
  }
  if (g.probes() > kMaxProbes)
    throw Error(what, "a probe grid of " + std::to_string(g.probes()) + " probes is over the " +
                          std::to_string(kMaxProbes) + " a bake holds");
}

}  // namespace prt
