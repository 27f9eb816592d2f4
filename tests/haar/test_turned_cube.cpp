// A Haar light turned from the environment's finer cube (haar/turned_cube.hpp), what the browser
// viewers relight with, against the light projectLight makes from the environment itself:
//   * power is kept exactly under any turn, and a constant environment's means scatter by no more
//     than the splat's share of points allows;
//   * unturned, the means are the fine cube's texels averaged over the coarse texel, exactly;
//   * a disc's power survives turning exactly, and it lands where the turn sends it;
//   * relit through a Haar bake under builtin:sky at several turns, the radiance is projectLight's
//     within a few per cent (what docs/haar.md states), while the light turned the wrong way is
//     not (the comparison can fail).

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "prt/core/error.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/haar/turned_cube.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/transport/bake.hpp"

namespace prt::haar {
namespace {

double power(const std::vector<Rgb>& means, int n, int channel) {
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(n);
  double p = 0;
  for (std::size_t k = 0; k < means.size(); ++k)
    p += double(means[k][std::size_t(channel)]) * omega[k % omega.size()];
  return p;
}

const Mat3d kTurns[] = {rotationEulerXYZ(20, -35, 10), rotationEulerXYZ(0, 90, 0),
                        rotationEulerXYZ(-60, 15, 140)};

TEST(TurnedCube, PowerIsKeptAndAConstantEnvironmentStaysNearlyConstant) {
  const envmap::Environment one =
      envmap::Environment::analytic([](const Vec3f&) { return Rgb(1.0f); }, {});
  const EnvironmentCube cube = environmentCube(one, 8);
  EXPECT_EQ(cube.resolution, 32);
  double scatter = 0;
  for (const Mat3d& r : kTurns) {
    const std::vector<Rgb> means = turnCubeMeans(cube, 8, r);
    EXPECT_NEAR(power(means, 8, 0), 4 * kPi, 1e-5);
    for (const Rgb& m : means) scatter = std::max(scatter, std::abs(double(m.x) - 1));
  }
  // Each coarse texel takes the points that turn into it: 64 of them, give or take a few.
  EXPECT_LT(scatter, 0.15);
  EXPECT_GT(scatter, 0.0);  // turned, the share is not exact
  std::cout << "a constant environment turned: its means scatter by " << scatter << "\n";
}

TEST(TurnedCube, UnturnedMeansAreTheFineCubeAveraged) {
  const envmap::Environment sky = envmap::builtinEnvironment("builtin:sky");
  const int n = 8;
  const EnvironmentCube cube = environmentCube(sky, n);
  const std::vector<Rgb> coarse = turnCubeMeans(cube, n, Mat3d::identity());
  const int m = cube.resolution, sub = m / n;
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(m);
  for (std::size_t j = 0; j < coarse.size(); ++j) {
    const CubeTexel t = cubeTexel(std::uint32_t(j), n);
    Rgbd sum(0.0);
    double w = 0;
    for (int y = t.y * sub; y < (t.y + 1) * sub; ++y)
      for (int x = t.x * sub; x < (t.x + 1) * sub; ++x) {
        const double o = omega[std::size_t(y) * m + std::size_t(x)];
        sum +=
            Rgbd(cube.means[std::size_t(t.face) * m * m + std::size_t(y) * m + std::size_t(x)]) * o;
        w += o;
      }
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(coarse[j][std::size_t(c)], sum[std::size_t(c)] / w,
                  1e-5 * std::max(1.0, sum[std::size_t(c)] / w))
          << "texel " << j;
  }
}

TEST(TurnedCube, ADiscKeepsItsPowerAndGoesWhereTheTurnSendsIt) {
  envmap::Cap cap;
  cap.direction = normalize(Vec3f(0.3f, 0.8f, -0.5f));
  cap.halfAngle = 0.004;  // far smaller than a fine texel
  cap.radiance = Rgb(5e4f);
  const envmap::Environment sun =
      envmap::Environment::analytic([](const Vec3f&) { return Rgb(0.0f); }, {cap});
  const int n = 16;
  const EnvironmentCube cube = environmentCube(sun, n);
  const double exact = cap.power().x;
  for (const Mat3d& r : kTurns) {
    const std::vector<Rgb> means = turnCubeMeans(cube, n, r);
    EXPECT_NEAR(power(means, n, 0), exact, 1e-5 * exact);
    // The brightest texel is where R sends the disc's centre, or beside it.
    std::size_t top = 0;
    for (std::size_t k = 1; k < means.size(); ++k)
      if (means[k].x > means[top].x) top = k;
    const Vec3f to = Vec3f(r * Vec3d(cap.direction));
    const CubeTexel want = cubeTexel(texelOf(to, n), n), got = cubeTexel(std::uint32_t(top), n);
    EXPECT_EQ(got.face, want.face);
    EXPECT_LE(std::abs(got.x - want.x), 1);
    EXPECT_LE(std::abs(got.y - want.y), 1);
  }
}

TEST(TurnedCube, RelightsAsTheLightProjectedFromTheEnvironment) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?grid=16&subdiv=3");
  const auto occ = makeEmbreeOccluder(mesh);
  BakeSettings s;
  s.mode = TransferMode::Shadowed;
  s.basis = TransferBasis::Haar;
  s.haar = {16, 96};
  s.samples = 1;
  const Transfer t = bake(mesh, *occ, s);
  const envmap::Environment sky = envmap::builtinEnvironment("builtin:sky");
  const EnvironmentCube cube = environmentCube(sky, 16);
  const auto rel = [](const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    double e = 0, r = 0;
    for (std::size_t v = 0; v < a.size(); ++v)
      for (int c = 0; c < 3; ++c) {
        const double d = double(a[v][std::size_t(c)]) - b[v][std::size_t(c)];
        e += d * d;
        r += double(b[v][std::size_t(c)]) * b[v][std::size_t(c)];
      }
    return std::sqrt(e / r);
  };
  double worst = 0;
  for (const Mat3d& r : {Mat3d::identity(), kTurns[0], kTurns[1], kTurns[2]}) {
    const std::vector<Rgb> exact =
        relight::relightHaar(t, projectLight(sky, 16, kDefaultLightTerms, r), mesh.normals, {});
    const std::vector<Rgb> turned =
        relight::relightHaar(t, turnedLight(cube, 16, kDefaultLightTerms, r), mesh.normals, {});
    const double e = rel(turned, exact);
    worst = std::max(worst, e);
    EXPECT_LT(e, 0.01);
    // Turned the other way, the sun's shadow falls elsewhere.
    const std::vector<Rgb> wrong = relight::relightHaar(
        t, turnedLight(cube, 16, kDefaultLightTerms, r.transposed()), mesh.normals, {});
    if (!(r == Mat3d::identity())) {
      EXPECT_GT(rel(wrong, exact), 10 * e + 0.02);
    }
  }
  std::cout << "the turned light against projectLight's, relit (sphere over a plane, builtin:sky, "
               "16² cube): worst rel. RMSE "
            << worst << "\n";
}

TEST(TurnedCube, BadCubesAreRefused) {
  const envmap::Environment sky = envmap::builtinEnvironment("builtin:sky");
  EXPECT_THROW(environmentCube(sky, 128), Error);  // past kMaxTurnedResolution
  EXPECT_THROW(environmentCube(sky, 12), Error);
  EnvironmentCube cube = environmentCube(sky, 4);
  EXPECT_THROW(turnCubeMeans(cube, 32, Mat3d::identity()), Error);  // coarser than asked
  cube.means.pop_back();
  EXPECT_THROW(turnCubeMeans(cube, 4, Mat3d::identity()), Error);
}

}  // namespace
}  // namespace prt::haar
