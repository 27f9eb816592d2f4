#include "prt/envmap/environment.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"

namespace prt::envmap {

bool Cap::contains(const Vec3f& d) const {
  return static_cast<double>(dot(d, direction)) >= std::cos(halfAngle);
}

Rgb Cap::power() const {
  return radiance * static_cast<float>(2.0 * kPi * (1.0 - std::cos(halfAngle)));
}

Environment Environment::latLong(image::Image img) {
  PRT_CHECK(img.width == 2 * img.height && img.height > 0, "lat-long images are 2:1");
  Environment e;
  e.kind_ = Kind::LatLong;
  e.images_.push_back(std::move(img));
  e.initTables();
  return e;
}

Environment Environment::probe(image::Image img) {
  PRT_CHECK(img.width == img.height && img.width > 0, "probe images are square");
  Environment e;
  e.kind_ = Kind::Probe;
  e.images_.push_back(std::move(img));
  e.initTables();
  return e;
}

Environment Environment::cube(std::array<image::Image, 6> faces) {
  const int n = faces[0].width;
  for (const auto& f : faces)
    PRT_CHECK(f.width == n && f.height == n && n > 0, "cube faces are square and equal");
  Environment e;
  e.kind_ = Kind::Cube;
  for (auto& f : faces) e.images_.push_back(std::move(f));
  e.initTables();
  return e;
}

Environment Environment::cross(const image::Image& img, Layout layout) {
  std::array<image::Image, 6> faces;
  using image::crop;
  if (layout == Layout::VCross) {
    PRT_CHECK(4 * img.width == 3 * img.height, "vertical crosses are 3:4");
    const int n = img.width / 3;
    faces[PosY] = crop(img, n, 0, n, n);
    faces[NegX] = crop(img, 0, n, n, n);
    faces[PosZ] = crop(img, n, n, n, n);
    faces[PosX] = crop(img, 2 * n, n, n, n);
    faces[NegY] = crop(img, n, 2 * n, n, n);
    faces[NegZ] = image::rotated180(crop(img, n, 3 * n, n, n));
  } else {
    PRT_CHECK(layout == Layout::HCross && 3 * img.width == 4 * img.height,
              "horizontal crosses are 4:3");
    const int n = img.width / 4;
    faces[PosY] = crop(img, n, 0, n, n);
    faces[NegX] = crop(img, 0, n, n, n);
    faces[PosZ] = crop(img, n, n, n, n);
    faces[PosX] = crop(img, 2 * n, n, n, n);
    faces[NegZ] = crop(img, 3 * n, n, n, n);
    faces[NegY] = crop(img, n, 2 * n, n, n);
  }
  return cube(std::move(faces));
}

Environment Environment::analytic(std::function<Rgb(const Vec3f&)> smooth, std::vector<Cap> caps,
                                  int texelWidth) {
  PRT_CHECK(texelWidth >= 2 && texelWidth % 2 == 0, "texel width must be even");
  const int w = texelWidth, h = texelWidth / 2;
  image::Image smoothImg(w, h), full(w, h);
  // Per-texel angular half-diagonal bound: a texel spans ≤ π/h in θ and ≤ 2π/w in φ.
  const double texelRadius = std::hypot(kPi / h, 2 * kPi / w);
  parallelFor(static_cast<std::size_t>(h), 1, [&](std::size_t y0, std::size_t y1) {
    for (std::size_t yy = y0; yy < y1; ++yy) {
      const int y = static_cast<int>(yy);
      for (int x = 0; x < w; ++x) {
        const Vec3f d(latLongDirection(w, h, x + 0.5, y + 0.5));
        const Rgb s = smooth ? smooth(d) : Rgb(0.0f);
        smoothImg.at(x, y) = s;
        Rgb c = s;
        for (const Cap& cap : caps) {
          const double ang =
              std::acos(std::clamp(static_cast<double>(dot(d, cap.direction)), -1.0, 1.0));
          if (ang > cap.halfAngle + texelRadius) continue;
          if (ang < cap.halfAngle - texelRadius) {
            c += cap.radiance;
            continue;
          }
          // Covered fraction by 8×8 samples, weighted by their own (sin θ) area.
          double in = 0, all = 0;
          for (int j = 0; j < 8; ++j)
            for (int i = 0; i < 8; ++i) {
              const double sy = y + (j + 0.5) / 8, sx = x + (i + 0.5) / 8;
              const double wgt = std::sin(kPi * sy / h);
              all += wgt;
              if (cap.contains(Vec3f(latLongDirection(w, h, sx, sy)))) in += wgt;
            }
          if (all > 0) c += cap.radiance * static_cast<float>(in / all);
        }
        full.at(x, y) = c;
      }
    }
  });
  Environment e;
  e.kind_ = Kind::Analytic;
  e.images_.push_back(std::move(full));
  e.smoothImage_ = std::move(smoothImg);
  e.smooth_ = std::move(smooth);
  e.caps_ = std::move(caps);
  e.initTables();
  return e;
}

Environment Environment::smoothPart() const {
  PRT_CHECK(kind_ == Kind::Analytic, "smoothPart() needs an analytic environment");
  Environment e = latLong(smoothImage_);
  e.source_ = source_;
  return e;
}

void Environment::initTables() {
  const image::Image& img = images_.at(0);
  switch (kind_) {
    case Kind::Cube: {
      count_ = 6 * img.size();
      solid_ = std::make_shared<const std::vector<double>>(cubeTexelSolidAngles(img.width));
      break;
    }
    case Kind::Probe: {
      count_ = img.size();
      solid_ =
          std::make_shared<const std::vector<double>>(probeTexelSolidAngles(img.width, img.height));
      break;
    }
    case Kind::LatLong:
    case Kind::Analytic: {
      count_ = img.size();
      const int w = img.width, h = img.height;
      auto rows = std::make_shared<std::vector<double>>(h);
      auto rowTrig = std::make_shared<std::vector<float>>(2 * h);
      auto colTrig = std::make_shared<std::vector<float>>(2 * w);
      const double dphi = 2 * kPi / w;
      for (int y = 0; y < h; ++y) {
        (*rows)[y] = dphi * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
        const double theta = kPi * (y + 0.5) / h;
        (*rowTrig)[2 * y] = static_cast<float>(std::sin(theta));
        (*rowTrig)[2 * y + 1] = static_cast<float>(std::cos(theta));
      }
      for (int x = 0; x < w; ++x) {
        const double phi = 2 * kPi * ((x + 0.5) / w - 0.5);
        (*colTrig)[2 * x] = static_cast<float>(std::cos(phi));
        (*colTrig)[2 * x + 1] = static_cast<float>(std::sin(phi));
      }
      solid_ = rows;
      rowTrig_ = rowTrig;
      colTrig_ = colTrig;
      break;
    }
  }
  auto f = std::make_shared<std::vector<float>>(solid_->size());
  for (std::size_t i = 0; i < f->size(); ++i) (*f)[i] = static_cast<float>((*solid_)[i]);
  solidF_ = f;
}

double Environment::texelSolidAngle(std::size_t k) const {
  switch (kind_) {
    case Kind::Cube: {
      const std::size_t n2 = images_[0].size();
      return (*solid_)[k % n2];
    }
    case Kind::Probe:
      return (*solid_)[k];
    default:
      return (*solid_)[k / static_cast<std::size_t>(images_[0].width)];
  }
}

Texel Environment::texel(std::size_t k) const {
  Texel t;
  switch (kind_) {
    case Kind::Cube: {
      const int n = images_[0].width;
      const std::size_t n2 = images_[0].size();
      const int face = static_cast<int>(k / n2);
      const std::size_t r = k % n2;
      const int y = static_cast<int>(r / n), x = static_cast<int>(r % n);
      const float s = 2.0f * (x + 0.5f) / n - 1.0f, tt = 2.0f * (y + 0.5f) / n - 1.0f;
      const float inv = 1.0f / std::sqrt(s * s + tt * tt + 1.0f);
      const Vec3d d = cubeFaceDirection(face, s, tt);
      t.direction = Vec3f(d) * inv;
      t.solidAngle = (*solidF_)[r];
      t.radiance = images_[face].pixels[r];
      return t;
    }
    case Kind::Probe: {
      const image::Image& img = images_[0];
      const int y = static_cast<int>(k / img.width), x = static_cast<int>(k % img.width);
      t.solidAngle = (*solidF_)[k];
      const double a = 2.0 * (x + 0.5) / img.width - 1.0, b = 1.0 - 2.0 * (y + 0.5) / img.height;
      t.direction = Vec3f(probeDirection(a, b));
      t.radiance = img.pixels[k];
      return t;
    }
    default: {
      const image::Image& img = images_[0];
      const std::size_t y = k / img.width, x = k % img.width;
      const float st = (*rowTrig_)[2 * y], ct = (*rowTrig_)[2 * y + 1];
      t.direction = {st * (*colTrig_)[2 * x], ct, st * (*colTrig_)[2 * x + 1]};
      t.solidAngle = (*solidF_)[y];
      t.radiance = img.pixels[k];
      return t;
    }
  }
}

Rgb Environment::lookup(const Vec3f& dir) const {
  switch (kind_) {
    case Kind::Analytic: {
      Rgb c = smooth_ ? smooth_(dir) : Rgb(0.0f);
      for (const Cap& cap : caps_)
        if (cap.contains(dir)) c += cap.radiance;
      return c;
    }
    case Kind::LatLong: {
      const image::Image& img = images_[0];
      float px, py;
      latLongPixel(dir, img.width, img.height, px, py);
      return image::sampleBilinear(img, px, py, true);
    }
    case Kind::Cube: {
      float s, t;
      const int face = cubeFaceCoords(dir, s, t);
      const image::Image& img = images_[face];
      return image::sampleBilinear(img, (s + 1) * 0.5 * img.width, (t + 1) * 0.5 * img.height,
                                   false);
    }
    case Kind::Probe: {
      const image::Image& img = images_[0];
      const double len = length(Vec3d(dir));
      const double dx = dir.x / len, dy = dir.y / len, dz = dir.z / len;
      const double rho = std::sqrt(dx * dx + dy * dy);
      const double r = std::acos(std::clamp(-dz, -1.0, 1.0)) / kPi;
      const double a = rho > 0 ? dx * r / rho : 0, b = rho > 0 ? dy * r / rho : 0;
      return image::sampleBilinear(img, (a + 1) * 0.5 * img.width, (1 - b) * 0.5 * img.height,
                                   false);
    }
  }
  return Rgb(0.0f);
}

}  // namespace prt::envmap
