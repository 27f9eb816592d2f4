#include "prt/render/primary.hpp"

#include <string>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"

namespace prt::render {

void checkFrameSettings(const FrameSettings& s) {
  constexpr int kMaxSide = image::kMaxImageSide;
  if (s.width <= 0 || s.height <= 0 || s.width > kMaxSide || s.height > kMaxSide)
    throw Error("image size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                " is invalid (each side must be 1.." + std::to_string(kMaxSide) + ")");
  if (s.spp <= 0 || s.spp > 65536)
    throw Error("samples per pixel must be 1..65536, got " + std::to_string(s.spp));
}

Vec2f subpixelOffset(const FrameSettings& s, int x, int y, int k) {
  if (s.spp == 1) return {0.5f, 0.5f};  // one sample: the pixel centre, no noise
  const std::uint64_t h =
      deriveSeed(s.seed, std::uint64_t(y) * std::uint64_t(s.width) + std::uint64_t(x));
  const Point2 p = scrambledSobol(std::uint32_t(k), std::uint32_t(h), std::uint32_t(h >> 32));
  return {p.x, p.y};
}

image::Image tracePrimary(const Camera& camera, const FrameSettings& settings,
                          const Occluder& occluder, const ShadeFn& shade,
                          const BackgroundFn& background, const ProgressFn& progress) {
  checkFrameSettings(settings);
  const RayGenerator gen(camera, settings.width, settings.height);
  image::Image img(settings.width, settings.height);
  Progress prog(progress, std::size_t(settings.height));
  const float inv = 1.0f / float(settings.spp);
  parallelFor(std::size_t(settings.height), 1, [&](std::size_t yb, std::size_t ye) {
    for (std::size_t yy = yb; yy < ye; ++yy) {
      const int y = int(yy);
      for (int x = 0; x < settings.width; ++x) {
        Rgb sum(0.0f);
        for (int k = 0; k < settings.spp; ++k) {
          const Vec2f o = subpixelOffset(settings, x, y, k);
          const Ray ray = gen.ray(float(x) + o.x, float(y) + o.y);
          const Hit hit = occluder.intersect(ray);
          if (hit.hit)
            sum += shade(ray, hit);
          else if (background)
            sum += background(ray.dir);
        }
        img.at(x, y) = sum * inv;
      }
      prog.advance(1);
    }
  });
  return img;
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
