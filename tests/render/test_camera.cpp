// The one camera convention (render/camera.hpp): the OpenGL matrices the viewers rasterise with
// put every point where RayGenerator::project (prt render) puts it, and the framing the web page
// receives as numbers gives frameMesh's camera.

#include <gtest/gtest.h>

#include "prt/geometry/builtin.hpp"
#include "prt/render/camera.hpp"

namespace prt::render {
namespace {

TEST(Camera, ViewProjectionMatchesRayGeneratorProject) {
  const Mesh mesh = builtinScene("cornell");
  const int w = 320, h = 200;
  for (const Camera& cam :
       {frameMesh(mesh, w, h), parseCamera("eye=3,1,-2;target=0.1,0.2,0;up=0,1,0.2;fov=55", {})}) {
    const RayGenerator rays(cam, w, h);
    const Mat4f vp = multiply(projectionMatrix(cam, w, h, 0.1f, 100.0f), viewMatrix(cam));
    int seen = 0;
    for (const Vec3f& p : mesh.positions) {
      float px, py;
      if (!rays.project(p, px, py)) continue;
      ++seen;
      float clip[4];
      for (int r = 0; r < 4; ++r)
        clip[r] = vp[r] * p.x + vp[4 + r] * p.y + vp[8 + r] * p.z + vp[12 + r];
      ASSERT_GT(clip[3], 0.0f);
      // ndc → pixels with row 0 at the top, as the file comment of camera.hpp says.
      EXPECT_NEAR(0.5f * (clip[0] / clip[3] + 1.0f) * w, px, 2e-3f);
      EXPECT_NEAR(0.5f * (1.0f - clip[1] / clip[3]) * h, py, 2e-3f);
    }
    EXPECT_GT(seen, 10);
  }
  // Depth: −1 at the near plane, +1 at the far plane, along forward.
  const Camera cam = frameMesh(mesh, w, h);
  const CameraBasis b = cameraBasis(cam, w, h);
  const Mat4f vp = multiply(projectionMatrix(cam, w, h, 0.5f, 20.0f), viewMatrix(cam));
  for (const auto& [z, want] : {std::pair{0.5f, -1.0f}, std::pair{20.0f, 1.0f}}) {
    const Vec3f p = cam.eye + b.forward * z;
    float clip[4];
    for (int r = 0; r < 4; ++r)
      clip[r] = vp[r] * p.x + vp[4 + r] * p.y + vp[8 + r] * p.z + vp[12 + r];
    EXPECT_NEAR(clip[2] / clip[3], want, 1e-4f);
  }
}

TEST(Camera, BasisIsOrthonormalLookAt) {
  const Camera cam = parseCamera("eye=1,2,3;target=0,0,0;up=0,1,0;fov=50", {});
  const CameraBasis b = cameraBasis(cam, 400, 300);
  EXPECT_NEAR(length(b.forward - normalize(Vec3f{-1, -2, -3})), 0.0f, 1e-6f);
  EXPECT_NEAR(dot(b.right, b.forward), 0.0f, 1e-6f);
  EXPECT_NEAR(dot(b.up, b.forward), 0.0f, 1e-6f);
  EXPECT_NEAR(dot(b.up, b.right), 0.0f, 1e-6f);
  EXPECT_NEAR(b.right.y, 0.0f, 1e-6f);  // right is horizontal for a +Y up
  EXPECT_GT(b.up.y, 0.0f);
  EXPECT_NEAR(length(cross(b.right, b.up) - (-b.forward)), 0.0f, 1e-6f);  // right-handed, −Z view
  EXPECT_NEAR(b.tanY, std::tan(25.0f * kPif / 180.0f), 1e-6f);
  EXPECT_NEAR(b.tanX, b.tanY * 4.0f / 3.0f, 1e-6f);
}

TEST(Camera, ZeroOrbitIsTheCameraAndFramingIsFrameMesh) {
  const Mesh mesh = builtinScene("sphere-plane");
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{300, 500}}) {
    const Camera framed = frameMesh(mesh, w, h);
    const Camera again = frameCamera(meshFraming(mesh), w, h);
    EXPECT_EQ(again.eye, framed.eye);
    EXPECT_EQ(again.target, framed.target);
    EXPECT_EQ(again.up, framed.up);
    const Camera same = orbitCamera(framed, Orbit{});
    EXPECT_EQ(same.eye, framed.eye);
    EXPECT_EQ(same.target, framed.target);
  }
  // Portrait frames pull back: the sphere must fit the narrower, horizontal field.
  const Framing f = meshFraming(mesh);
  const float landscape = length(frameCamera(f, 640, 480).eye - f.centre);
  const float portrait = length(frameCamera(f, 480, 640).eye - f.centre);
  EXPECT_NEAR(landscape, f.margin * f.radius / std::sin(20.0f * kPif / 180.0f), 1e-4f);
  EXPECT_GT(portrait, 1.2f * landscape);
}

}  // namespace
}  // namespace prt::render
