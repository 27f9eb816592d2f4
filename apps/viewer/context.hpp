#pragma once
// OpenGL 3.3 core contexts for the viewer: an offscreen one through EGL (no display needed:
// Mesa's surfaceless platform, else the device platform, else the default display with a
// pbuffer; on a machine without a GPU this is llvmpipe), and a GLFW window. GL entry points are
// resolved by libepoxy for either. Failures throw prt::Error with one line saying why.

#include <memory>
#include <string>

struct GLFWwindow;

namespace prt::viewer {

/// An offscreen context, current on the calling thread from construction to destruction.
/// Rendering goes to framebuffer objects (the default framebuffer is absent or a 1×1 pbuffer).
class HeadlessContext {
 public:
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  /// "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6, EGL surfaceless".
  const std::string& description() const { return description_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string description_;
};

/// True when a HeadlessContext can be created here; otherwise `why` says what failed.
bool headlessAvailable(std::string* why = nullptr);

/// GLFW (initialised once per process). Throws prt::Error when there is no display to open a
/// window on, with GLFW's own reason.
void initWindowSystem();

/// A resizable window with a current OpenGL 3.3 core context and vsync.
class Window {
 public:
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  std::string renderer() const;

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace prt::viewer
