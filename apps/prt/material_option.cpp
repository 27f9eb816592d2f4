#include "material_option.hpp"

#include "cli.hpp"

namespace prt::cli {

Material materialOption(const std::string& spec, const BakeSettings& baked, const std::string& file,
                        const std::string& consequence) {
  if (spec.empty()) return baked.material;
  Material m = parseMaterial(spec);
  if (!m.diffuse) m.diffuse = baked.material.diffuse;
  if (glossyBounces(baked) &&
      !(m.lobe == baked.material.lobe && m.specular == baked.material.specular))
    warn(file + ": its bounces were baked off " + baked.material.spec() + "; " + consequence);
  return m;
}

}  // namespace prt::cli
