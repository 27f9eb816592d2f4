// Layout geometry: every layout's texel solid angles sum to 4π, per-texel solid angles agree with
// independent quadratures, direction conventions hold (lat-long azimuth, OpenGL faces, crosses).

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "prt/core/error.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/envmap/layout.hpp"

using namespace prt;
using namespace prt::envmap;

namespace {

double totalSolidAngle(const Environment& env) {
  double s = 0;
  for (std::size_t k = 0; k < env.texelCount(); ++k) s += env.texelSolidAngle(k);
  return s;
}

double angleBetween(const Vec3d& a, const Vec3d& b) {
  return std::atan2(length(cross(a, b)), dot(a, b));
}

}  // namespace

TEST(Layout, ConstantEnvironmentIntegratesTo4PiInEveryLayout) {
  const double fourPi = 4 * kPi;
  for (int h : {1, 3, 32, 101})
    EXPECT_NEAR(totalSolidAngle(Environment::latLong(image::Image(2 * h, h))) / fourPi, 1, 1e-6);
  for (int n : {1, 2, 7, 64}) {
    std::array<image::Image, 6> faces;
    for (auto& f : faces) f = image::Image(n, n);
    EXPECT_NEAR(totalSolidAngle(Environment::cube(faces)) / fourPi, 1, 1e-6) << n;
    EXPECT_NEAR(
        totalSolidAngle(Environment::cross(image::Image(3 * n, 4 * n), Layout::VCross)) / fourPi, 1,
        1e-6);
    EXPECT_NEAR(
        totalSolidAngle(Environment::cross(image::Image(4 * n, 3 * n), Layout::HCross)) / fourPi, 1,
        1e-6);
  }
  for (int n : {1, 2, 5, 64, 129})
    EXPECT_NEAR(totalSolidAngle(Environment::probe(image::Image(n, n))) / fourPi, 1, 1e-6) << n;
  EXPECT_NEAR(
      totalSolidAngle(Environment::analytic([](const Vec3f&) { return Rgb(1.0f); }, {}, 64)) /
          fourPi,
      1, 1e-6);
}

TEST(Layout, CubeTexelSolidAngleMatchesQuadrature) {
  // dω = ds dt / (1 + s² + t²)^{3/2} on the face plane at unit distance; midpoint rule, 200².
  const int n = 5;
  const std::vector<double> sa = cubeTexelSolidAngles(n);
  for (int y : {0, 2}) {
    for (int x : {0, 1, 4}) {
      const double s0 = 2.0 * x / n - 1, t0 = 2.0 * y / n - 1, h = 2.0 / n / 200;
      double q = 0;
      for (int j = 0; j < 200; ++j)
        for (int i = 0; i < 200; ++i) {
          const double s = s0 + (i + 0.5) * h, t = t0 + (j + 0.5) * h;
          q += h * h / std::pow(1 + s * s + t * t, 1.5);
        }
      EXPECT_NEAR(sa[y * n + x], q, 1e-6 * q) << x << "," << y;
    }
  }
}

TEST(Layout, ProbeTexelSolidAngleMatchesQuadrature) {
  // dω = π sin(πr)/r dA inside the unit disc, 0 outside; dense midpoint sampling of the texel.
  const int n = 9;
  const std::vector<double> sa = probeTexelSolidAngles(n, n);
  for (auto [x, y] :
       std::vector<std::pair<int, int>>{{4, 4}, {5, 3}, {8, 4}, {0, 0}, {1, 1}, {7, 2}}) {
    const int m = 800;
    const double a0 = 2.0 * x / n - 1, b0 = 1 - 2.0 * (y + 1) / n, h = 2.0 / n / m;
    double q = 0;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const double a = a0 + (i + 0.5) * h, b = b0 + (j + 0.5) * h, r = std::hypot(a, b);
        if (r < 1) q += h * h * kPi * std::sin(kPi * r) / r;
      }
    EXPECT_NEAR(sa[y * n + x], q, 2e-4 * std::max(q, 0.01)) << x << "," << y;
  }
  EXPECT_EQ(sa[0], 0.0);  // the corner texel lies outside the disc
}

TEST(Layout, LatLongConvention) {
  // Stated convention: top row up, centre column +X, u = 1/4 → −Z, u = 3/4 → +Z, edges −X.
  const int w = 400, h = 200;
  EXPECT_NEAR(latLongDirection(w, h, 200, 100).x, 1, 1e-12);
  EXPECT_NEAR(latLongDirection(w, h, 100, 100).z, -1, 1e-12);
  EXPECT_NEAR(latLongDirection(w, h, 300, 100).z, 1, 1e-12);
  EXPECT_NEAR(latLongDirection(w, h, 0, 100).x, -1, 1e-12);
  EXPECT_NEAR(latLongDirection(w, h, 17, 0).y, 1, 1e-12);
  EXPECT_NEAR(latLongDirection(w, h, 17, 200).y, -1, 1e-12);
  for (double x : {0.5, 33.25, 211.0, 399.5})
    for (double y : {0.5, 57.0, 150.5}) {
      float px, py;
      latLongPixel(Vec3f(latLongDirection(w, h, x, y)), w, h, px, py);
      EXPECT_NEAR(px, x, 1e-3);
      EXPECT_NEAR(py, y, 1e-3);
    }
}

TEST(Layout, CubeFacesFollowOpenGL) {
  // Face centres and the orientation of s and t (OpenGL 4.6 table 8.19: +X has sc = −z, tc = −y).
  const Vec3d centres[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f)
    EXPECT_LT(angleBetween(cubeFaceDirection(f, 0, 0), centres[f]), 1e-12);
  EXPECT_LT(angleBetween(cubeFaceDirection(PosX, 1, 0), {1, 0, -1}), 1e-12);
  EXPECT_LT(angleBetween(cubeFaceDirection(PosX, 0, -1), {1, 1, 0}), 1e-12);  // top row looks up
  EXPECT_LT(angleBetween(cubeFaceDirection(PosZ, 1, 0), {1, 0, 1}), 1e-12);
  EXPECT_LT(angleBetween(cubeFaceDirection(PosY, 0, 1), {0, 1, 1}),
            1e-12);  // +Y bottom edge meets +Z
  EXPECT_LT(angleBetween(cubeFaceDirection(NegY, 0, -1), {0, -1, 1}), 1e-12);
  for (int f = 0; f < 6; ++f)
    for (double s : {-0.9, 0.1, 0.7})
      for (double t : {-0.3, 0.95}) {
        float ss, tt;
        EXPECT_EQ(cubeFaceCoords(Vec3f(cubeFaceDirection(f, s, t)), ss, tt), f);
        EXPECT_NEAR(ss, s, 1e-6);
        EXPECT_NEAR(tt, t, 1e-6);
      }
}

TEST(Layout, CrossNeighboursAreNeighboursOnTheSphere) {
  // Each cross pixel stores its own (x, y); after cutting into faces every texel knows where it
  // came from. Pixels adjacent in the cross image within the cross's cells must then look in
  // directions about one texel apart, which checks every cut and the 180° turn of −Z.
  const int n = 8;
  for (Layout layout : {Layout::VCross, Layout::HCross}) {
    const int w = layout == Layout::VCross ? 3 * n : 4 * n,
              h = layout == Layout::VCross ? 4 * n : 3 * n;
    image::Image img(w, h, Rgb(-1.0f));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        img.at(x, y) = Rgb(static_cast<float>(x), static_cast<float>(y), 1.0f);
    const Environment env = Environment::cross(img, layout);
    std::map<std::pair<int, int>, Vec3d> dirOf;
    for (std::size_t k = 0; k < env.texelCount(); ++k) {
      const Texel t = env.texel(k);
      dirOf[{static_cast<int>(t.radiance.x), static_cast<int>(t.radiance.y)}] = Vec3d(t.direction);
    }
    ASSERT_EQ(dirOf.size(), 6u * n * n);
    int pairs = 0;
    for (const auto& [p, d] : dirOf)
      for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        auto it = dirOf.find({p.first + dx, p.second + dy});
        if (it == dirOf.end()) continue;
        EXPECT_LT(angleBetween(d, it->second), 2.5 * (kPi / 2) / n) << p.first << "," << p.second;
        ++pairs;
      }
    EXPECT_GT(pairs, 6 * n * (n - 1) * 2);  // includes pairs across cell borders
  }
}

TEST(Layout, DetectionAndParsing) {
  EXPECT_EQ(detectLayout(512, 256, "a"), Layout::LatLong);
  EXPECT_EQ(detectLayout(300, 300, "a"), Layout::Probe);
  EXPECT_EQ(detectLayout(300, 400, "a"), Layout::VCross);
  EXPECT_EQ(detectLayout(400, 300, "a"), Layout::HCross);
  try {
    detectLayout(500, 256, "odd.hdr");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("odd.hdr: 500x256 fits no layout"), std::string::npos)
        << e.what();
  }
  for (Layout l : {Layout::LatLong, Layout::Probe, Layout::VCross, Layout::HCross, Layout::Faces})
    EXPECT_EQ(parseLayout(layoutName(l)), l);
  EXPECT_THROW(parseLayout("sphere"), Error);
}

TEST(Environment, LookupReturnsTexelValuesAtTexelCentres) {
  image::Image ll(16, 8);
  for (std::size_t i = 0; i < ll.size(); ++i) ll.pixels[i] = Rgb(static_cast<float>(i));
  std::array<image::Image, 6> faces;
  for (int f = 0; f < 6; ++f) {
    faces[f] = image::Image(4, 4);
    for (std::size_t i = 0; i < 16; ++i) faces[f].pixels[i] = Rgb(static_cast<float>(100 * f + i));
  }
  image::Image pr(9, 9);
  for (std::size_t i = 0; i < pr.size(); ++i) pr.pixels[i] = Rgb(static_cast<float>(i));
  // Probe texels whose centre lies outside the unit disc are skipped: the whole rim maps to the
  // one direction +Z, so a lookup there cannot pick the texel back out.
  const auto rimOfProbe = [&](std::size_t k) {
    const double a = 2.0 * (k % 9 + 0.5) / 9 - 1, b = 1 - 2.0 * (k / 9 + 0.5) / 9;
    return a * a + b * b > 1;
  };
  int probeChecked = 0;
  for (const Environment& env :
       {Environment::latLong(ll), Environment::cube(faces), Environment::probe(pr)})
    for (std::size_t k = 0; k < env.texelCount(); ++k) {
      const Texel t = env.texel(k);
      if (t.solidAngle == 0) continue;
      if (env.texelCount() == pr.size()) {  // the probe (the others have 128 and 96)
        if (rimOfProbe(k)) continue;
        ++probeChecked;
      }
      EXPECT_NEAR(env.lookup(t.direction).x, t.radiance.x, 1e-3 * (1 + t.radiance.x)) << k;
    }
  EXPECT_GE(probeChecked, 49);  // the inner texels of the 9×9 probe were all checked
}
