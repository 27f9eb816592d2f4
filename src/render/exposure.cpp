#include "prt/render/exposure.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/image/exposure.hpp"
#include "prt/relight/relight.hpp"
#include "prt/render/relit_view.hpp"
#include "prt/render/render.hpp"
#include "prt/render/texel_points.hpp"

namespace prt::render {

std::vector<Rgb> modelPixels(const Mesh& mesh, const Occluder& occluder,
                             std::span<const Rgb> radiance, const Camera& camera, int width,
                             int height) {
  return modelPixels(occluder, vertexRadianceShader(mesh, radiance), camera, width, height);
}

std::vector<Rgb> modelPixels(const Occluder& occluder, const ShadeFn& shade, const Camera& camera,
                             int width, int height) {
  PRT_CHECK(width > 0 && height > 0, "image size must be positive");
  const RayGenerator gen(camera, width, height);
  // One row per slot, joined in row order: the same pixels whatever the thread count.
  std::vector<std::vector<Rgb>> rows(static_cast<std::size_t>(height));
  parallelFor(rows.size(), 1, [&](std::size_t yb, std::size_t ye) {
    for (std::size_t y = yb; y < ye; ++y)
      for (int x = 0; x < width; ++x) {
        const Ray ray = gen.ray(float(x) + 0.5f, float(y) + 0.5f);
        const Hit hit = occluder.intersect(ray);
        if (hit.hit) rows[y].push_back(shade(ray, hit));
      }
  });
  std::vector<Rgb> out;
  for (const auto& r : rows) out.insert(out.end(), r.begin(), r.end());
  return out;
}

float autoExposure(const Mesh& mesh, const Occluder& occluder, std::span<const Rgb> radiance,
                   const Camera& camera, int width, int height, image::ToneMap op) {
  return autoExposure(occluder, vertexRadianceShader(mesh, radiance), camera, width, height, op);
}

float autoExposure(const Occluder& occluder, const ShadeFn& shade, const Camera& camera, int width,
                   int height, image::ToneMap op) {
  PRT_CHECK(width > 0 && height > 0, "image size must be positive");
  const int w = std::min(width, kExposureProbeWidth);
  const int h = std::max(1, int(std::lround(double(height) * w / width)));
  return image::autoExposure(modelPixels(occluder, shade, camera, w, h), op);
}

float relitExposure(const Mesh& mesh, const Transfer& transfer, const Material& material,
                    const sh::RgbSh& light, const Mat3d& rotation, const Camera& camera, int width,
                    int height, image::ToneMap op, int bands) {
  const auto occluder = makeEmbreeOccluder(mesh);
  RelitView view(mesh, *occluder, transfer, material);
  if (bands > 0 && bands < transfer.bands()) view.setBands(bands);
  view.relight(light, rotation, camera.eye, mesh.source);
  return view.autoExposure(camera, width, height, op);
}

}  // namespace prt::render
