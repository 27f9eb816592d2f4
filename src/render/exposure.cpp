#include "prt/render/exposure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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
  return surveyFrame(occluder, shade, camera, width, height, op).exposureStops;
}

FrameSurvey surveyFrame(const Occluder& occluder, const ShadeFn& shade, const Camera& camera,
                        int width, int height, image::ToneMap op) {
  PRT_CHECK(width > 0 && height > 0, "image size must be positive");
  const int w = std::min(width, kExposureProbeWidth);
  const int h = std::max(1, int(std::lround(double(height) * w / width)));
  const std::vector<Rgb> pixels = modelPixels(occluder, shade, camera, w, h);
  FrameSurvey s;
  s.exposureStops = image::autoExposure(pixels, op);
  std::size_t negative = 0;
  for (const Rgb& p : pixels) negative += p.x < 0 || p.y < 0 || p.z < 0;
  s.negativeShare = pixels.empty() ? 0 : double(negative) / double(pixels.size());
  return s;
}

std::string negativeRadianceWarning(double share) {
  if (!(share > kNegativeShareWarned)) return "";
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "the relit radiance is negative on %.1f%% of the model's pixels, drawn black: SH "
                "ringing of a bright, small source; window the light (prt light --window hanning, "
                "or dering) or relight with fewer bands (--bands)",
                100 * share);
  return buf;
}

FrameSurvey relitSurvey(const Mesh& mesh, const Transfer& transfer, const Material& material,
                        const sh::RgbSh& light, const Mat3d& rotation, const Camera& camera,
                        int width, int height, image::ToneMap op, int bands) {
  const auto occluder = makeEmbreeOccluder(mesh);
  RelitView view(mesh, *occluder, transfer, material);
  if (bands > 0 && bands < transfer.bands()) view.setBands(bands);
  view.relight(light, rotation, camera.eye, mesh.source);
  return surveyFrame(*occluder, view.shader(), camera, width, height, op);
}

}  // namespace prt::render
