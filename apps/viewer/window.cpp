#include "window.hpp"

#include <epoxy/gl.h>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <utility>

#include "capture.hpp"
#include "context.hpp"
#include "prt/core/error.hpp"
#include "prt/image/color.hpp"

namespace prt::viewer {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kOrbitRadPerPixel = 0.3 * kPi / 180.0;
/// The panel opens expanded only in a window at least this large (width, height); smaller, it
/// starts as its title bar (click to open).
constexpr int kPanelOpenAbove[2] = {960, 600};

/// Files dropped since the last frame (GLFW calls back from glfwPollEvents).
std::vector<std::string>& droppedFiles() {
  static std::vector<std::string> files;
  return files;
}
extern "C" void onDrop(GLFWwindow*, int count, const char** paths) {
  for (int i = 0; i < count; ++i) droppedFiles().emplace_back(paths[i]);
}

struct Message {
  std::string text;
  bool error = false;
};

/// The panel and its transient state.
struct Ui {
  std::deque<Message> messages;
  double frameMs = 0.0, cpuMs = 0.0;  // exponentially smoothed
  std::string renderer;
  std::string upload;  // SceneView::uploadSummary of the last frame

  void post(const std::string& text, bool error, const Output& out) {
    (error ? out.warn : out.info)(text);
    messages.push_back({text, error});
    while (messages.size() > 6) messages.pop_front();
  }

  /// The material: the lobe, its width and ks, live (the lobe is applied at relighting time, so
  /// a change costs one CPU relighting, no re-bake). Vector transfer shows kd only.
  static void materialPanel(Scene& scene) {
    Material m = scene.material();
    if (!scene.transfer().transfer.isMatrix()) {
      ImGui::TextDisabled("material: diffuse (vector transfer)");
      return;
    }
    bool changed = false;
    int kind = int(m.lobe.kind);
    const char* kinds[] = {"lambert (no lobe)", "phong", "ggx"};
    if (ImGui::Combo("lobe", &kind, kinds, 3)) {
      m.lobe.kind = LobeKind(kind);
      // parseMaterial's defaults for a lobe chosen here first.
      if (m.lobe.kind == LobeKind::Phong && m.lobe.exponent <= 0)
        m.lobe.exponent = kDefaultPhongExponent;
      if (m.lobe.kind == LobeKind::Ggx && m.lobe.roughness <= 0)
        m.lobe.roughness = kDefaultGgxRoughness;
      if (m.lobe.kind != LobeKind::None && m.specular == Rgb(0.0f))
        m.specular = Rgb(kDefaultSpecular);
      changed = true;
    }
    // The sliders span the ranges parseMaterial accepts (material.hpp's limits); a value typed
    // past them (ctrl+click) is kept only if parseMaterial accepts it, below.
    if (m.lobe.kind == LobeKind::Phong) {
      float s = float(m.lobe.exponent);
      if (ImGui::SliderFloat("exponent", &s, 0.0f, float(kMaxPhongExponent), "%.1f",
                             ImGuiSliderFlags_Logarithmic))
        m.lobe.exponent = double(s), changed = true;
    } else if (m.lobe.kind == LobeKind::Ggx) {
      float r = float(m.lobe.roughness);
      if (ImGui::SliderFloat("roughness", &r, float(kMinGgxRoughness), 1.0f, "%.3f"))
        m.lobe.roughness = double(r), changed = true;
    }
    if (m.lobe.kind != LobeKind::None) {
      float ks[3] = {m.specular.x, m.specular.y, m.specular.z};
      if (ImGui::ColorEdit3("ks", ks, ImGuiColorEditFlags_Float))
        m.specular = {ks[0], ks[1], ks[2]}, changed = true;
      // What the shown bands cannot hold of the lobe (GlossyLobe::energyBeyond).
      ImGui::TextDisabled("lobe energy beyond %d bands: %.0f%%", scene.bands(),
                          100.0 * m.lobe.energyBeyond(scene.bands()));
    }
    ImGui::TextDisabled("%s", m.spec().c_str());
    // The one policy for what a material may be: parseMaterial's (the CLI's --material). A value
    // it refuses is dropped (the panel shows the scene's material again next frame).
    if (changed) {
      try {
        scene.setMaterial(parseMaterial(m.spec()));
      } catch (const Error&) {
      }
    }
  }

  /// A probe bake's moving object: where it is (within the probes' box), its size, the probe
  /// markers (probe_view.hpp).
  static void objectPanel(Scene& scene) {
    MovingObject& o = *scene.object;
    ImGui::TextDisabled("%s", o.name().c_str());
    const ProbeGrid grid = scene.bake().probeGrid();
    const Vec3f lo = grid.origin, hi = grid.position(grid.probes() - 1);
    const char* axes[3] = {"x", "y", "z"};
    Vec3f at = o.position();
    for (int a = 0; a < 3; ++a)
      if (hi[a] > lo[a] && ImGui::SliderFloat(axes[a], &at[a], lo[a], hi[a], "%.3f"))
        o.moveTo(at);
    float size = o.size();
    if (ImGui::SliderFloat("size", &size, 0.1f * o.defaultSize(), 4.0f * o.defaultSize(), "%.3f"))
      o.setSize(size);
    ImGui::Checkbox("show probes", &scene.showProbes);
    ImGui::TextDisabled("%s, lit through them", grid.describe().c_str());
  }

  /// The panel: what is shown and the controls used most (transfer, bands, environment,
  /// exposure) always; the material, the display and light controls and the help as sections
  /// (the material open for glossy transfer, where it matters). Collapsed to its title bar when
  /// the window is smaller than kPanelOpenAbove at start, so it never hides a small view.
  void panel(Scene& scene, int windowWidth, int windowHeight) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(windowWidth < kPanelOpenAbove[0] ||
                                      windowHeight < kPanelOpenAbove[1],
                                  ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("prt view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushItemWidth(ImGui::GetFontSize() * 12.0f);
    const Mesh& mesh = scene.bake().mesh;
    ImGui::TextUnformatted(scene.bakeName().c_str());
    ImGui::TextDisabled("%zu triangles  %.2f ms (%.0f fps)", mesh.triangleCount(), frameMs,
                        frameMs > 0 ? 1000.0 / frameMs : 0.0);

    const auto label = [](const BakedTransfer& t) {
      const Transfer& x = t.transfer;
      return fmt::format("{} {} ({}){}", toString(t.mode()), toString(x.layout()),
                         x.channels() == 3 ? "RGB" : "scalar",
                         x.compressed()
                             ? fmt::format(", CPCA {}x{}", x.cpca().clusters, x.cpca().basisCount)
                             : "");
    };
    if (ImGui::BeginCombo("transfer", label(scene.transfer()).c_str())) {
      for (int k = 0; k < int(scene.transferCount()); ++k)
        if (ImGui::Selectable(label(scene.transferAt(k)).c_str(), k == scene.transferIndex()))
          scene.selectTransfer(k);
      ImGui::EndCombo();
    }
    int bands = scene.bands();
    if (ImGui::SliderInt("bands", &bands, 1, scene.bakeBands())) scene.setBands(bands);
    if (ImGui::BeginCombo("environment",
                          scene.environment(scene.environmentIndex()).name.c_str())) {
      for (int k = 0; k < int(scene.environmentCount()); ++k)
        if (ImGui::Selectable(scene.environment(k).name.c_str(), k == scene.environmentIndex()))
          scene.selectEnvironment(k);
      ImGui::EndCombo();
    }
    // ±8 on the slider; a value typed in (Ctrl+click) stays within the library's limit.
    if (ImGui::SliderFloat("exposure", &scene.exposureStops, -8.0f, 8.0f, "%.1f stops"))
      scene.exposureStops = image::clampExposure(scene.exposureStops);

    if (scene.object) {
      if (ImGui::CollapsingHeader("object in the probe grid", ImGuiTreeNodeFlags_DefaultOpen))
        objectPanel(scene);
    } else {
      const bool glossy = scene.transfer().transfer.isMatrix();
      if (ImGui::CollapsingHeader("material", glossy ? ImGuiTreeNodeFlags_DefaultOpen : 0))
        materialPanel(scene);
    }
    if (ImGui::CollapsingHeader("display and light")) {
      int bg = int(scene.background);
      const char* bgNames[] = {"environment", "SH reconstruction", "black"};
      if (ImGui::Combo("background", &bg, bgNames, 3)) scene.background = BackgroundMode(bg);
      int tm = int(scene.toneMap);
      const char* tmNames[] = {"clamp", "reinhard", "aces"};
      if (ImGui::Combo("tone map", &tm, tmNames, 3)) scene.toneMap = image::ToneMap(tm);
      ImGui::Checkbox("auto-rotate light", &scene.autoRotate);
      float speed = float(scene.spinDegreesPerSecond);
      if (ImGui::SliderFloat("speed", &speed, -180.0f, 180.0f, "%.0f deg/s"))
        scene.spinDegreesPerSecond = speed;
      if (ImGui::Button("reset light")) scene.resetLight();
      ImGui::SameLine();
      if (ImGui::Button("reset camera")) scene.orbit.reset();
    }
    if (ImGui::CollapsingHeader("help and renderer")) {
      ImGui::TextDisabled("left drag: orbit   right/shift drag: light");
      ImGui::TextDisabled("middle/ctrl drag: pan   wheel: zoom");
      if (scene.object) ImGui::TextDisabled("alt drag: move the object");
      ImGui::TextDisabled("space: auto-rotate   B: background");
      ImGui::TextDisabled("[ ]: bands   Tab: next environment");
      ImGui::TextDisabled("drop an image, face folder or .glb");
      ImGui::TextDisabled("light CPU %.3f ms", cpuMs);
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 22.0f);
      ImGui::TextDisabled("%s", renderer.c_str());
      // Compressed transfer: K, N and what it uploads per vertex against the dense rows.
      if (scene.transfer().transfer.compressed()) ImGui::TextDisabled("%s", upload.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 22.0f);
    for (const Message& m : messages)
      ImGui::TextColored(m.error ? ImVec4(1, 0.4f, 0.4f, 1) : ImVec4(0.7f, 1, 0.7f, 1), "%s",
                         m.text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopItemWidth();
    ImGui::End();
  }
};

/// Mouse and keys the panel did not take.
void handleInput(Scene& scene, int height) {
  ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureMouse) {
    const double dx = io.MouseDelta.x, dy = io.MouseDelta.y;
    const bool left = io.MouseDown[0], right = io.MouseDown[1], middle = io.MouseDown[2];
    if (left && io.KeyAlt && scene.object && (dx != 0 || dy != 0))
      scene.object->drag(scene.orbit.camera(), dx, dy, height);
    else if ((right || (left && io.KeyShift)) && (dx != 0 || dy != 0))
      scene.dragLight(dx, dy);
    else if ((middle || (left && io.KeyCtrl)) && (dx != 0 || dy != 0))
      scene.orbit.pan(dx / height, dy / height);
    else if (left && (dx != 0 || dy != 0))
      scene.orbit.orbit(-dx * kOrbitRadPerPixel, dy * kOrbitRadPerPixel);
    if (io.MouseWheel != 0) scene.orbit.zoom(std::pow(0.9, double(io.MouseWheel)));
  }
  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) scene.autoRotate = !scene.autoRotate;
    if (ImGui::IsKeyPressed(GLFW_KEY_B, false))
      scene.background = BackgroundMode((int(scene.background) + 1) % 3);
    if (ImGui::IsKeyPressed(GLFW_KEY_LEFT_BRACKET)) scene.setBands(scene.bands() - 1);
    if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT_BRACKET)) scene.setBands(scene.bands() + 1);
    if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false))
      scene.selectEnvironment((scene.environmentIndex() + 1) % int(scene.environmentCount()));
  }
}

}  // namespace

void runWindow(Scene& scene, const Options& o, const Output& out) {
  Window window(o.width, o.height, "prt view - " + o.bake);
  GLFWwindow* w = window.handle();
  glfwSetDropCallback(w, onDrop);
  SceneView view;
  view.glossyOnGpu = o.glossyOnGpu;

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // leave no imgui.ini behind
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(w, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  struct ImGuiGuard {
    ~ImGuiGuard() {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
  } guard;

  Ui ui;
  ui.renderer = window.renderer();
  out.info("prt view: " + ui.renderer);
  FrameStats stats;
  auto last = Clock::now();
  for (int frame = 0; !glfwWindowShouldClose(w); ++frame) {
    glfwPollEvents();
    const auto now = Clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    ui.frameMs = ui.frameMs == 0 ? dt * 1e3 : 0.9 * ui.frameMs + 0.1 * dt * 1e3;

    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(w, &fbw, &fbh);
    for (const std::string& path : std::exchange(droppedFiles(), {})) {
      const std::string error = scene.loadDropped(path, std::max(fbw, 1), std::max(fbh, 1));
      ui.post(error.empty() ? "loaded " + path : error, !error.empty(), out);
    }
    scene.advanceSpin(dt);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) glfwSetWindowShouldClose(w, GLFW_TRUE);
    handleInput(scene, std::max(fbh, 1));
    int ww = 0, wh = 0;
    glfwGetWindowSize(w, &ww, &wh);
    ui.panel(scene, ww, wh);
    ImGui::Render();

    if (fbw > 0 && fbh > 0) {
      try {
        const auto t0 = Clock::now();
        const FrameParams f = view.prepare(scene, fbw, fbh);
        const double cpu = view.lastLightSeconds() * 1e3;
        ui.cpuMs = ui.cpuMs == 0 ? cpu : 0.9 * ui.cpuMs + 0.1 * cpu;
        view.renderer().draw(f, 0);
        ui.upload = view.uploadSummary(scene);
        if (o.stats) {
          glFinish();  // only when asked: it stalls the pipeline
          stats.add(std::chrono::duration<double, std::milli>(Clock::now() - t0).count(), cpu,
                    view.renderer().lastUploadSeconds() * 1e6, view.lastRelightSeconds() * 1e3);
        }
      } catch (const Error& e) {
        // A transfer the GPU cannot hold: say so and go back to the first one.
        ui.post(e.what(), true, out);
        if (scene.transferIndex() != 0)
          scene.selectTransfer(0);
        else
          throw;
      }
    }
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    const bool lastFrame = o.frames > 0 && frame + 1 >= o.frames;
    if (lastFrame && !o.screenshot.empty() && fbw > 0 && fbh > 0) {
      writeScreenshot(o.screenshot, readFramebufferEncoded(0, fbw, fbh),
                      view.renderer().readLinear());
      out.info(fmt::format("wrote {} ({}x{}, the window with its panel)", o.screenshot, fbw, fbh));
    }
    glfwSwapBuffers(w);
    if (lastFrame) break;
  }
  if (o.stats) {
    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(w, &fbw, &fbh);
    stats.path = view.path();
    stats.print(ui.renderer, scene, fbw, fbh, view.lightUploadBytes(), view.uploadSummary(scene));
  }
}

}  // namespace prt::viewer
