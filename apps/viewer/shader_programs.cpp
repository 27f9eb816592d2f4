#include "shader_programs.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "renderer.hpp"

namespace prt::viewer {

// ---- shaders ---------------------------------------------------------------------------------
// The stages live in shaders/stages/ (shared with the web page), flattened with the desktop's
// host interface shaders/hosts/gl33.glsl and embedded at configure time (cmake/Shaders.cmake).
// Each source gets the desktop's #version here and the sizes its arrays take from the C++
// limits: the light block's kMaxPackedCoeffs vec4s, the glossy kernels' kMaxShaderGlossy².

std::string glsl330(const char* body, const char* defines) {
  return fmt::format(
      "#version 330 core\n#define PRT_LIGHT_VEC4S {}\n#define PRT_GLOSSY_COEFFS {}\n{}{}",
      kMaxViewerCoeffs, bands::kMaxShaderGlossy * bands::kMaxShaderGlossy, defines, body);
}

namespace {

GLuint compile(GLenum type, const std::string& source, const char* name) {
  const GLuint s = glCreateShader(type);
  const char* src = source.c_str();
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    std::string line(log);
    std::replace(line.begin(), line.end(), '\n', ' ');
    glDeleteShader(s);
    throw Error(fmt::format("viewer shader '{}' does not compile: {}", name, line));
  }
  return s;
}

}  // namespace

GLuint link(const std::string& vs, const std::string& fs, const char* name) {
  const GLuint v = compile(GL_VERTEX_SHADER, vs, name), f = compile(GL_FRAGMENT_SHADER, fs, name);
  const GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    glDeleteProgram(p);
    throw Error(fmt::format("viewer shader '{}' does not link: {}", name, log));
  }
  return p;
}

}  // namespace prt::viewer
