#include "render_haar.hpp"

#include <fmt/format.h>

#include "cli.hpp"
#include "prt/core/error.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/io/haar_light_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/haar_shader.hpp"
#include "prt/render/primary.hpp"

namespace prt::cli {

void renderHaarBake(const BakeFile& bake, const BakedTransfer& baked, const Material& material,
                    const HaarRenderArgs& a, Report& report) {
  const Transfer& transfer = baked.transfer;
  const int n = transfer.shape().haar.resolution;
  // A Haar light file at the bake's resolution, or the environment itself resampled into the
  // cube (an SH light file's bands hold no wavelets).
  haar::HaarLight light;
  std::optional<io::Lighting> lighting;
  if (io::isHaarLightFile(a.light)) {
    light = io::readHaarLightJson(a.light).light;
    if (light.resolution != n)
      throw Error(a.light, fmt::format("is a Haar light over a {}² cube, and {} holds Haar "
                                       "transfer over a {}² cube (prt light --basis haar "
                                       "--resolution {})",
                                       light.resolution, a.bake, n, n));
    if (!(a.rotation == Mat3d::identity()))
      throw Error(a.light, "a Haar light file cannot be turned (--rotate resamples the "
                           "environment: give the environment itself)");
  } else {
    lighting = io::loadLighting(a.light, 1);
    for (const std::string& w : lighting->warnings) warn(w);
    if (lighting->isShFile())
      throw Error(a.light, "is an SH light file, and " + a.bake +
                               " holds Haar transfer: give the environment (an image, a face "
                               "folder or builtin:NAME) or a Haar light (prt light --basis haar)");
    light = haar::projectLight(*lighting->image, n, std::size_t(a.lightTerms), a.rotation);
  }
  // Drawn as prt view draws it (render/haar_shader.hpp).
  const auto occluder = makeEmbreeOccluder(bake.mesh);
  std::vector<Rgb> radiance;
  const render::ShadeFn shade =
      render::haarShader(bake.mesh, *occluder, transfer, material, light, radiance, a.bake);
  render::Camera camera = render::frameMesh(bake.mesh, a.frame.width, a.frame.height);
  if (!a.camera.empty()) camera = render::parseCamera(a.camera, camera);
  image::WriteOptions write = a.write;
  const render::FrameSurvey survey = render::surveyFrame(*occluder, shade, camera, a.frame.width,
                                                         a.frame.height, write.toneMap);
  write.exposureStops = a.exposure ? *a.exposure : survey.exposureStops;
  report["negativeShare"] = survey.negativeShare;
  if (a.background == render::Background::Sh)
    throw Error("--background sh draws an SH light, and " + a.bake + " holds Haar transfer");
  // A Haar light file holds no image to draw behind the object: none, unless a colour is asked.
  const render::Background kind =
      !lighting && a.background == render::Background::Env ? render::Background::None
                                                            : a.background;
  const render::BackgroundFn bg = render::background(
      kind, a.backgroundColour, lighting ? &*lighting->image : nullptr, nullptr,
      a.rotation);
  const image::Image img =
      render::tracePrimary(camera, a.frame, *occluder, shade, bg, progressBar("rendering"));
  image::writeImage(a.output, img, write);
  report.output(a.output);
  report["basis"] = "haar";
  report["resolution"] = n;
  report["lightTerms"] = light.terms();
  report["lightEnergyKept"] = light.energyKept;
  report["exposureStops"] = write.exposureStops;
  report["camera"] = cameraJson(camera);
  info(fmt::format("wrote {} ({}x{}, {} spp, {} transfer, Haar {}² cube, the light's {} largest "
                   "terms of {} ({:.4f}% of its energy), {}, exposure {:.2f}{})",
                   a.output, a.frame.width, a.frame.height, a.frame.spp, baked.describe(), n,
                   light.terms(), haar::coefficientCount(n), 100 * light.energyKept,
                   material.spec(), write.exposureStops, a.exposure ? "" : " auto"));
}

}  // namespace prt::cli
