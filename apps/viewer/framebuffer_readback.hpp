#pragma once
// Frames read back to the CPU: an offscreen target for headless display output, and 8-bit
// framebuffers (the window's back buffer included) as images, top row first.
// Renderer::readLinear, the renderer's resolved float frame, is defined beside them
// (framebuffer_readback.cpp) so that all readback shares one pixel reader.

#include "prt/image/image.hpp"

namespace prt::viewer {

/// An RGBA8 colour framebuffer object for offscreen display output (headless mode).
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;
  unsigned fbo() const { return fbo_; }
  /// The tone-mapped sRGB pixels as an image of codes / 255 (top row first).
  image::Image readEncoded() const;

 private:
  int width_, height_;
  unsigned fbo_ = 0, colour_ = 0;
};

/// Reads an 8-bit framebuffer (0: the window's back buffer) as codes / 255, top row first.
image::Image readFramebufferEncoded(unsigned fbo, int width, int height);

}  // namespace prt::viewer
