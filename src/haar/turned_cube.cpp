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

/// The fine cube at direction d: bilinear between the four nearest texel centres of its face.
Rgbd lookup(const std::vector<Rgb>& means, int m, const Vec3d& d) {
  double s = 0, t = 0;
  const int f = faceCoords(d, s, t);
  const double u = (s + 1) * 0.5 * m - 0.5, v = (t + 1) * 0.5 * m - 0.5;
  const double fu = std::floor(u), fv = std::floor(v), wx = u - fu, wy = v - fv;
  const auto at = [&](double x, double y) {
    const int xi = std::clamp(int(x), 0, m - 1), yi = std::clamp(int(y), 0, m - 1);
    return Rgbd(means[std::size_t(f) * m * m + std::size_t(yi) * m + std::size_t(xi)]);
  };
  return (at(fu, fv) * (1 - wx) + at(fu + 1, fv) * wx) * (1 - wy) +
         (at(fu, fv + 1) * (1 - wx) + at(fu + 1, fv + 1) * wx) * wy;
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
  const int m = cube.resolution;
  if (m < n || m % n != 0 || cube.means.size() != coefficientCount(m))
    throw Error("a turned Haar light: a cube of " + std::to_string(cube.means.size()) +
                " texel means at " + std::to_string(m) + "² a face does not refine a " +
                std::to_string(n) + "² cube");
  const int sub = m / n;
  const std::vector<double> omega = envmap::cubeTexelSolidAngles(m);
  const Mat3d inverse = rotation.transposed();
  std::vector<Rgb> out(coefficientCount(n));
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        Rgbd sum(0.0);
        double weight = 0;
        for (int j = 0; j < sub; ++j)
          for (int i = 0; i < sub; ++i) {
            const int px = x * sub + i, py = y * sub + j;
            const double s = 2.0 * (px + 0.5) / m - 1.0, t = 2.0 * (py + 0.5) / m - 1.0;
            const Vec3d d = inverse * normalize(envmap::cubeFaceDirection(f, s, t));
            const double w = omega[std::size_t(py) * m + std::size_t(px)];
            sum += lookup(cube.means, m, d) * w;
            weight += w;
          }
        out[std::size_t(f) * n * n + std::size_t(y) * n + std::size_t(x)] = Rgb(sum / weight);
      }
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
