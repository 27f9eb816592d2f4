#pragma once
// A pinhole camera and its primary rays: the one camera convention of prt render, prt view and
// the web page (docs/conventions.md, "Camera"). World is right-handed, +Y up; the camera looks
// from `eye` toward `target` with `up` as the approximate up direction; `fovY` is the full
// vertical field of view in degrees. Its frame (cameraBasis) is gluLookAt's:
//   forward = normalize(target − eye), right = normalize(forward × up), up' = right × forward.
// Image pixel (x, y) has row 0 at the top; a continuous image point (px, py) ∈ [0, w] × [0, h]
// maps to the ray through
//   ndc = (2 px / w − 1, 1 − 2 py / h),
//   dir ∝ forward + ndc.x · tan(fovY/2) · aspect · right + ndc.y · tan(fovY/2) · up',
// which is exactly what OpenGL's viewMatrix and projectionMatrix below rasterise.

#include <array>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/ray.hpp"

namespace prt::render {

struct Camera {
  Vec3f eye{0.0f, 0.0f, 3.0f};
  Vec3f target{0.0f, 0.0f, 0.0f};
  Vec3f up{0.0f, 1.0f, 0.0f};
  float fovY = 40.0f;  ///< degrees, full vertical angle
};

/// The camera's orthonormal frame and the half-angle tangents of a width × height image.
struct CameraBasis {
  Vec3f eye, forward, right, up;  ///< up is up' (orthogonal to forward), not Camera::up
  float tanX = 1, tanY = 1;       ///< tan(fovX/2) = tan(fovY/2) · width / height, tan(fovY/2)
};
/// The frame every view builds from a Camera (the file comment).
CameraBasis cameraBasis(const Camera& camera, int width, int height);

/// A 4×4 matrix, column-major as OpenGL and three.js take it: m[column * 4 + row].
using Mat4f = std::array<float, 16>;
/// World → eye space (gluLookAt): eye at the origin looking down −Z, up' along +Y.
Mat4f viewMatrix(const Camera& camera);
/// Eye → clip space for a width × height image (gluPerspective with the camera's fovY): x and y
/// reach ±1 at the image edges exactly where RayGenerator::project puts them, depth −1..1 from
/// nearZ to farZ.
Mat4f projectionMatrix(const Camera& camera, int width, int height, float nearZ, float farZ);
/// a · b (a named function: Mat4f is a std::array, so an operator would not be found).
Mat4f multiply(const Mat4f& a, const Mat4f& b);

/// An orbit about a camera's target, as changes from that camera (prt view's mouse). The zero
/// orbit gives the camera back bit for bit.
struct Orbit {
  double yaw = 0;  ///< radians about the camera's up axis through the target; + moves the eye right
  double pitch = 0;  ///< radians about the right axis; + raises the eye (clamped, see clampPitch)
  double scale = 1;  ///< the eye's distance to the target multiplied by this
  Vec3d pan{0.0, 0.0, 0.0};  ///< added to the target (and so to the eye)
};
/// The elevation of an orbit stays within ±89° of the plane orthogonal to `up`.
inline constexpr double kMaxOrbitElevationDegrees = 89.0;
/// `camera` orbited: yaw, then pitch, then scale, then pan; up stays the camera's.
Camera orbitCamera(const Camera& camera, const Orbit& orbit);
/// `pitch` limited so that orbitCamera keeps the eye's elevation within ±89°; a camera already
/// beyond is never pushed further out (and the zero pitch stays zero).
double clampPitch(const Camera& camera, double pitch);

/// The default viewing direction (from the target toward the eye): in front (+Z), a little to
/// the right and above (about 20° azimuth, 25° elevation), so tops and one side are visible.
Vec3f defaultViewDirection();

/// How prt frames a mesh by default: a bounding sphere, looked at from `direction` with `up`,
/// from the distance where the sphere, grown by `margin`, fits the narrower field of view
/// (frameSphere). prt web writes these numbers into the page, which frames with them.
struct Framing {
  Vec3f centre{0.0f, 0.0f, 0.0f};
  float radius = 1.0f;
  Vec3f direction = defaultViewDirection();  ///< target → eye
  Vec3f up{0.0f, 1.0f, 0.0f};
  float fovY = 40.0f;
  float margin = 1.05f;
};
/// A ground part: a flat, horizontal part facing up (+Y: every normal within ~2.5° of it, its
/// heights within 1e-4 of its width) whose top is no higher than the lowest point of the other
/// parts — the plane under an object, a Cornell box's floor. Never the mesh's only part.
bool isGroundPart(const Mesh& mesh, const MeshPart& part);
/// The object of interest, what the default camera frames: the vertices of the mesh's non-ground
/// parts (isGroundPart), or all of them when every part is ground or the mesh has no parts.
std::vector<Vec3f> framedVertices(const Mesh& mesh);
/// The default framing of a mesh (every tool's default camera: render, validate, view, web, demo):
/// the object of interest (framedVertices), centred on its bounds, radius to its farthest vertex.
Framing meshFraming(const Mesh& mesh);
/// The camera of `framing` for a width × height image.
Camera frameCamera(const Framing& framing, int width, int height);

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

}  // namespace prt::render
