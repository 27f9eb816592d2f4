#pragma once
// prt view: the real-time viewer's entry point, called by apps/prt/view.cpp. See docs/viewer.md.
//
//   prt view bunny.glb --env studio.exr --env builtin:sky
//   prt view bunny.glb --headless --frames 10 --screenshot frame.png --rotate 0,90,0 --stats

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "prt/io/bake_file.hpp"
#include "prt/render/camera.hpp"
#include "prt/sh/sh.hpp"

namespace prt::viewer {

struct Options {
  std::string bake;
  std::vector<std::string> environments;  ///< empty: builtin:sky
  int width = 640, height = 480;
  std::optional<std::array<double, 3>> rotateDeg;  ///< X, Y, Z as prt render --rotate
  std::string camera;                              ///< as prt render --camera
  std::string mode;                                ///< transfer mode; "" = richest
  std::string material;                            ///< as prt render --material; "" = the bake's
  bool glossyOnGpu = false;        ///< --glossy-on gpu: matrix transfer relit in the vertex shader
  int bands = 0;                   ///< 0 = all the bake has
  std::string background = "env";  ///< env | sh | none
  std::optional<float>
      exposure;  ///< stops; nullopt: auto (render::relitSurvey of the first view)
  std::string toneMap = "aces";
  bool autoRotate = false;
  double spinDegreesPerSecond = 30.0;
  bool headless = false;       ///< render offscreen (EGL) instead of opening a window
  int frames = 0;              ///< frames to draw, then exit (0: headless 1, window until closed)
  std::string screenshot;      ///< after the last frame: .png as shown, .exr/.hdr linear
  bool stats = false;          ///< print timings to stdout at exit
  bool statsOnStderr = false;  ///< print them to stderr instead (prt view --json -)
  // A probe bake's moving object (as prt render's --object, --at, --object-size) and markers.
  std::string object;     ///< mesh file or builtin:NAME; "": a sphere
  std::optional<Vec3f> at;  ///< none: the grid's centre
  float objectSize = 0;   ///< its largest side; 0: a fifth of the grid's
  bool showProbes = false;
};

/// What a headless run drew and measured (prt view --json, docs/formats-report.md). Times in
/// seconds: medians over the frames after the first, which uploads.
struct HeadlessReport {
  std::string renderer;                     ///< the OpenGL renderer and context
  const BakedTransfer* transfer = nullptr;  ///< the transfer drawn (valid during the call)
  std::string material;                     ///< what it was relit with (spec)
  std::string shaderPath;                   ///< relight::toString(ShaderPath)
  int bands = 0, bakeBands = 0;
  std::string environment;  ///< as given (builtin:sky by default)
  sh::RgbSh light;          ///< its SH at the bake's bands, before the rotation
  render::Camera camera;
  float exposureStops = 0;
  std::size_t frames = 0;
  double firstFrameSeconds = 0, medianFrameSeconds = 0, minFrameSeconds = 0;
  double medianCpuSeconds = 0, medianLightUploadSeconds = 0;
  std::size_t lightUploadBytes = 0;
  std::optional<double> medianRelightSeconds;  ///< CPU relighting of matrices only
  std::size_t relitFrames = 0;
};

/// Chatter and warnings go through these (the CLI's quiet flag applies to `info`).
struct Output {
  std::function<void(const std::string&)> info, warn;
  /// Called once by a headless run, after the screenshot (unset: not called).
  std::function<void(const HeadlessReport&)> headless;
};

/// Validates the options (throws prt::Error with one line), loads the bake and environments,
/// then runs the window loop, or renders `frames` frames offscreen and writes the screenshot.
void run(const Options& options, const Output& out);

}  // namespace prt::viewer
