#include "haar_view.hpp"

#include <algorithm>

#include "prt/haar/project_light.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/texel_points.hpp"

namespace prt::viewer {

namespace {
/// kHaarViewLightTerms, or all of an N² cube's coefficients where it has fewer.
std::size_t lightTerms(int resolution) {
  return std::min(kHaarViewLightTerms, haar::coefficientCount(resolution));
}
}  // namespace

haar::HaarLight haarRenderLight(const envmap::Environment& env, int resolution,
                                const Mat3d& rotation) {
  return haar::projectLight(env, resolution, lightTerms(resolution), rotation);
}

HaarViewLight::HaarViewLight(const envmap::Environment& env, int resolution)
    : env_(&env), resolution_(resolution) {
  if (resolution <= haar::kMaxTurnedResolution) cube_ = haar::environmentCube(env, resolution);
}

haar::HaarLight HaarViewLight::at(const Mat3d& rotation) const {
  if (!cube_) return haarRenderLight(*env_, resolution_, rotation);
  return haar::turnedLight(*cube_, resolution_, lightTerms(resolution_), rotation);
}

std::vector<Vec3f> haarTexelNormals(const Mesh& mesh, const Transfer& transfer) {
  const auto occluder = makeEmbreeOccluder(mesh);
  return render::texelRelight(mesh, *occluder, transfer, Material{}).points.normals;
}

}  // namespace prt::viewer
