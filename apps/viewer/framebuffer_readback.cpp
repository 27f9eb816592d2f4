#include "framebuffer_readback.hpp"

#include <epoxy/gl.h>

#include <fmt/format.h>

#include <cstddef>
#include <vector>

#include "prt/core/error.hpp"
#include "renderer.hpp"

namespace prt::viewer {

namespace {

/// Reads the bound read framebuffer's colour attachment into a top-row-first image.
image::Image readPixels(int w, int h, GLenum type) {
  image::Image img;
  img.width = w, img.height = h;
  img.pixels.resize(std::size_t(w) * h);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (type == GL_FLOAT) {
    std::vector<float> rows(std::size_t(w) * h * 3);
    glReadPixels(0, 0, w, h, GL_RGB, GL_FLOAT, rows.data());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float* p = &rows[(std::size_t(h - 1 - y) * w + x) * 3];
        img.pixels[std::size_t(y) * w + x] = {p[0], p[1], p[2]};
      }
  } else {
    std::vector<unsigned char> rows(std::size_t(w) * h * 3);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const unsigned char* p = &rows[(std::size_t(h - 1 - y) * w + x) * 3];
        img.pixels[std::size_t(y) * w + x] = {p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f};
      }
  }
  return img;
}

}  // namespace

// ---- OffscreenTarget ------------------------------------------------------------------------

OffscreenTarget::OffscreenTarget(int width, int height) : width_(width), height_(height) {
  glGenTextures(1, &colour_);
  glBindTexture(GL_TEXTURE_2D, colour_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error(fmt::format("cannot create a {}x{} offscreen framebuffer", width, height));
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

OffscreenTarget::~OffscreenTarget() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &colour_);
}

image::Image OffscreenTarget::readEncoded() const {
  return readFramebufferEncoded(fbo_, width_, height_);
}

image::Image readFramebufferEncoded(unsigned fbo, int width, int height) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  if (fbo == 0) glReadBuffer(GL_BACK);
  image::Image img = readPixels(width, height, GL_UNSIGNED_BYTE);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return img;
}

image::Image Renderer::readLinear() const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolveFbo_);
  image::Image img = readPixels(fbWidth_, fbHeight_, GL_FLOAT);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return img;
}

}  // namespace prt::viewer
