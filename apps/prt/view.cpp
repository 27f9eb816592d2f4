// prt view: the real-time viewer (apps/viewer/, docs/viewer.md).
//
//   prt view bunny.glb --env studio.exr --env builtin:sky
//   prt view bunny.glb --headless --size 160x120 --rotate 0,90,0 --screenshot frame.png
//   prt view bunny.glb --headless --frames 30 --json -       (what it drew and its timings)
//
// Built only when GLFW, libepoxy, EGL and Dear ImGui were found at configure time
// (PRT_HAVE_VIEWER); otherwise the verb exists and says so.

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/envmap/builtin.hpp"
#include "report.hpp"
#include "transfer_options.hpp"

#ifdef PRT_HAVE_VIEWER
#include "viewer.hpp"
#endif

namespace prt::cli {

namespace {

struct ViewArgs {
  std::string bake;
  std::vector<std::string> envs;
  std::string size = "1280x800";
  std::string rotate;
  std::string camera, mode, material, glossyOn = "cpu", background = "env", toneMap = "aces",
                                      screenshot;
  int bands = 0, frames = 0;
  std::string exposure = "auto";
  bool autoRotate = false, headless = false, stats = false;
  double spin = 30.0;
  std::string json;
  // A probe bake's moving object.
  std::string object, at;
  float objectSize = 0;
  bool showProbes = false;
};

#ifdef PRT_HAVE_VIEWER
void runView(const ViewArgs& a) {
  std::vector<NamedPath> inputs = {{"input", a.bake}};
  for (const std::string& e : a.envs) inputs.push_back({"--env", e});
  checkOutputs({{"--screenshot", a.screenshot}}, inputs);
  Report report("view", a.json);
  if (report.wanted() && !a.headless)
    throw Error(
        "--json reports a headless run: add --headless (a window's session has no "
        "results to report)");
  report.check({{"--screenshot", a.screenshot}}, inputs);
  viewer::Options o;
  o.bake = a.bake;
  o.environments = a.envs;
  parseSize(a.size, o.width, o.height);
  if (!a.rotate.empty()) o.rotateDeg = parseEulerDegrees(a.rotate);
  o.camera = a.camera;
  o.mode = a.mode;
  o.material = a.material;
  o.glossyOnGpu = a.glossyOn == "gpu";
  o.bands = a.bands;
  o.background = a.background;
  o.exposure = exposureOption(a.exposure);
  o.toneMap = a.toneMap;
  o.autoRotate = a.autoRotate;
  o.spinDegreesPerSecond = a.spin;
  o.headless = a.headless;
  o.frames = a.frames;
  o.screenshot = a.screenshot;
  o.stats = a.stats;
  o.statsOnStderr = report.toStandardOutput();
  o.object = a.object;
  if (!a.at.empty()) {
    const std::vector<double> v = parseNumberList(a.at, "--at");
    if (v.size() != 3) throw Error("--at '" + a.at + "' is not a point x,y,z");
    o.at = Vec3f(Vec3d(v[0], v[1], v[2]));
  }
  o.objectSize = a.objectSize;
  o.showProbes = a.showProbes;
  viewer::Output out{
      [](const std::string& s) { info(s); }, [](const std::string& s) { warn(s); }, {}};
  if (report.wanted())
    out.headless = [&](const viewer::HeadlessReport& r) {
      report["renderer"] = r.renderer;
      report["width"] = o.width;
      report["height"] = o.height;
      report["transfer"] = transferJson(*r.transfer);
      report["material"] = r.material;
      report["shaderPath"] = r.shaderPath;
      report["bands"] = r.bands;
      report["environment"] = r.environment;
      report["light"] = shLightJson(r.light);
      report["camera"] = cameraJson(r.camera);
      report["exposureStops"] = r.exposureStops;
      report["exposureAuto"] = !o.exposure.has_value();
      report["toneMap"] = o.toneMap;
      report["screenshot"] = a.screenshot.empty() ? Json(nullptr) : fileJson(a.screenshot);
      report["frames"] = r.frames;
      report["firstFrameSeconds"] = r.firstFrameSeconds;
      report["medianFrameSeconds"] = r.medianFrameSeconds;
      report["minFrameSeconds"] = r.minFrameSeconds;
      report["medianCpuSeconds"] = r.medianCpuSeconds;
      report["lightUploadBytes"] = r.lightUploadBytes;
      report["medianLightUploadSeconds"] = r.medianLightUploadSeconds;
      report["medianRelightSeconds"] =
          r.medianRelightSeconds ? Json(*r.medianRelightSeconds) : Json(nullptr);
      report["relitFrames"] = r.relitFrames;
    };
  viewer::run(o, out);
  report.input(a.bake);
  for (const std::string& e :
       a.envs.empty() ? std::vector<std::string>{envmap::kDefaultEnvironment} : a.envs)
    report.input(e);
  if (!a.screenshot.empty()) report.output(a.screenshot);
  report.write();
}
#else
void runView(const ViewArgs&) {
  throw Error("this build has no viewer (GLFW/OpenGL not found at configure time)");
}
#endif

}  // namespace

void addViewCommand(CLI::App& root) {
  auto a = std::make_shared<ViewArgs>();
  CLI::App* cmd = root.add_subcommand("view", "Real-time viewer: relight a bake on the GPU");
  cmd->add_option("bake", a->bake, "Bake file (.glb)")->required();
  cmd->add_option("--env,--light", a->envs,
                  "Environment image, face folder, builtin:NAME or SH light (.json/.txt); repeat "
                  "to switch between several (default builtin:sky)");
  cmd->add_option("--size", a->size, "Window or frame size WxH")->capture_default_str();
  cmd->add_option("--rotate", a->rotate,
                  "Rotate the environment: X,Y,Z degrees (X, then Y, then Z; as prt render)");
  cmd->add_option("--camera", a->camera,
                  "Camera 'eye=x,y,z;target=x,y,z;up=x,y,z;fov=deg' (default: prt render's "
                  "framing)");
  cmd->add_option("--mode", a->mode, "Transfer mode to start with (default: the richest)");
  addMaterialOption(cmd, a->material, "to relight with");
  cmd->add_option("--glossy-on", a->glossyOn,
                  "Where glossy (matrix) transfer is relit: cpu (relight::Relighter into a vertex "
                  "buffer) or gpu (the vertex shader, scalar matrices up to " +
                      std::to_string(bands::kMaxShaderGlossy) + " bands)")
      ->check(CLI::IsMember({"cpu", "gpu"}))
      ->capture_default_str();
  cmd->add_option("--bands", a->bands, "Start with at most this many SH bands")
      ->check(intRange(1, bands::kMaxPackedLight));
  cmd->add_option("--background", a->background,
                  "env (the image), sh (its SH reconstruction) or none")
      ->capture_default_str();
  cmd->add_option("--exposure", a->exposure,
                  "Initial exposure in stops, or auto: prt render's rule on a CPU relight of the "
                  "first view")
      ->check(exposureStopsOrAuto())
      ->capture_default_str();
  cmd->add_option("--tonemap", a->toneMap, "aces, reinhard or clamp")->capture_default_str();
  cmd->add_flag("--auto-rotate", a->autoRotate, "Turn the light about +Y");
  cmd->add_option("--spin", a->spin, "Auto-rotation speed, degrees per second")
      ->check(finite(-36000, 36000))
      ->capture_default_str();
  cmd->add_flag("--headless", a->headless,
                "Render offscreen (EGL, no display needed) instead of opening a window");
  cmd->add_option("--frames", a->frames,
                  "Draw N frames, then exit (headless default 1, 1/60 s apart; window: until "
                  "closed)")
      ->check(intRange(0, 1000000));
  cmd->add_option("--screenshot", a->screenshot,
                  "After the last frame write it: .png as shown (the window's with its panel), "
                  ".exr/.hdr linear radiance");
  cmd->add_flag("--stats", a->stats,
                "Print frame, CPU and upload timings on stdout at exit (stderr with --json -)");
  cmd->add_option("--object", a->object,
                  "A probe bake (prt probes): the object moved through the grid, a mesh file or "
                  "builtin:NAME (default a sphere; Alt+drag or the panel moves it)");
  cmd->add_option("--at", a->at, "A probe bake: where the object starts, x,y,z (default the "
                                 "grid's centre)");
  cmd->add_option("--object-size", a->objectSize,
                  "A probe bake: the object's largest side (default a fifth of the grid's)")
      ->check(finite(1e-6, 1e6));
  cmd->add_flag("--show-probes", a->showProbes,
                "A probe bake: draw every probe as a small octahedron lit as the object is");
  addJsonOption(cmd, a->json);
  cmd->callback([a] { runView(*a); });
}

}  // namespace prt::cli
