#include "prt/haar/turned_cube.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/envmap/project.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/haar/resolution.hpp"

namespace prt::haar {

namespace {

/// envmap::cubeFaceCoords in double: the face a direction falls on and its (s, t) in [−1, 1]².
int faceCoords(const Vec3d& d, double& s, double& t) {
  const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  if (ax >= ay && ax >= az) {
    t = -d.y / ax;
    s = (d.x > 0 ? -d.z : d.z) / ax;
    return d.x > 0 ? 0 : 1;
  }
  if (ay >= az) {
    s = d.x / ay;
    t = (d.y > 0 ? d.z : -d.z) / ay;
    return d.y > 0 ? 2 : 3;
  }
  t = -d.y / az;
  s = (d.z > 0 ? d.x : -d.x) / az;
  return d.z > 0 ? 4 : 5;
}

}  // namespace

EnvironmentCube environmentCube(const envmap::Environment& env, int lightResolution) {
  checkResolution(lightResolution, "a turned Haar light");
  if (lightResolution > kMaxTurnedResolution)
    throw Error("a turned Haar light is made for cubes up to " +
                std::to_string(kMaxTurnedResolution) + "² a face, not " +
                std::to_string(lightResolution) + "²");
  EnvironmentCube c;
  c.resolution = kFineCubeFactor * lightResolution;
  c.means = cubeMeans(env, c.resolution);
  c.sh = envmap::projectEnvironment(env, kUnshadowedBands);
  return c;
}

std::vector<Rgb> turnCubeMeans(const EnvironmentCube& cube, int n, const Mat3d& rotation) {
  checkResolution(n, "a turned Haar light");
  const int m = cube.resolution, q = kSplatPoints;
  if (m < n || m % n != 0 || cube.means.size() != coefficientCount(m))
    throw Error("a turned Haar light: a cube of " + std::to_string(cube.means.size()) +
                " texel means at " + std::to_string(m) + "² a face does not refine a " +
                std::to_string(n) + "² cube");
  const std::vector<double> fine = envmap::cubeTexelSolidAngles(m),
                            coarse = envmap::cubeTexelSolidAngles(n);
  std::vector<Rgbd> power(coefficientCount(n), Rgbd(0.0));
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < m; ++y)
      for (int x = 0; x < m; ++x) {
        // The fine texel's power, in q² equal parts, each to the coarse texel its point turns to.
        const Rgbd part =
            Rgbd(cube.means[std::size_t(f) * m * m + std::size_t(y) * m + std::size_t(x)]) *
            (fine[std::size_t(y) * m + std::size_t(x)] / (q * q));
        for (int j = 0; j < q; ++j)
          for (int i = 0; i < q; ++i) {
            const double s = 2.0 * (x + (i + 0.5) / q) / m - 1.0;
            const double t = 2.0 * (y + (j + 0.5) / q) / m - 1.0;
            const Vec3d d = rotation * normalize(envmap::cubeFaceDirection(f, s, t));
            double fs = 0, ft = 0;
            const int face = faceCoords(d, fs, ft);
            const int cx = std::clamp(int((fs + 1) * 0.5 * n), 0, n - 1);
            const int cy = std::clamp(int((ft + 1) * 0.5 * n), 0, n - 1);
            power[std::size_t(face) * n * n + std::size_t(cy) * n + std::size_t(cx)] += part;
          }
      }
  std::vector<Rgb> out(coefficientCount(n));
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = Rgb(power[k] / coarse[k % coarse.size()]);
  return out;
}

HaarLight turnedLight(const EnvironmentCube& cube, int n, std::size_t terms, const Mat3d& rotation,
                      Selection selection) {
  const std::vector<Rgb> means = turnCubeMeans(cube, n, rotation);
  HaarLight light = approximate(means, n, terms, selection);
  UnshadowedPart part = unshadowedPart(cube.sh, means, n, rotation);
  light.unshadowed = std::move(part.sh);
  light.bright = std::move(part.bright);
  return light;
}

}  // namespace prt::haar
