#include "context.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <GLFW/glfw3.h>

#include <fmt/format.h>

#include <cstdlib>
#include <vector>

#include "prt/core/error.hpp"

namespace prt::viewer {

namespace {

std::string eglErrorName(EGLint e) {
  switch (e) {
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return fmt::format("EGL error 0x{:x}", e);
  }
}

std::string glString(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "?";
}

}  // namespace

struct HeadlessContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
  std::string platform;

  ~Impl() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }

  // Tries the platforms in order of independence from any window system.
  bool openDisplay(std::string& why) {
    const bool platformBase = epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base");
    auto tryDisplay = [&](EGLDisplay d, const char* name) {
      EGLint major = 0, minor = 0;
      if (d == EGL_NO_DISPLAY) return false;
      if (!eglInitialize(d, &major, &minor)) {
        why += fmt::format("{}: eglInitialize failed ({}); ", name, eglErrorName(eglGetError()));
        return false;
      }
      display = d;
      platform = name;
      return true;
    };
    if (platformBase && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless") &&
        tryDisplay(
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
            "EGL surfaceless"))
      return true;
    if (platformBase && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") &&
        epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
      EGLDeviceEXT devices[8];
      EGLint n = 0;
      if (eglQueryDevicesEXT(8, devices, &n))
        for (EGLint k = 0; k < n; ++k)
          if (tryDisplay(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[k], nullptr),
                         "EGL device"))
            return true;
    }
    if (tryDisplay(eglGetDisplay(EGL_DEFAULT_DISPLAY), "EGL default display")) return true;
    if (why.empty()) why = "no EGL display could be opened; ";
    return false;
  }
};

HeadlessContext::HeadlessContext() : impl_(std::make_unique<Impl>()) {
  std::string why;
  if (!impl_->openDisplay(why))
    throw Error("cannot create a headless OpenGL context: " + why.substr(0, why.size() - 2));
  Impl& m = *impl_;
  if (!eglBindAPI(EGL_OPENGL_API))
    throw Error("cannot create a headless OpenGL context: " + m.platform +
                " has no desktop OpenGL (" + eglErrorName(eglGetError()) + ")");
  const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                  EGL_PBUFFER_BIT,
                                  EGL_RENDERABLE_TYPE,
                                  EGL_OPENGL_BIT,
                                  EGL_RED_SIZE,
                                  8,
                                  EGL_GREEN_SIZE,
                                  8,
                                  EGL_BLUE_SIZE,
                                  8,
                                  EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  eglChooseConfig(m.display, configAttribs, &config, 1, &count);
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                   3,
                                   EGL_CONTEXT_MINOR_VERSION,
                                   3,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                   EGL_NONE};
  const bool noConfig = epoxy_has_egl_extension(m.display, "EGL_KHR_no_config_context");
  if (count == 0 && !noConfig)
    throw Error("cannot create a headless OpenGL context: " + m.platform +
                " offers no OpenGL pbuffer config");
  m.context = eglCreateContext(m.display, count > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                               contextAttribs);
  if (m.context == EGL_NO_CONTEXT)
    throw Error("cannot create an OpenGL 3.3 core context on " + m.platform + " (" +
                eglErrorName(eglGetError()) + ")");
  // Surfaceless where the driver allows it, else a 1×1 pbuffer: we draw into FBOs anyway.
  if (!epoxy_has_egl_extension(m.display, "EGL_KHR_surfaceless_context") && count > 0) {
    const EGLint pbufferAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    m.surface = eglCreatePbufferSurface(m.display, config, pbufferAttribs);
  }
  if (!eglMakeCurrent(m.display, m.surface, m.surface, m.context))
    throw Error("cannot make the headless OpenGL context current (" + eglErrorName(eglGetError()) +
                ")");
  if (epoxy_gl_version() < 33)
    throw Error("the headless OpenGL context is " + glString(GL_VERSION) + "; 3.3 is needed");
  description_ = glString(GL_RENDERER) + ", OpenGL " + glString(GL_VERSION) + ", " + m.platform;
}

HeadlessContext::~HeadlessContext() = default;

bool headlessAvailable(std::string* why) {
  try {
    HeadlessContext context;
    return true;
  } catch (const std::exception& e) {
    if (why) *why = e.what();
    return false;
  }
}

namespace {
std::string& glfwLastError() {
  static std::string s;
  return s;
}
extern "C" void onGlfwError(int, const char* message) {
  glfwLastError() = message;
}
}  // namespace

void initWindowSystem() {
  static bool done = false;
  if (done) return;
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    const bool none = (!display || !*display) && (!wayland || !*wayland);
    throw Error(std::string("cannot open a window: ") +
                (none ? "no display available (DISPLAY is not set)"
                      : "the display cannot be opened (" + glfwLastError() + ")") +
                "; use --headless --screenshot FILE to render without one");
  }
  std::atexit(glfwTerminate);
  done = true;
}

Window::Window(int width, int height, const std::string& title) {
  initWindowSystem();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 0);  // the renderer multisamples its own framebuffer
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) throw Error("cannot open an OpenGL 3.3 core window (" + glfwLastError() + ")");
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
}

std::string Window::renderer() const {
  return glString(GL_RENDERER) + ", OpenGL " + glString(GL_VERSION) + ", GLFW";
}

}  // namespace prt::viewer
