#pragma once
// A pinhole camera and its primary rays. World is right-handed, +Y up; the camera looks from
// `eye` toward `target` with `up` as the approximate up direction; `fovY` is the full vertical
// field of view in degrees. Image pixel (x, y) has row 0 at the top; a continuous image point
// (px, py) ∈ [0, w] × [0, h] maps to the ray through
//   ndc = (2 px / w − 1, 1 − 2 py / h),
//   dir ∝ forward + ndc.x · tan(fovY/2) · aspect · right + ndc.y · tan(fovY/2) · up'.

#include <string>

#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"

namespace prt::render {

struct Camera {
  Vec3f eye{0.0f, 0.0f, 3.0f};
  Vec3f target{0.0f, 0.0f, 0.0f};
  Vec3f up{0.0f, 1.0f, 0.0f};
  float fovY = 40.0f;  ///< degrees, full vertical angle
};

/// The default viewing direction (from the target toward the eye): in front (+Z), a little to
/// the right and above (about 20° azimuth, 25° elevation), so tops and one side are visible.
Vec3f defaultViewDirection();

/// Frames a bounding sphere: looks at `centre` from `viewDir` (target → eye), at the distance
/// where the sphere, grown by `margin`, fits both the vertical and the horizontal field of view
/// of a `width`×`height` image: d = margin · r / sin(min(fovY, fovX) / 2).
Camera frameSphere(const Vec3f& centre, float radius, int width, int height, float fovY = 40.0f,
                   const Vec3f& viewDir = defaultViewDirection(), float margin = 1.05f);
/// frameSphere on a bounding sphere of the mesh: centred on its bounds, radius to the farthest
/// vertex.
Camera frameMesh(const Mesh& mesh, int width, int height);

/// Parses "eye=x,y,z;target=x,y,z;up=x,y,z;fov=deg" (any subset, any order, ';' or ' '
/// separated); missing keys keep the values of `base`. Throws prt::Error naming the bad item.
Camera parseCamera(const std::string& spec, const Camera& base);

/// Precomputed camera frame for generating rays quickly.
class RayGenerator {
 public:
  RayGenerator(const Camera& camera, int width, int height);
  /// The primary ray through continuous image point (px, py) (see the file comment).
  Ray ray(float px, float py) const;
  /// Image point where world point p projects; false when p is behind the camera.
  bool project(const Vec3f& p, float& px, float& py) const;

 private:
  Vec3f eye_, forward_, right_, up_;
  float tanY_, tanX_;
  int width_, height_;
};

/// Heuristic: true when the eye is inside a closed mesh, i.e. most of a few probe rays from the
/// eye hit triangles from behind (against their counter-clockwise front). False when nothing or
/// mostly front faces are hit.
bool eyeInsideMesh(const Mesh& mesh, const Occluder& occluder, const Vec3f& eye);

}  // namespace prt::render
