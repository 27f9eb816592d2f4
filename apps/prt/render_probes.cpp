// prt render of a probe bake (issue 32): relight every probe under the light (turned by
// --rotate: on its SH coefficients, as for surfaces), place --object at --at, and draw the scene
// and the object with every vertex lit through the probes around it (render/probe_shading.hpp).
//
//   prt probes builtin:cornell -o box-probes.glb
//   prt render box-probes.glb --object 'builtin:sphere?r=0.25' --at 0.4,0.5,0.3 -o ball.png
//
// The object does not shadow the scene, nor the scene's surfaces shade themselves from their own
// transfer: a probe grid lights what moves, and engines draw the static scene from its lightmap
// or vertex bake (prt bake). Here the scene is lit through the probes too, to show where it is.

#include "render_probes.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/load.hpp"
#include "prt/io/lighting.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/primary.hpp"
#include "prt/render/probe_object.hpp"
#include "prt/render/probe_shading.hpp"
#include "prt/sh/rotate.hpp"

namespace prt::cli {

void renderProbeBake(const BakeFile& bake, const ProbeRenderArgs& a, Report& report) {
  const BakedTransfer& baked = pickTransfer(bake, {}, {}, a.bake);
  Transfer transfer = baked.transfer;
  if (a.bands > 0 && a.bands < transfer.bands()) transfer = transfer.cut(a.bands);
  const ProbeGrid grid = bake.probeGrid();
  const io::Lighting lighting =
      io::loadLighting(a.light, transfer.bands(), progressBar("projecting"));
  for (const std::string& w : lighting.warnings) warn(w);
  sh::RgbSh light = lighting.coefficients;
  sh::Rotation(light.bands, a.rotation).apply(lighting.coefficients.c.data(), light.c.data());
  const relight::ProbeLighting probes = relight::relightProbes(transfer, light);

  // The scene, and the object where --at puts it (the grid's centre by default).
  Mesh scene = bake.mesh;
  foldBaseColour(scene);
  if (!a.object.empty()) {
    Vec3f at = render::defaultObjectPosition(grid);
    if (!a.at.empty()) {
      const std::vector<double> v = parseNumberList(a.at, "--at");
      if (v.size() != 3) throw Error("--at '" + a.at + "' is not a point x,y,z");
      at = Vec3f(Vec3d(v[0], v[1], v[2]));
    }
    const float size = a.objectSize > 0 ? a.objectSize : render::defaultObjectSize(grid);
    Mesh object = render::placeObject(loadScene({a.object}), at, size);
    foldBaseColour(object);
    appendMesh(scene, object);
  }
  const auto occluder = makeEmbreeOccluder(scene);
  const std::vector<Rgb> radiance = render::shadeThroughProbes(probes, scene);
  render::checkFiniteRadiance(radiance, a.bake);
  const render::ShadeFn shade = render::vertexRadianceShader(scene, radiance);

  render::Camera camera = render::frameMesh(bake.mesh, a.frame.width, a.frame.height);
  if (!a.camera.empty()) camera = render::parseCamera(a.camera, camera);
  image::WriteOptions write = a.write;
  const render::FrameSurvey survey = render::surveyFrame(*occluder, shade, camera, a.frame.width,
                                                         a.frame.height, write.toneMap);
  write.exposureStops = a.exposure ? *a.exposure : survey.exposureStops;
  // SH ringing of a bright light (a sun at 3 bands) makes a probe that sees little of the sky
  // negative: said as for surfaces, pointing at a windowed light.
  const std::string ringing = render::negativeRadianceWarning(survey.negativeShare);
  if (!ringing.empty()) warn(ringing);
  report["negativeShare"] = survey.negativeShare;
  const render::BackgroundFn bg =
      render::background(a.background, a.backgroundColour,
                         lighting.image ? &*lighting.image : nullptr, &light, a.rotation);
  const image::Image img =
      render::tracePrimary(camera, a.frame, *occluder, shade, bg, progressBar("rendering"));
  image::writeImage(a.output, img, write);
  report.output(a.output);
  report["probes"] = grid.probes();
  report["bands"] = probes.bands;
  report["exposureStops"] = write.exposureStops;
  report["camera"] = cameraJson(camera);
  info(fmt::format("wrote {} ({}x{}, {} spp, {} through {} at {} bands{}, exposure {:.2f}{})",
                   a.output, a.frame.width, a.frame.height, a.frame.spp,
                   a.object.empty() ? std::string("the scene lit") : a.object + " and the scene lit",
                   grid.describe(), probes.bands, "", write.exposureStops,
                   a.exposure ? "" : " auto"));
}

}  // namespace prt::cli
