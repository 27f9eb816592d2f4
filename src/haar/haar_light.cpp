#include "prt/haar/haar_light.hpp"

#include <cmath>

#include "prt/core/error.hpp"
#include "prt/haar/cube_haar.hpp"

namespace prt::haar {

std::vector<Rgb> HaarLight::dense() const {
  std::vector<Rgb> out(coefficientCount(resolution), Rgb(0.0f));
  for (std::size_t t = 0; t < index.size(); ++t) out[index[t]] = value[t];
  return out;
}

void HaarLight::check(const std::string& what) const {
  checkResolution(resolution, what);
  if (index.size() != value.size())
    throw Error(what + ": " + std::to_string(index.size()) + " indices for " +
                std::to_string(value.size()) + " values");
  const std::size_t n = coefficientCount(resolution);
  for (std::size_t t = 0; t < index.size(); ++t) {
    if (index[t] >= n)
      throw Error(what + ": term " + std::to_string(t) + " has index " + std::to_string(index[t]) +
                  ", past the " + std::to_string(n) + " coefficients of the cube");
    if (t > 0 && index[t] <= index[t - 1])
      throw Error(what + ": term indices must ascend (term " + std::to_string(t) + ")");
    const Rgb& v = value[t];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw Error(what + ": term " + std::to_string(t) + " is not finite");
  }
  if (unshadowed.bands != kUnshadowedBands)
    throw Error(what + ": the unshadowed part's SH has " + std::to_string(unshadowed.bands) +
                " bands, expected " + std::to_string(kUnshadowedBands));
  for (const Rgb& v : unshadowed.c)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw Error(what + ": the unshadowed part's SH is not finite");
  if (bright.size() > kBrightTexels)
    throw Error(what + ": " + std::to_string(bright.size()) + " bright texels, at most " +
                std::to_string(kBrightTexels));
  for (std::size_t b = 0; b < bright.size(); ++b) {
    if (bright[b].texel >= n)
      throw Error(what + ": bright texel " + std::to_string(bright[b].texel) +
                  " is past the cube's " + std::to_string(n));
    for (std::size_t c = 0; c < b; ++c)
      if (bright[c].texel == bright[b].texel)
        throw Error(what + ": bright texel " + std::to_string(bright[b].texel) + " twice");
    if (!std::isfinite(bright[b].radiance.x) || !std::isfinite(bright[b].radiance.y) ||
        !std::isfinite(bright[b].radiance.z))
      throw Error(what + ": bright texel " + std::to_string(bright[b].texel) + " is not finite");
  }
  if (!(energyKept >= 0 && energyKept <= 1.0 + 1e-6))
    throw Error(what + ": the energy kept must lie in [0, 1]");
}

}  // namespace prt::haar
