// Zonal convolution, the clamped-cosine kernel, the RH quadratic form, windows and de-ringing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "prt/core/error.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/project.hpp"

using namespace prt;
using namespace prt::sh;

// Λ_l against Funk–Hecke by numeric quadrature: 2π ∫_0^1 t P_l(t) dt (Gauss–Legendre on [0, 1],
// exact for this polynomial), for l up to 31.
TEST(ShConvolve, ClampedCosineKernelMatchesQuadrature) {
  const auto k = clampedCosineKernel(kMaxBands);
  const SphereQuadrature q = gaussLegendreSphere(40);  // z nodes reused on [-1, 1]
  for (int l = 0; l < kMaxBands; ++l) {
    // ∫ over the sphere of max(z, 0) P_l(z) = 2π ∫ max(t,0) P_l(t) dt; the kink at t = 0 is not
    // polynomial, so integrate on [0, 1] by mapping nodes t = (z + 1)/2.
    double s = 0;
    for (std::size_t p = 0; p < q.dirs.size(); ++p) {
      const double t = 0.5 * (q.dirs[p].z + 1);
      double p0 = 1, p1 = t;
      for (int n = 2; n <= l; ++n) {
        const double pn = ((2.0 * n - 1) * t * p1 - (n - 1.0) * p0) / n;
        p0 = p1;
        p1 = pn;
      }
      const double pl = l == 0 ? 1 : p1;
      s += q.weights[p] * 0.5 * t * pl;  // dt = dz/2; Σ over φ of w/(2π)·2π keeps the 2π
    }
    EXPECT_NEAR(k[l], s, 1e-12) << "l=" << l;
  }
  EXPECT_NEAR(k[0], kPi, 1e-15);
  EXPECT_NEAR(k[2], kPi / 4, 1e-15);
}

// Irradiance of band-limited radiance, by convolution and by brute-force quadrature of
// ∫ L(ω) max(n·ω, 0) dω; and the RH quadratic form equals the convolution route.
TEST(ShConvolve, IrradianceRoutesAgree) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  RgbSh L(3);
  for (auto& c : L.c) c = Rgb(float(u(rng)), float(u(rng)), float(u(rng)));
  const RgbSh E = irradiance(L);
  const SphereQuadrature q = gaussLegendreSphere(200);
  for (int t = 0; t < 20; ++t) {
    const Vec3d n = normalize(Vec3d(u(rng), u(rng), u(rng)));
    const Rgb conv = reconstruct(E, Vec3f(n));
    const Rgb quad = irradianceQuadratic(L, Vec3f(n));
    Rgbd brute(0.0);
    for (std::size_t p = 0; p < q.dirs.size(); ++p) {
      const double c = dot(n, q.dirs[p]);
      if (c > 0) brute += Rgbd(reconstruct(L, Vec3f(q.dirs[p]))) * (c * q.weights[p]);
    }
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(quad[ch], conv[ch], 1e-5);
      EXPECT_NEAR(conv[ch], brute[ch], 2e-3);  // the kink limits quadrature accuracy
    }
  }
  EXPECT_THROW(irradianceQuadratic(RgbSh(2), Vec3f(0, 0, 1)), Error);
}

// Convolution theorem at higher bands: projecting E(n) computed by quadrature gives Λ_l L_lm.
TEST(ShConvolve, HigherBandsMatchQuadrature) {
  const int bands = 8;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  RgbSh L(bands);
  for (auto& c : L.c) c = Rgb(float(u(rng)));
  const SphereQuadrature fine = gaussLegendreSphere(150);
  std::vector<double> lv(fine.dirs.size());
  for (std::size_t p = 0; p < fine.dirs.size(); ++p) lv[p] = reconstruct(L, Vec3f(fine.dirs[p])).x;
  const ShCoeffs E = projectFunction(
      bands,
      [&](const Vec3d& n) {
        double s = 0;
        for (std::size_t p = 0; p < fine.dirs.size(); ++p)
          s += lv[p] * std::fmax(dot(n, fine.dirs[p]), 0.0) * fine.weights[p];
        return s;
      },
      bands + 4);
  const RgbSh conv = irradiance(L);
  for (int i = 0; i < bands * bands; ++i) EXPECT_NEAR(E.c[i], conv.c[i].x, 3e-3) << i;
}

namespace {
// A sharp cap: 1 within 30° of +Y, projected at B bands (rings strongly).
RgbSh sharpCap(int bands) {
  const double c0 = std::cos(30 * kPi / 180);
  return projectFunctionRgb(
      bands, [c0](const Vec3d& d) { return Rgbd(d.y > c0 ? 1.0 : 0.0); }, 64);
}
}  // namespace

TEST(ShWindow, WindowsReduceRinging) {
  const int bands = 9;
  const RgbSh cap = sharpCap(bands);
  const double before = minimumValue(cap);
  EXPECT_LT(before, -0.01);  // it does ring
  for (const auto& w : {hanningWindow(bands), lanczosWindow(bands)}) {
    EXPECT_DOUBLE_EQ(w[0], 1.0);
    for (int l = 1; l < bands; ++l) EXPECT_LE(w[l], w[l - 1]);
    RgbSh c = cap;
    convolveZonal(c, w);
    EXPECT_GT(minimumValue(c), before);
  }
  EXPECT_NEAR(hanningWindow(4, 2)[1], 0.5, 1e-15);
  EXPECT_EQ(hanningWindow(4, 2)[2], 0.0);
  EXPECT_THROW(hanningWindow(4, -1), Error);
}

TEST(ShWindow, DeringMakesNonNegative) {
  for (int bands : {3, 6, 9, 16}) {
    RgbSh c = sharpCap(bands);
    const RgbSh orig = c;
    const DeringResult r = dering(c);
    EXPECT_LT(r.minBefore, 0) << bands;
    EXPECT_NEAR(r.minBefore, minimumValue(orig), 1e-12);
    // Checked on the library's grid and on an independent finer one.
    const double maxV = reconstruct(c, Vec3f(0, 1, 0)).x;
    EXPECT_GE(r.minAfter, -1e-6 * maxV) << bands;
    EXPECT_GE(minimumValue(c), -1e-6 * maxV);
    const SphereQuadrature g = gaussLegendreSphere(97);
    double lo = 1e9;
    for (const auto& d : g.dirs) lo = std::fmin(lo, reconstruct(c, Vec3f(d)).x);
    EXPECT_GE(lo, -1e-6 * maxV) << bands;
    // The window keeps the mean.
    EXPECT_EQ(c.c[0], orig.c[0]);
    ASSERT_EQ(int(r.window.size()), bands);
  }
}
