#include "prt/envmap/preview.hpp"

#include <cmath>

#include "prt/core/parallel.hpp"
#include "prt/image/color.hpp"
#include "prt/image/exposure.hpp"
#include "prt/sh/convolve.hpp"

namespace prt::envmap {

namespace {

template <typename Fn>
image::Image renderLatLong(int width, const Fn& fn) {
  const int w = width, h = width / 2;
  image::Image img(w, h);
  parallelFor(static_cast<std::size_t>(h), 1, [&](std::size_t y0, std::size_t y1) {
    for (std::size_t y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x)
        img.at(x, static_cast<int>(y)) =
            fn(Vec3f(latLongDirection(w, h, x + 0.5, static_cast<double>(y) + 0.5)));
  });
  return img;
}

}  // namespace

image::Image renderEnvironment(const Environment& env, int width, const Mat3d& rotation) {
  const Mat3f rt = rotation.transposed().cast<float>();
  return renderLatLong(width, [&](const Vec3f& d) { return env.lookup(rt * d); });
}

image::Image renderSh(const sh::RgbSh& f, int width) {
  return renderLatLong(width, [&](const Vec3f& d) { return sh::reconstruct(f, d); });
}

image::Image renderIrradiance(const sh::RgbSh& f, int width) {
  sh::RgbSh e = sh::irradiance(f);
  for (Rgb& c : e.c) c /= kPif;
  return renderSh(e, width);
}

image::Image previewPanels(const Environment& env, const sh::RgbSh& f, int width,
                           const Mat3d& rotation) {
  const image::Image a = renderEnvironment(env, width, rotation), b = renderSh(f, width),
                     c = renderIrradiance(f, width);
  return image::stackVertically({&a, &b, &c});
}

float previewExposure(const image::Image& panels, image::ToneMap op) {
  const int h = panels.height / 3;
  const image::Image irradiance =
      image::crop(panels, 0, 2 * h, panels.width, panels.height - 2 * h);
  return image::autoExposure(irradiance.pixels, op);
}

}  // namespace prt::envmap
