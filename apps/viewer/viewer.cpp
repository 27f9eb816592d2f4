#include "viewer.hpp"

#include <epoxy/gl.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>

#include "capture.hpp"
#include "context.hpp"
#include "haar_view.hpp"
#include "probe_view.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/options.hpp"
#include "prt/geometry/load.hpp"
#include "prt/image/image.hpp"
#include "prt/image/image_io.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/haar_shader.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/sh/sh.hpp"
#include "scene.hpp"
#include "window.hpp"

namespace prt::viewer {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

BackgroundMode parseBackgroundMode(const std::string& s) {
  if (s == "env") return BackgroundMode::Env;
  if (s == "sh") return BackgroundMode::Sh;
  if (s == "none") return BackgroundMode::None;
  throw Error("--background '" + s + "': expected env, sh or none");
}

void checkOptions(const Options& o) {
  if (o.width <= 0 || o.height <= 0 || o.width > image::kMaxImageSide ||
      o.height > image::kMaxImageSide)
    throw Error(fmt::format("--size {}x{}: width and height must be 1..{}", o.width, o.height,
                            image::kMaxImageSide));
  if (o.frames < 0) throw Error("--frames must be positive (0: until the window is closed)");
  if (o.bands != 0) checkOptionRange(OptionSpelling::Cli, "bands", o.bands, 1, kMaxViewerBands);
  if (!o.headless && !o.screenshot.empty() && o.frames == 0)
    throw Error("--screenshot in a window needs --frames N (or --headless)");
  if (!o.screenshot.empty()) {
    const std::string ext = fileExtension(o.screenshot);
    if (ext != "png" && ext != "exr" && ext != "hdr")
      throw Error(o.screenshot + ": the screenshot must be .png, .exr or .hdr");
    checkWritable(o.screenshot);
  }
  if (o.rotateDeg)
    for (double a : *o.rotateDeg)
      if (!std::isfinite(a)) throw Error("--rotate: angles must be finite");
}

/// A probe bake's object: --object's mesh (the scene's sphere without it), at --at, of
/// --object-size, markers with --show-probes.
void placeObject(Scene& scene, const Options& o) {
  if (!o.object.empty()) scene.setObject(prt::loadScene({o.object}), o.object);
  if (o.at) scene.object->moveTo(*o.at);
  if (o.objectSize > 0) scene.object->setSize(o.objectSize);
  scene.showProbes = o.showProbes;
}

/// Loads everything named on the command line into a scene (errors name the file).
Scene loadScene(const Options& o, const Output& out) {
  Scene scene;
  if (!o.material.empty()) scene.overrideMaterial(parseMaterial(o.material));
  scene.warn = out.warn;
  scene.setBake(Scene::readCheckedBake(o.bake), o.bake, o.width, o.height);
  if (!o.mode.empty()) scene.selectMode(parseTransferMode(o.mode));
  if (scene.material().glossy() && !scene.transfer().transfer.isMatrix())
    out.warn(
        fmt::format("{}: the {} transfer is a vector (diffuse only); the material's glossy "
                    "lobe needs a matrix bake (prt bake --transfer matrix)",
                    o.bake, toString(scene.transfer().mode())));
  if (scene.haarBake() && o.bands > 0)
    throw Error(o.bake,
                "--bands shows SH transfer at fewer bands; this bake holds Haar transfer "
                "(relit under the light's largest wavelet terms)");
  if (o.bands > scene.bakeBands())
    out.warn(fmt::format("--bands {} asked for, but the bake has only {} bands: showing {}",
                         o.bands, scene.bakeBands(), scene.bakeBands()));
  if (o.bands > 0) scene.setBands(o.bands);
  if (!scene.probeBake() && (!o.object.empty() || o.at || o.objectSize > 0 ||
                             o.showProbes))
    throw Error(o.bake, "--object, --at, --object-size and --show-probes place an object in a "
                        "probe grid (prt probes); this bake holds " +
                            std::string(toString(scene.bake().domain())));
  if (scene.probeBake()) placeObject(scene, o);

  const std::vector<std::string> envs =
      o.environments.empty() ? std::vector<std::string>{"builtin:sky"} : o.environments;
  for (const std::string& spec : envs)
    scene.addEnvironment(Scene::loadEnvironment(spec, scene.bakeBands()));
  scene.selectEnvironment(0);

  if (!o.camera.empty())
    scene.orbit = OrbitCamera(render::parseCamera(o.camera, scene.orbit.camera()));
  if (o.rotateDeg)
    scene.setUserRotation(
        rotationEulerXYZ((*o.rotateDeg)[0], (*o.rotateDeg)[1], (*o.rotateDeg)[2]));
  scene.background = parseBackgroundMode(o.background);
  if (scene.haarBake() && scene.background == BackgroundMode::Sh)
    throw Error("--background sh draws an SH light, and " + o.bake + " holds Haar transfer");
  scene.toneMap = image::parseToneMap(o.toneMap);
  if (o.exposure) {
    image::checkExposure(*o.exposure, "--exposure");
    scene.exposureStops = *o.exposure;
  } else if (scene.haarBake()) {
    // prt render's rule on the first view of a Haar bake: its radiance, relit as it draws it.
    const Mesh& mesh = scene.bake().mesh;
    const Transfer& t = scene.transfer().transfer;
    const EnvironmentEntry& env = scene.environment(std::size_t(scene.environmentIndex()));
    const auto occluder = makeEmbreeOccluder(mesh);
    std::vector<Rgb> radiance;
    const render::ShadeFn shade = render::haarShader(
        mesh, *occluder, t, scene.material(),
        haarRenderLight(*env.lighting.image, t.shape().haar.resolution, scene.lightRotation()),
        radiance, o.bake);
    const render::FrameSurvey survey = render::surveyFrame(*occluder, shade, scene.orbit.camera(),
                                                           o.width, o.height, scene.toneMap);
    scene.exposureStops = survey.exposureStops;
    const std::string ringing = render::negativeRadianceWarning(survey.negativeShare);
    if (!ringing.empty()) out.warn(ringing + " (the first view)");
  } else if (scene.probeBake()) {
    // prt render's rule on the first view: the scene and the object shaded through the probes.
    const Mesh drawn = probeSceneMesh(scene.bake(), &*scene.object, scene.showProbes);
    const Mat3d r = scene.lightRotation();
    const sh::RgbSh light = sh::Rotation(scene.bands(), r).apply(
        scene.environment(std::size_t(scene.environmentIndex())).light.truncated(scene.bands()));
    const std::vector<Rgb> radiance =
        shadeProbeScene(scene.transfer().transfer, scene.bands(), light.c, drawn);
    const render::FrameSurvey survey = vertexRadianceSurvey(drawn, radiance, scene.orbit.camera(),
                                                            o.width, o.height, scene.toneMap);
    scene.exposureStops = survey.exposureStops;
    const std::string ringing = render::negativeRadianceWarning(survey.negativeShare);
    if (!ringing.empty()) out.warn(ringing + " (the first view)");
  } else {
    // prt render's rule on a CPU relight of the first view (the same bake, light and camera).
    const Mesh& mesh = scene.bake().mesh;
    const render::FrameSurvey survey = render::relitSurvey(
        mesh, scene.transfer().transfer, scene.material(),
        scene.environment(std::size_t(scene.environmentIndex())).lighting.coefficients,
        scene.lightRotation(), scene.orbit.camera(), o.width, o.height, scene.toneMap,
        scene.bands());
    scene.exposureStops = survey.exposureStops;
    const std::string ringing = render::negativeRadianceWarning(survey.negativeShare);
    if (!ringing.empty()) out.warn(ringing + " (the first view)");
  }
  scene.autoRotate = o.autoRotate;
  scene.spinDegreesPerSecond = o.spinDegreesPerSecond;
  return scene;
}

void runHeadless(Scene& scene, const Options& o, const Output& out) {
  HeadlessContext context;
  SceneView view;
  view.glossyOnGpu = o.glossyOnGpu;
  OffscreenTarget target(o.width, o.height);
  FrameStats stats;
  for (int k = 0; k < std::max(o.frames, 1); ++k) {
    const auto t0 = Clock::now();
    const FrameParams f = view.prepare(scene, o.width, o.height);
    const double cpu = view.lastLightSeconds() * 1e3;
    view.renderer().draw(f, target.fbo());
    glFinish();
    stats.add(msSince(t0), cpu, view.renderer().lastUploadSeconds() * 1e6,
              view.lastRelightSeconds() * 1e3);
    scene.advanceSpin(1.0 / 60.0);  // headless frames are 1/60 s apart
  }
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    throw Error(fmt::format("OpenGL error 0x{:x} while rendering", e));
  if (!o.screenshot.empty()) {
    writeScreenshot(o.screenshot, target.readEncoded(), view.renderer().readLinear());
    out.info(fmt::format("wrote {} ({}x{}, {}, {} transfer, {})", o.screenshot, o.width, o.height,
                         scene.basisText(), scene.transfer().describe(), scene.material().spec()));
  }
  stats.path = view.path();
  if (o.stats)
    stats.print(context.description(), scene, o.width, o.height, view.lightUploadBytes(),
                view.uploadSummary(scene), o.statsOnStderr ? stderr : stdout);
  if (out.headless) {
    const FrameSummary s = stats.summary();
    HeadlessReport r;
    r.renderer = context.description();
    r.transfer = &scene.transfer();
    r.material = scene.material().spec();
    r.shaderPath = relight::toString(stats.path);
    r.bands = scene.bands();
    r.bakeBands = scene.bakeBands();
    const EnvironmentEntry& env = scene.environment(std::size_t(scene.environmentIndex()));
    r.environment = env.name;
    r.light = env.lighting.coefficients;
    r.camera = scene.orbit.camera();
    r.exposureStops = scene.exposureStops;
    r.frames = s.frames;
    r.firstFrameSeconds = s.firstMs * 1e-3;
    r.medianFrameSeconds = s.medianMs * 1e-3;
    r.minFrameSeconds = s.minMs * 1e-3;
    r.medianCpuSeconds = s.cpuMedianMs * 1e-3;
    r.medianLightUploadSeconds = s.uploadMedianUs * 1e-6;
    r.lightUploadBytes = view.lightUploadBytes();
    if (stats.path == relight::ShaderPath::CpuRadiance) {
      r.medianRelightSeconds = s.relightMedianMs * 1e-3;
      r.relitFrames = s.relitFrames;
    }
    out.headless(r);
  }
}

}  // namespace

void run(const Options& o, const Output& out) {
  checkOptions(o);
  // Without a display, say so at once, before loading anything.
  if (!o.headless) initWindowSystem();
  Scene scene = loadScene(o, out);
  if (o.headless)
    runHeadless(scene, o, out);
  else
    runWindow(scene, o, out);
}

}  // namespace prt::viewer
