#include "validation_errors.hpp"

#include <algorithm>
#include <cmath>

#include "prt/image/image.hpp"
#include "prt/render/metrics.hpp"

namespace prt::render {

namespace {

/// Per-vertex values as a one-row image, so render::metrics applies unchanged.
image::Image row(const std::vector<Rgb>& v) {
  image::Image img(static_cast<int>(v.size()), 1);
  std::copy(v.begin(), v.end(), img.pixels.begin());
  return img;
}

}  // namespace

ErrorColumns errorColumns(const Metric& metric, const std::vector<Rgb>& prt,
                          const std::vector<char>& counted, double negativeBelow,
                          std::size_t negativeVertices, std::vector<float>* err) {
  const std::vector<Rgb>& ref = metric.ref;
  const std::size_t n = ref.size();
  if (err) err->assign(n, 0.0f);
  double sum = 0, mx = 0, diffEnergy = 0, refEnergy = 0;
  std::size_t negative = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d2 = sumSq(prt[i] - ref[i]), r2 = sumSq(ref[i]);
    const double e = std::sqrt(d2 / (r2 + 3 * metric.eps));
    if (err) (*err)[i] = static_cast<float>(e);
    sum += e;
    mx = std::max(mx, e);
    diffEnergy += d2;
    refEnergy += r2;
    if (counted[i] && std::min({prt[i].x, prt[i].y, prt[i].z}) < negativeBelow) ++negative;
  }
  ErrorColumns c;
  c.relRmse = relativeRmse(row(prt), row(ref), metric.eps);
  // Energy-weighted: ‖R − R_ref‖ / ‖R_ref‖ over all vertices and channels, i.e. e(p)² weighted
  // by each vertex's share of the reference energy (no ε): bright vertices count most.
  c.energyRel = refEnergy > 0 ? std::sqrt(diffEnergy / refEnergy) : 0.0;
  c.meanRel = sum / double(std::max<std::size_t>(n, 1));
  c.maxRel = mx;
  c.negativeShare = negativeVertices > 0 ? double(negative) / double(negativeVertices) : 0.0;
  return c;
}

}  // namespace prt::render
