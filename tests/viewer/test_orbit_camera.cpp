// prt view's orbit camera is the library's camera plus yaw, pitch, distance and pan: at rest its
// view matrix is render::frameMesh's, and a yaw turns the view about the up axis through the
// target.

#include <gtest/gtest.h>

#include <cmath>

#include "prt/geometry/builtin.hpp"
#include "prt/render/camera.hpp"
#include "scene.hpp"

namespace prt::viewer::test {
namespace {

void expectSameMatrix(const render::Mat4f& got, const render::Mat4f& want, float tol) {
  for (int k = 0; k < 16; ++k) EXPECT_NEAR(got[k], want[k], tol) << "element " << k;
}

/// M · (p, 1), the xyz of the result.
Vec3d apply(const render::Mat4f& m, const Vec3d& p) {
  Vec3d r;
  for (int row = 0; row < 3; ++row)
    (&r.x)[row] = m[row] * p.x + m[4 + row] * p.y + m[8 + row] * p.z + m[12 + row];
  return r;
}

TEST(OrbitCamera, AtRestItsViewIsFrameMeshs) {
  const Mesh mesh = builtinScene("cornell");
  for (const auto& [w, h] : {std::pair{320, 240}, std::pair{240, 320}}) {
    const render::Camera framed = render::frameMesh(mesh, w, h);
    const OrbitCamera orbit(framed);
    expectSameMatrix(orbit.view(), render::viewMatrix(framed), 1e-6f);
    // The camera itself comes back bit for bit (so prt view's first frame is prt render's).
    EXPECT_EQ(orbit.camera().eye, framed.eye);
    EXPECT_EQ(orbit.camera().target, framed.target);
    EXPECT_EQ(orbit.camera().up, framed.up);
    EXPECT_EQ(orbit.camera().fovY, framed.fovY);
  }
  // After moving and resetting, the same again; a moved camera's view differs.
  OrbitCamera orbit(render::frameMesh(mesh, 320, 240));
  orbit.orbit(0.3, 0.1);
  orbit.zoom(0.5);
  orbit.pan(0.1, 0.0);
  float moved = 0;
  const render::Mat4f rest = render::viewMatrix(render::frameMesh(mesh, 320, 240));
  for (int k = 0; k < 16; ++k) moved = std::max(moved, std::abs(orbit.view()[k] - rest[k]));
  EXPECT_GT(moved, 0.1f);
  orbit.reset();
  expectSameMatrix(orbit.view(), rest, 0.0f);
}

TEST(OrbitCamera, YawIsARotationAboutTheUpAxisThroughTheTarget) {
  const Mesh mesh = builtinScene("cornell");
  const render::Camera start = render::frameMesh(mesh, 320, 240);
  const Vec3d target(start.target), axis = normalize(Vec3d(start.up));
  for (double yaw : {0.4, -1.3, 2.5}) {
    OrbitCamera orbit(start);
    orbit.orbit(yaw, 0.0);
    const render::Mat4f before = render::viewMatrix(start), after = orbit.view();
    // A world point turned by yaw about the axis looks, from the turned camera, exactly as the
    // point did from the start: view_after(R p) = view_before(p) for R = rotation about the axis
    // (target, up) by yaw.
    const Mat3d R = rotationAxisAngle(axis, yaw);
    for (const Vec3d& p : {Vec3d{0, 0, 0}, Vec3d{1, 2, 3}, Vec3d{-0.5, 0.25, 2}, target}) {
      const Vec3d turned = target + R * (p - target);
      const Vec3d a = apply(after, turned), b = apply(before, p);
      EXPECT_NEAR(length(a - b), 0.0, 1e-5 * (1 + length(b))) << "yaw " << yaw;
    }
    // The eye keeps its height along up and its distance to the target; the target stays.
    const render::Camera c = orbit.camera();
    EXPECT_NEAR(dot(Vec3d(c.eye) - target, axis), dot(Vec3d(start.eye) - target, axis), 1e-5);
    EXPECT_NEAR(length(Vec3d(c.eye) - target), length(Vec3d(start.eye) - target), 1e-5);
    EXPECT_EQ(c.target, start.target);
    // A positive yaw moves the eye toward the camera's right.
    if (std::abs(yaw) < 1.5) {
      const render::CameraBasis b = render::cameraBasis(start, 320, 240);
      EXPECT_EQ(dot(c.eye - start.eye, b.right) > 0, yaw > 0) << "yaw " << yaw;
    }
  }
}

TEST(OrbitCamera, PitchIsClampedShortOfThePoles) {
  const render::Camera start = render::frameMesh(builtinScene("cornell"), 320, 240);
  OrbitCamera orbit(start);
  orbit.orbit(0.0, 10.0);  // far past straight up
  const Vec3d d = normalize(Vec3d(orbit.camera().eye) - Vec3d(orbit.camera().target));
  EXPECT_NEAR(std::asin(d.y) * 180.0 / kPi, render::kMaxOrbitElevationDegrees, 1e-6);
  orbit.orbit(0.0, -0.1);  // and back down at once: no wound-up pitch to undo first
  const Vec3d e = normalize(Vec3d(orbit.camera().eye) - Vec3d(orbit.camera().target));
  EXPECT_NEAR(std::asin(e.y), (render::kMaxOrbitElevationDegrees * kPi / 180.0) - 0.1, 1e-6);
}

}  // namespace
}  // namespace prt::viewer::test
