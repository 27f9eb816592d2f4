#include "prt/io/lighting.hpp"

#include <algorithm>

#include "prt/envmap/load.hpp"
#include "prt/envmap/project.hpp"
#include "prt/io/light_file.hpp"

namespace prt::io {

Lighting loadLighting(const std::string& spec, int bands, const ProgressFn& progress) {
  Lighting l;
  l.name = spec;
  if (isLightFile(spec)) {
    const sh::RgbSh source = readLight(spec).coefficients;
    l.sourceBands = source.bands;
    l.coefficients = source.truncated(std::min(source.bands, bands));
    if (source.bands < bands)
      l.warnings.push_back(spec + ": the light has " + std::to_string(source.bands) +
                           " bands but the transfer " + std::to_string(bands) +
                           "; relighting with " + std::to_string(source.bands) +
                           " bands (the transfer's upper bands see no light; write it with prt "
                           "light --bands " +
                           std::to_string(bands) + ")");
    return l;
  }
  envmap::LoadedEnvironment loaded = envmap::loadEnvironment(spec);
  for (std::string& w : envmap::repairWarnings(loaded)) l.warnings.push_back(std::move(w));
  l.coefficients = envmap::projectEnvironment(loaded.env, bands, progress);
  l.image = std::move(loaded.env);
  return l;
}

sh::RgbSh padded(const sh::RgbSh& light, int bands) {
  if (light.bands >= bands) return light.truncated(bands);
  sh::RgbSh out(bands);
  std::copy(light.c.begin(), light.c.end(), out.c.begin());
  return out;
}

}  // namespace prt::io
