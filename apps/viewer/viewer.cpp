#include "viewer.hpp"

#include <epoxy/gl.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>

#include "context.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/image/image_io.hpp"
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
  if (o.width <= 0 || o.height <= 0 || o.width > 16384 || o.height > 16384)
    throw Error(fmt::format("--size {}x{}: width and height must be 1..16384", o.width, o.height));
  if (o.frames < 1) throw Error("--frames must be at least 1");
  if (o.bands < 0 || o.bands > kMaxViewerBands)
    throw Error(fmt::format("--bands must be 1..{}", kMaxViewerBands));
  if (!o.headless && (!o.screenshot.empty() || o.frames != 1))
    throw Error("--screenshot and --frames need --headless");
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

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// Loads everything named on the command line into a scene (errors name the file).
Scene loadScene(const Options& o, const Output& out) {
  Scene scene;
  BakeFile bake = Scene::readCheckedBake(o.bake);
  std::optional<TransferMode> mode;
  if (!o.mode.empty()) {
    mode = parseTransferMode(o.mode);
    if (!bake.find(*mode)) {
      std::string have;
      for (const auto& t : bake.transfers)
        have += std::string(have.empty() ? "" : ", ") + toString(t.settings.mode);
      throw Error(o.bake,
                  fmt::format("no {} transfer in the bake (it has {})", toString(*mode), have));
    }
  }
  scene.setBake(std::move(bake), o.bake, o.width, o.height);
  if (mode)
    for (int k = 0; k < int(scene.bake().transfers.size()); ++k)
      if (scene.bake().transfers[k].settings.mode == *mode) scene.selectTransfer(k);
  if (o.bands > scene.bakeBands())
    out.warn(fmt::format("--bands {}: the bake has only {} bands; using {}", o.bands,
                         scene.bakeBands(), scene.bakeBands()));
  if (o.bands > 0) scene.setBands(o.bands);

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
  scene.exposureStops = o.exposure;
  scene.toneMap = image::parseToneMap(o.toneMap);
  scene.autoRotate = o.autoRotate;
  scene.spinDegreesPerSecond = o.spinDegreesPerSecond;
  return scene;
}

void runHeadless(Scene& scene, const Options& o, const Output& out) {
  HeadlessContext context;
  SceneView view;
  OffscreenTarget target(o.width, o.height);
  std::vector<double> frameMs, cpuMs, uploadUs;
  for (int k = 0; k < o.frames; ++k) {
    const auto t0 = Clock::now();
    const FrameParams f = view.prepare(scene, o.width, o.height);
    cpuMs.push_back(msSince(t0));
    view.renderer().draw(f, target.fbo());
    glFinish();
    frameMs.push_back(msSince(t0));
    uploadUs.push_back(view.renderer().lastUploadSeconds() * 1e6);
    scene.advanceSpin(1.0 / 60.0);  // headless frames are 1/60 s apart
  }
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    throw Error(fmt::format("OpenGL error 0x{:x} while rendering", e));
  if (!o.screenshot.empty()) {
    if (fileExtension(o.screenshot) == "png") {
      // What the window shows: the shader's tone-mapped sRGB codes, written as they are.
      image::Image shown = target.readEncoded();
      for (Rgb& p : shown.pixels)
        p = {image::srgbToLinear(p.x), image::srgbToLinear(p.y), image::srgbToLinear(p.z)};
      image::WriteOptions w;
      w.toneMap = image::ToneMap::Clamp;  // codes are already display-referred
      image::writeImage(o.screenshot, shown, w);
    } else {
      image::writeImage(o.screenshot, view.renderer().readLinear());
    }
    out.info(fmt::format("wrote {} ({}x{}, {} bands, {} transfer)", o.screenshot, o.width, o.height,
                         scene.bands(), toString(scene.transfer().settings.mode)));
  }
  if (o.stats) {
    // The first frame uploads the mesh, transfer and textures; steady state is the rest.
    const auto steady = [](const std::vector<double>& v) {
      return v.size() > 1 ? std::vector<double>(v.begin() + 1, v.end()) : v;
    };
    std::printf("renderer: %s\n", context.description().c_str());
    std::printf("scene: %zu triangles, %zu vertices, %d of %d bands, %s transfer (%s)\n",
                scene.bake().mesh.triangleCount(), scene.bake().mesh.vertexCount(), scene.bands(),
                scene.bakeBands(), toString(scene.transfer().settings.mode),
                scene.transfer().field.channels == 3 ? "RGB" : "scalar");
    std::printf("frames: %d at %dx%d; first frame %.2f ms (uploads)\n", o.frames, o.width, o.height,
                frameMs.front());
    std::printf("frame time (draw + glFinish): median %.3f ms, min %.3f ms\n",
                median(steady(frameMs)), *std::min_element(frameMs.begin(), frameMs.end()));
    std::printf("CPU per frame (light rotation + packing): median %.4f ms\n",
                median(steady(cpuMs)));
    std::printf("light upload (glBufferSubData, %zu bytes): median %.2f us\n",
                view.packer().bytes(), median(steady(uploadUs)));
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
