#include "prt/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "prt/core/error.hpp"

namespace prt::render {

Vec3f defaultViewDirection() {
  return normalize(Vec3f(0.34f, 0.42f, 0.84f));
}

Camera frameSphere(const Vec3f& centre, float radius, int width, int height, float fovY,
                   const Vec3f& viewDir, float margin) {
  PRT_CHECK(width > 0 && height > 0, "image size must be positive");
  const double halfY = 0.5 * fovY * kPi / 180.0;
  const double halfX = std::atan(std::tan(halfY) * double(width) / double(height));
  const double half = std::min(halfY, halfX);
  const double r = std::max(double(radius), 1e-6);
  // The cone of half-angle `half` from the eye is tangent to the sphere at distance r / sin(half).
  const double d = margin * r / std::sin(half);
  Camera c;
  c.target = centre;
  c.eye = centre + normalize(viewDir) * float(d);
  c.up = {0.0f, 1.0f, 0.0f};
  c.fovY = fovY;
  return c;
}

Camera frameMesh(const Mesh& mesh, int width, int height) {
  // A tighter bounding sphere than the box's half-diagonal: same centre, radius to the farthest
  // vertex (a unit sphere gets radius 1, not √3).
  const Vec3f c = computeBounds(mesh).centre();
  float r2 = 0.0f;
  for (const Vec3f& p : mesh.positions) r2 = std::max(r2, dot(p - c, p - c));
  return frameSphere(c, std::sqrt(r2), width, height);
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
  PRT_CHECK(width > 0 && height > 0, "image size must be positive");
  forward_ = normalize(camera.target - camera.eye);
  right_ = normalize(cross(forward_, camera.up));
  up_ = cross(right_, forward_);
  tanY_ = std::tan(0.5f * camera.fovY * kPif / 180.0f);
  tanX_ = tanY_ * float(width) / float(height);
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

bool eyeInsideMesh(const Mesh& mesh, const Occluder& occluder, const Vec3f& eye) {
  // 64 well-spread directions (Fibonacci sphere); count back-face against front-face hits.
  const int n = 64;
  int back = 0, front = 0;
  for (int k = 0; k < n; ++k) {
    const float z = 1.0f - (2.0f * k + 1.0f) / n;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.399963f * k;  // golden angle
    Ray ray;
    ray.origin = eye;
    ray.dir = Vec3f(r * std::cos(phi), z, r * std::sin(phi));
    const Hit h = occluder.intersect(ray);
    if (!h.hit) continue;
    const auto& t = mesh.triangles[h.triangle];
    const Vec3f ng = cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                           mesh.positions[t[2]] - mesh.positions[t[0]]);
    (dot(ng, ray.dir) > 0.0f ? back : front)++;
  }
  return back > front && back >= n / 2;
}

}  // namespace prt::render
