// Rotating the light is rotating the world: relighting a bake under the light rotated by R
// (sh::Rotation on its coefficients) must equal relighting a bake of the scene turned by R⁻¹
// under the unrotated light. L'(ω) = L(Rᵀω), so the radiance at p of scene S under L' is the
// radiance at Rᵀp of the scene RᵀS under L. The two bakes draw different directions (each
// vertex's sampling frame follows its normal), so they agree within Monte Carlo error, not
// bit for bit.

#include <gtest/gtest.h>

#include <cmath>

#include "prt/envmap/builtin.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/transport/bake.hpp"

namespace prt {
namespace {

Mesh turned(Mesh mesh, const Mat3d& r) {
  for (Vec3f& p : mesh.positions) p = Vec3f(r * Vec3d(p));
  for (Vec3f& n : mesh.normals) n = normalize(Vec3f(r * Vec3d(n)));
  return mesh;
}

std::vector<Rgb> bakeAndRelight(const Mesh& mesh, const sh::RgbSh& light, const Mat3d& rotation,
                                double* stdErr) {
  const auto occluder = makeEmbreeOccluder(mesh);
  BakeSettings s;
  s.mode = TransferMode::Shadowed;
  s.bands = light.bands;
  s.samples = 2048;
  BakeStats stats;
  const Transfer t = bake(mesh, *occluder, s, &stats);
  *stdErr = stats.stdErrConstMean;
  return relight::relight(t, light, Material{}, {{}, {}, mesh.albedo}, Vec3f(0.0f), rotation);
}

double rmsDifference(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) sum += (double(a[i][c]) - b[i][c]) * (double(a[i][c]) - b[i][c]);
  return std::sqrt(sum / (3.0 * a.size()));
}

TEST(Relight, RotatingTheLightEqualsBakingTheSceneRotatedBack) {
  // A sphere over a plane (the sphere shadows the plane), lit by the sky with its sun low in
  // the east, at 4 bands.
  const Mesh scene = builtinScene("builtin:sphere-plane?grid=24&subdiv=3&size=2");
  const sh::RgbSh light = envmap::projectEnvironment(
      envmap::builtinEnvironment("builtin:sky?elevation=35&azimuth=60", 128), 4);
  const Mat3d r = rotationEulerXYZ(25, 70, -10);

  double seA = 0, seB = 0;
  const std::vector<Rgb> lightTurned = bakeAndRelight(scene, light, r, &seA);
  const std::vector<Rgb> sceneTurnedBack =
      bakeAndRelight(turned(scene, r.transposed()), light, Mat3d::identity(), &seB);
  const std::vector<Rgb> wrongWay =
      bakeAndRelight(turned(scene, r), light, Mat3d::identity(), &seB);

  double rms = 0;
  for (const Rgb& c : lightTurned) rms += (double(c.x) * c.x + double(c.y) * c.y + c.z * c.z) / 3;
  rms = std::sqrt(rms / lightTurned.size());
  ASSERT_GT(rms, 0.05);
  // The light's magnitude per unit of √(4π)·T₀ bounds how far each bake's noise moves the
  // radiance; the difference of two independent bakes is within a few such standard errors.
  const double scale = std::abs(light.c[0].y) / std::sqrt(4 * kPi);
  const double noise = std::sqrt(seA * seA + seB * seB) * scale * 2;
  const double same = rmsDifference(lightTurned, sceneTurnedBack);
  EXPECT_LT(same, 3 * noise) << "rms radiance " << rms;
  EXPECT_LT(same, 0.01 * rms);
  // Turning the scene the wrong way is far off: the comparison can fail.
  EXPECT_GT(rmsDifference(lightTurned, wrongWay), 10 * same);
}

}  // namespace
}  // namespace prt
