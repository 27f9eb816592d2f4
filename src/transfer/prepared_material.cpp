#include "prt/transfer/prepared_material.hpp"

#include <vector>

#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"

namespace prt {

PreparedMaterial prepareMaterial(const Material& material, int bands) {
  sh::checkBands(bands);
  PreparedMaterial p;
  p.bands = bands;
  p.specular = material.specular;
  p.kd = material.diffuse;
  const std::vector<double> a = sh::clampedCosineKernel(bands);
  const std::vector<double> g =
      material.glossy() ? material.lobe.zonal(bands) : std::vector<double>{};
  p.diffuse.resize(static_cast<std::size_t>(bands * bands));
  if (!g.empty()) p.glossy.resize(p.diffuse.size());
  for (int l = 0; l < bands; ++l)
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) {
      p.diffuse[i] = static_cast<float>(a[l] / kPi);
      if (!g.empty()) p.glossy[i] = static_cast<float>(g[l]);
    }
  return p;
}

void PreparedMaterial::responses(const Vec3f& position, const Vec3f& normal, const Vec3f& eye,
                                 float* d, float* g, float* scratch) const {
  const std::size_t nB = diffuse.size();
  sh::eval(bands, normal, scratch);
  for (std::size_t i = 0; i < nB; ++i) d[i] = diffuse[i] * scratch[i];
  if (glossy.empty()) return;
  const Vec3f toEye = eye - position;
  const float len = length(toEye);
  sh::eval(bands, reflectView(normal, len > 0 ? toEye / len : normal), scratch);
  for (std::size_t i = 0; i < nB; ++i) g[i] = glossy[i] * scratch[i];
}

}  // namespace prt
