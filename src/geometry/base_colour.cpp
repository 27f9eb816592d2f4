#include "prt/geometry/base_colour.hpp"

#include <cmath>

#include "prt/image/color.hpp"

namespace prt {

Rgb sampleBaseColour(const BaseColourTexture& texture, Vec2f uv) {
  const image::Srgb8Image& im = texture.image;
  if (im.empty() || im.width < 1 || im.height < 1 || !std::isfinite(uv.x) || !std::isfinite(uv.y))
    return Rgb(1.0f);
  // Repeat: only the fraction of u and v matters (in double, so u = 1e7 + 0.25 keeps its 0.25
  // as well as float held it). Continuous texel coordinates put texel centres on integers.
  const double u = double(uv.x) - std::floor(double(uv.x));
  const double v = double(uv.y) - std::floor(double(uv.y));
  const double x = u * im.width - 0.5, y = v * im.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const float fx = float(x - x0), fy = float(y - y0);
  // x0 lies in [−1, W − 1]: −1 wraps to the last column, x0 + 1 = W to the first.
  const auto wrap = [](int i, int n) { return i < 0 ? i + n : i >= n ? i - n : i; };
  const int xa = wrap(int(x0), im.width), xb = wrap(int(x0) + 1, im.width);
  const int ya = wrap(int(y0), im.height), yb = wrap(int(y0) + 1, im.height);
  const auto texel = [&im](int tx, int ty) {
    return Rgb{image::srgb8ToLinear(im.code(tx, ty, 0)), image::srgb8ToLinear(im.code(tx, ty, 1)),
               image::srgb8ToLinear(im.code(tx, ty, 2))};
  };
  return (texel(xa, ya) * (1.0f - fx) + texel(xb, ya) * fx) * (1.0f - fy) +
         (texel(xa, yb) * (1.0f - fx) + texel(xb, yb) * fx) * fy;
}

}  // namespace prt
