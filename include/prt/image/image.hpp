#pragma once
// An image of linear, scene-referred RGB float pixels, stored row-major with row 0 at the top
// (the order image files use). Pixel (x, y) covers [x, x+1) × [y, y+1); its centre is
// (x + 0.5, y + 0.5).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt::image {

/// The widest and tallest image any verb renders or a viewer opens (16384² is the pixel cap,
/// limits().maxImagePixels, at its default).
inline constexpr int kMaxImageSide = 16384;

struct Image {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;  ///< width·height pixels, row-major, top row first

  Image() = default;
  Image(int w, int h, Rgb fill = Rgb(0.0f))
      : width(w),
        height(h),
        pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill) {}

  bool empty() const { return pixels.empty(); }
  std::size_t size() const { return pixels.size(); }
  Rgb& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

/// An image of 8-bit sRGB-encoded RGB codes, row-major, top row first: a colour texture as PNG
/// and JPEG hold it (a material's base colour, geometry/base_colour.hpp). Kept as its codes, not
/// decoded, so it is written back bit for bit and decoded where it is sampled (srgb8ToLinear),
/// as a GPU's sRGB texture format does.
struct Srgb8Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 codes per pixel (r, g, b), width·height pixels

  bool empty() const { return rgb.empty(); }
  /// The code of channel c (0..2) of pixel (x, y).
  std::uint8_t code(int x, int y, int c) const {
    return rgb[3 * (static_cast<std::size_t>(y) * width + x) + c];
  }
  bool operator==(const Srgb8Image&) const = default;
};

/// A copy of the w×h block whose top-left pixel is (x0, y0) (must lie inside `src`).
Image crop(const Image& src, int x0, int y0, int w, int h);
/// Rotates by 180° (flips both axes).
Image rotated180(const Image& src);
/// Stacks images vertically (all must have the same width).
Image stackVertically(const std::vector<const Image*>& parts);
/// Bilinear lookup at continuous pixel coordinates (pixel centres at +0.5); x wraps around when
/// `wrapX`, otherwise clamps; y always clamps.
Rgb sampleBilinear(const Image& img, double x, double y, bool wrapX);

}  // namespace prt::image
