#pragma once
// The viewer's GLSL programs built from the embedded stages (prt_viewer_shaders.hpp): the
// desktop's #version and array sizes prepended, compiled and linked. Needs a current OpenGL 3.3
// core context.

#include <epoxy/gl.h>

#include <string>

namespace prt::viewer {

/// `body` as GLSL 3.30 core, after `defines` and the array sizes the C++ limits set.
std::string glsl330(const char* body, const char* defines = "");

/// Compiles and links a vertex and a fragment stage; throws prt::Error with the driver's log,
/// naming the program `name`.
GLuint link(const std::string& vs, const std::string& fs, const char* name);

}  // namespace prt::viewer
