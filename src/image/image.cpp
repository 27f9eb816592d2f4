#include "prt/image/image.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"

namespace prt::image {

Image crop(const Image& src, int x0, int y0, int w, int h) {
  PRT_CHECK(x0 >= 0 && y0 >= 0 && w >= 0 && h >= 0 && x0 + w <= src.width && y0 + h <= src.height,
            "crop outside the image");
  Image out(w, h);
  for (int y = 0; y < h; ++y) std::copy_n(&src.at(x0, y0 + y), w, &out.at(0, y));
  return out;
}

Image rotated180(const Image& src) {
  Image out = src;
  std::reverse(out.pixels.begin(), out.pixels.end());
  return out;
}

Image stackVertically(const std::vector<const Image*>& parts) {
  int w = parts.empty() ? 0 : parts[0]->width, h = 0;
  for (const Image* p : parts) {
    PRT_CHECK(p->width == w, "stacked images must share their width");
    h += p->height;
  }
  Image out(w, h);
  auto it = out.pixels.begin();
  for (const Image* p : parts) it = std::copy(p->pixels.begin(), p->pixels.end(), it);
  return out;
}

Rgb sampleBilinear(const Image& img, double x, double y, bool wrapX) {
  const double fx = x - 0.5, fy = y - 0.5;
  const double x0f = std::floor(fx), y0f = std::floor(fy);
  const float tx = static_cast<float>(fx - x0f), ty = static_cast<float>(fy - y0f);
  auto cx = [&](long v) -> int {
    if (wrapX) {
      long m = v % img.width;
      return static_cast<int>(m < 0 ? m + img.width : m);
    }
    return static_cast<int>(std::clamp<long>(v, 0, img.width - 1));
  };
  auto cy = [&](long v) { return static_cast<int>(std::clamp<long>(v, 0, img.height - 1)); };
  const long x0 = static_cast<long>(x0f), y0 = static_cast<long>(y0f);
  const int xa = cx(x0), xb = cx(x0 + 1), ya = cy(y0), yb = cy(y0 + 1);
  const Rgb top = img.at(xa, ya) * (1 - tx) + img.at(xb, ya) * tx;
  const Rgb bottom = img.at(xa, yb) * (1 - tx) + img.at(xb, yb) * tx;
  return top * (1 - ty) + bottom * ty;
}

}  // namespace prt::image
