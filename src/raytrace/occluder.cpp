#include "prt/raytrace/occluder.hpp"

#include "prt/core/error.hpp"

namespace prt {

void Occluder::occluded(std::span<const Ray> rays, std::span<std::uint8_t> out) const {
  PRT_CHECK(out.size() >= rays.size(), "occluded: output span shorter than the rays");
  for (std::size_t k = 0; k < rays.size(); ++k) out[k] = occluded(rays[k]) ? 1 : 0;
}

void Occluder::intersect(std::span<const Ray> rays, std::span<Hit> out) const {
  PRT_CHECK(out.size() >= rays.size(), "intersect: output span shorter than the rays");
  for (std::size_t k = 0; k < rays.size(); ++k) out[k] = intersect(rays[k]);
}

}  // namespace prt
