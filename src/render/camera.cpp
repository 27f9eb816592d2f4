#include "prt/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "prt/core/error.hpp"

namespace prt::render {

CameraBasis cameraBasis(const Camera& camera, int width, int height) {
  PRT_CHECK(width > 0 && height > 0, "image size must be positive");
  CameraBasis b;
  b.eye = camera.eye;
  b.forward = normalize(camera.target - camera.eye);
  b.right = normalize(cross(b.forward, camera.up));
  b.up = cross(b.right, b.forward);
  b.tanY = std::tan(0.5f * camera.fovY * kPif / 180.0f);
  b.tanX = b.tanY * float(width) / float(height);
  return b;
}

Mat4f viewMatrix(const Camera& camera) {
  const CameraBasis b = cameraBasis(camera, 1, 1);
  // Rows: right, up', −forward; translation −R·eye.
  const Vec3f rows[3] = {b.right, b.up, -b.forward};
  Mat4f m{};
  for (int r = 0; r < 3; ++r) {
    m[0 + r] = rows[r].x, m[4 + r] = rows[r].y, m[8 + r] = rows[r].z;
    m[12 + r] = -dot(rows[r], b.eye);
  }
  m[15] = 1.0f;
  return m;
}

Mat4f projectionMatrix(const Camera& camera, int width, int height, float nearZ, float farZ) {
  PRT_CHECK(nearZ > 0.0f && farZ > nearZ, "clip planes must satisfy 0 < near < far");
  const CameraBasis b = cameraBasis(camera, width, height);
  // x_clip = x_eye / tanX, y_clip = y_eye / tanY, w_clip = −z_eye (the depth along forward),
  // z_clip = A z + B w with A = (f + n)/(n − f), B = 2 f n/(n − f): ndc depth −1 at n, +1 at f.
  Mat4f m{};
  m[0] = 1.0f / b.tanX;
  m[5] = 1.0f / b.tanY;
  m[10] = (farZ + nearZ) / (nearZ - farZ);
  m[11] = -1.0f;
  m[14] = 2.0f * farZ * nearZ / (nearZ - farZ);
  return m;
}

Mat4f multiply(const Mat4f& a, const Mat4f& b) {
  Mat4f m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      float s = 0.0f;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + r] * b[c * 4 + k];
      m[c * 4 + r] = s;
    }
  return m;
}

namespace {

/// v rotated by `angle` about the unit `axis` (Rodrigues). An angle of 0 returns v exactly.
Vec3d rotateAbout(const Vec3d& v, const Vec3d& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0 - c));
}

/// The elevation of eye − target above the plane orthogonal to up, in radians.
double elevation(const Camera& camera) {
  const Vec3d d = normalize(Vec3d(camera.eye) - Vec3d(camera.target));
  return std::asin(std::clamp(dot(d, normalize(Vec3d(camera.up))), -1.0, 1.0));
}

}  // namespace

double clampPitch(const Camera& camera, double pitch) {
  const double limit = kMaxOrbitElevationDegrees * kPi / 180.0, e = elevation(camera);
  if (pitch > 0) return std::min(pitch, std::max(0.0, limit - e));
  if (pitch < 0) return std::max(pitch, std::min(0.0, -limit - e));
  return pitch;
}

Camera orbitCamera(const Camera& camera, const Orbit& orbit) {
  // In double, from the offset eye − target (exact for floats of similar magnitude), so that the
  // zero orbit returns the camera bit for bit: each step multiplies by cos 0 = 1, adds sin 0 = 0.
  const Vec3d target = Vec3d(camera.target);
  const Vec3d axis = normalize(Vec3d(camera.up));
  Vec3d offset = rotateAbout(Vec3d(camera.eye) - target, axis, orbit.yaw);
  const double pitch = clampPitch(camera, orbit.pitch);
  const Vec3d side = cross(-offset, axis);  // the right axis after the yaw
  if (pitch != 0 && length(side) > 0) offset = rotateAbout(offset, normalize(side), -pitch);
  Camera c = camera;
  c.target = Vec3f(target + orbit.pan);
  c.eye = Vec3f(target + orbit.pan + offset * orbit.scale);
  return c;
}

Vec3f defaultViewDirection() {
  return normalize(Vec3f(0.34f, 0.42f, 0.84f));
}

Camera frameCamera(const Framing& f, int width, int height) {
  PRT_CHECK(width > 0 && height > 0, "image size must be positive");
  const double halfY = 0.5 * f.fovY * kPi / 180.0;
  const double halfX = std::atan(std::tan(halfY) * double(width) / double(height));
  const double half = std::min(halfY, halfX);
  const double r = std::max(double(f.radius), 1e-6);
  // The cone of half-angle `half` from the eye is tangent to the sphere at distance r / sin(half).
  const double d = f.margin * r / std::sin(half);
  Camera c;
  c.target = f.centre;
  c.eye = f.centre + normalize(f.direction) * float(d);
  c.up = f.up;
  c.fovY = f.fovY;
  return c;
}

Camera frameSphere(const Vec3f& centre, float radius, int width, int height, float fovY,
                   const Vec3f& viewDir, float margin) {
  Framing f;
  f.centre = centre;
  f.radius = radius;
  f.direction = viewDir;
  f.fovY = fovY;
  f.margin = margin;
  return frameCamera(f, width, height);
}

bool isGroundPart(const Mesh& mesh, const MeshPart& part) {
  if (mesh.parts.size() < 2 || part.vertexCount == 0) return false;
  const std::size_t v0 = part.firstVertex, v1 = std::size_t(part.firstVertex) + part.vertexCount;
  if (v1 > mesh.positions.size() || v1 > mesh.normals.size()) return false;
  Vec3f lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (std::size_t v = v0; v < v1; ++v) {
    if (mesh.normals[v].y < 0.999f) return false;  // within ~2.5° of +Y
    lo = min(lo, mesh.positions[v]);
    hi = max(hi, mesh.positions[v]);
  }
  const float width = std::max(hi.x - lo.x, hi.z - lo.z);
  if (!(width > 0.0f) || hi.y - lo.y > 1e-4f * width) return false;
  // Under everything else: no other part reaches below its top.
  float othersLow = std::numeric_limits<float>::max();
  for (const MeshPart& q : mesh.parts) {
    if (&q == &part) continue;
    const std::size_t e =
        std::min(mesh.positions.size(), std::size_t(q.firstVertex) + q.vertexCount);
    for (std::size_t v = q.firstVertex; v < e; ++v)
      othersLow = std::min(othersLow, mesh.positions[v].y);
  }
  return othersLow >= hi.y - 1e-4f * width;
}

std::vector<Vec3f> framedVertices(const Mesh& mesh) {
  std::vector<Vec3f> out;
  for (const MeshPart& p : mesh.parts) {
    if (isGroundPart(mesh, p)) continue;
    const std::size_t e =
        std::min(mesh.positions.size(), std::size_t(p.firstVertex) + p.vertexCount);
    out.insert(out.end(),
               mesh.positions.begin() + std::ptrdiff_t(std::min<std::size_t>(p.firstVertex, e)),
               mesh.positions.begin() + std::ptrdiff_t(e));
  }
  if (out.empty()) out = mesh.positions;
  return out;
}

Framing meshFraming(const Mesh& mesh) {
  // A tighter bounding sphere than the box's half-diagonal: same centre, radius to the farthest
  // vertex (a unit sphere gets radius 1, not √3).
  Framing f;
  const std::vector<Vec3f> object = framedVertices(mesh);
  if (object.empty()) {
    f.radius = 0.0f;
    return f;
  }
  Vec3f lo = object.front(), hi = object.front();
  for (const Vec3f& p : object) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  f.centre = (lo + hi) * 0.5f;
  // In double: a squared distance of coordinates near the cap (PRT_MAX_COORDINATE) overflows
  // float, which gave "radius": inf on the web page.
  double r2 = 0.0;
  for (const Vec3f& p : object) {
    const Vec3d d = Vec3d(p) - Vec3d(f.centre);
    r2 = std::max(r2, dot(d, d));
  }
  f.radius = static_cast<float>(std::sqrt(r2));
  return f;
}

Camera frameMesh(const Mesh& mesh, int width, int height) {
  return frameCamera(meshFraming(mesh), width, height);
}

namespace {

Vec3f parseVec(const std::string& key, const std::string& value) {
  Vec3f v;
  char c1 = 0, c2 = 0;
  std::istringstream in(value);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() ||
      !isFinite(v))
    throw Error("camera: " + key + "=" + value + " is not three numbers x,y,z");
  return v;
}

}  // namespace

Camera parseCamera(const std::string& spec, const Camera& base) {
  Camera c = base;
  std::string item;
  std::string s = spec;
  std::replace(s.begin(), s.end(), ' ', ';');
  std::istringstream in(s);
  while (std::getline(in, item, ';')) {
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw Error("camera: '" + item + "' is not key=value (keys: eye, target, up, fov)");
    const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
    if (key == "eye") {
      c.eye = parseVec(key, value);
    } else if (key == "target") {
      c.target = parseVec(key, value);
    } else if (key == "up") {
      c.up = parseVec(key, value);
    } else if (key == "fov") {
      std::size_t used = 0;
      float f = 0;
      try {
        f = std::stof(value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != value.size() || !(f > 0.0f && f < 180.0f))
        throw Error("camera: fov=" + value + " is not an angle in (0, 180) degrees");
      c.fovY = f;
    } else {
      throw Error("camera: unknown key '" + key + "' (keys: eye, target, up, fov)");
    }
  }
  if (length(c.target - c.eye) <= 0.0f) throw Error("camera: eye and target coincide");
  if (length(cross(c.target - c.eye, c.up)) <= 1e-6f * length(c.target - c.eye) * length(c.up))
    throw Error("camera: the up vector is parallel to the viewing direction");
  return c;
}

RayGenerator::RayGenerator(const Camera& camera, int width, int height)
    : eye_(camera.eye), width_(width), height_(height) {
  const CameraBasis b = cameraBasis(camera, width, height);
  forward_ = b.forward, right_ = b.right, up_ = b.up;
  tanY_ = b.tanY, tanX_ = b.tanX;
}

Ray RayGenerator::ray(float px, float py) const {
  const float nx = 2.0f * px / float(width_) - 1.0f;
  const float ny = 1.0f - 2.0f * py / float(height_);
  Ray r;
  r.origin = eye_;
  r.dir = normalize(forward_ + right_ * (nx * tanX_) + up_ * (ny * tanY_));
  r.tnear = 0.0f;
  return r;
}

bool RayGenerator::project(const Vec3f& p, float& px, float& py) const {
  const Vec3f d = p - eye_;
  const float z = dot(d, forward_);
  if (z <= 0.0f) return false;
  const float nx = dot(d, right_) / (z * tanX_);
  const float ny = dot(d, up_) / (z * tanY_);
  px = 0.5f * (nx + 1.0f) * float(width_);
  py = 0.5f * (1.0f - ny) * float(height_);
  return true;
}

}  // namespace prt::render
