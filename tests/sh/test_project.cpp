// Projection recovers band-limited functions exactly; samples accumulate deterministically.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/project.hpp"

using namespace prt;
using namespace prt::sh;

TEST(ShProject, RecoversBandLimitedFunctions) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int bands : {1, 2, 3, 6, 9, 16}) {
    const int n = bands * bands;
    std::vector<double> coef(n);
    for (double& c : coef) c = u(rng);
    auto f = [&](const Vec3d& d) {
      std::vector<double> y(n);
      evalReference(bands, d, y.data());  // independent of the projection's own eval
      double s = 0;
      for (int i = 0; i < n; ++i) s += coef[i] * y[i];
      return s;
    };
    // Exact with the minimal order n = bands (degree 2B-2 ≤ 2n-1) and with the default.
    for (int qn : {bands, 0}) {
      const ShCoeffs p = projectFunction(bands, f, qn);
      for (int i = 0; i < n; ++i)
        EXPECT_NEAR(p.c[i], coef[i], 2e-6) << "bands=" << bands << " i=" << i;
    }
  }
}

TEST(ShProject, AnalyticFunctions) {
  // z² = 1/3 + (3z² − 1)/3 = a Y00 + b Y20 with Y00 = 1/sqrt(4π), Y20 = k20 (3z² − 1).
  const double k20 = std::sqrt(5.0 / (16 * kPi));
  const double a = std::sqrt(4 * kPi) / 3, b = 1.0 / (3 * k20);
  const ShCoeffs p = projectFunction(4, [](const Vec3d& d) { return d.z * d.z; });
  EXPECT_NEAR(p.c[0], a, 1e-6);
  EXPECT_NEAR(p.c[index(2, 0)], b, 1e-6);
  for (int i = 0; i < 16; ++i)
    if (i != 0 && i != index(2, 0)) {
      EXPECT_NEAR(p.c[i], 0, 1e-6) << i;
    }
  // A constant c has the single coefficient c·sqrt(4π).
  const RgbSh k = projectFunctionRgb(3, [](const Vec3d&) { return Rgbd(1, 2, 3); });
  EXPECT_NEAR(k.c[0].y, 2 * std::sqrt(4 * kPi), 1e-5);
  EXPECT_NEAR(k.c[4].z, 0, 1e-6);
}

TEST(ShProject, SamplesMatchQuadratureAndAreDeterministic) {
  const int bands = 5;
  const SphereQuadrature q = gaussLegendreSphere(12);
  std::vector<Vec3f> dirs;
  std::vector<Rgb> vals;
  std::vector<float> w;
  auto f = [](const Vec3d& d) { return Rgbd(1 + d.x, std::exp(d.y), d.z * d.z * d.x); };
  for (std::size_t k = 0; k < q.dirs.size(); ++k) {
    dirs.emplace_back(q.dirs[k]);
    vals.emplace_back(f(q.dirs[k]));
    w.push_back(float(q.weights[k]));
  }
  // Repeat to span several chunks.
  const std::size_t once = dirs.size();
  for (int rep = 0; rep < 40; ++rep)
    for (std::size_t k = 0; k < once; ++k) {
      dirs.push_back(dirs[k]);
      vals.push_back(vals[k]);
      w.push_back(w[k] / 41);
    }
  for (std::size_t k = 0; k < once; ++k) w[k] /= 41;
  const RgbSh a = projectSamples(bands, dirs, vals, w);
  const RgbSh ref = projectFunctionRgb(bands, f, 12);
  for (int i = 0; i < bands * bands; ++i) {
    EXPECT_NEAR(a.c[i].x, ref.c[i].x, 1e-5);
    EXPECT_NEAR(a.c[i].y, ref.c[i].y, 1e-5);
    EXPECT_NEAR(a.c[i].z, ref.c[i].z, 1e-5);
  }
  RgbSh one;
  {
    ThreadLimit limit(1);
    one = projectSamples(bands, dirs, vals, w);
  }
  for (int i = 0; i < bands * bands; ++i) EXPECT_EQ(one.c[i], a.c[i]);
  EXPECT_THROW(projectSamples(bands, dirs, vals, std::span<const float>(w).first(3)), Error);
}
