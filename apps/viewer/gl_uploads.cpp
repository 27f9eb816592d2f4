#include "gl_uploads.hpp"

#include <fmt/format.h>

#include "prt/core/error.hpp"
#include "prt/core/vec.hpp"

namespace prt::viewer {

void requireTextureBufferTexels(double texels, const char* what, const char* advice) {
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  if (texels > double(maxTexels))
    throw Error(
        fmt::format("{} needs {:.0f} texels, more than this OpenGL's texture buffer "
                    "limit of {} ({})",
                    what, texels, maxTexels, advice));
}

void uploadTextureBuffer(GLuint& buffer, GLuint& texture, std::span<const float> rgba,
                         GLenum usage) {
  if (!buffer) glGenBuffers(1, &buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  // Orphan and refill: a previous frame may still be reading the old contents.
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(sizeof(float) * rgba.size()), rgba.data(), usage);
  if (!texture) glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_BUFFER, texture);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
}

static_assert(sizeof(Vec3f) == 3 * sizeof(float) && sizeof(Rgb) == 3 * sizeof(float));

void uploadVertexAttribute(GLuint& buffer, GLuint location, const void* data, std::size_t count,
                           GLenum usage) {
  if (!buffer) glGenBuffers(1, &buffer);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(sizeof(float) * 3 * count), data, usage);
  glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, sizeof(float) * 3, nullptr);
  glEnableVertexAttribArray(location);
}

void uploadLatLong(GLuint& texture, const image::Image& img) {
  if (!texture) glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, img.width, img.height, 0, GL_RGB, GL_FLOAT,
               img.pixels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

}  // namespace prt::viewer
