// Irradiance encodings (issue 34): each against an independent computation — brute-force
// quadrature of ∫ L max(n·ω, 0) dω, the projection onto a rotated zonal harmonic by quadrature,
// the papers' closed forms — and the invariants that make them worth storing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "prt/core/error.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/sh/project.hpp"

using namespace prt;
using namespace prt::sh;

namespace {

/// A light of `bands` bands: a positive constant and random higher bands of scale `spread`.
RgbSh randomLight(int bands, std::mt19937& rng, double spread) {
  std::normal_distribution<double> g(0, spread);
  RgbSh L(bands);
  for (int ch = 0; ch < 3; ++ch) L.c[0][ch] = float(1.0 + 0.2 * ch);
  for (int i = 1; i < bands * bands; ++i)
    for (int ch = 0; ch < 3; ++ch) L.c[i][ch] = float(g(rng) / (1 + i / 4));
  return L;
}

/// The radiance SH (up to `bands`) of a unit delta light from `dir`: L_lm = Y_lm(dir).
RgbSh deltaLight(int bands, const Vec3d& dir) {
  std::vector<double> y(bands * bands);
  eval(bands, dir, y.data());
  RgbSh L(bands);
  for (int i = 0; i < bands * bands; ++i) L.c[i] = Rgb(float(y[i]));
  return L;
}

/// Irradiance at n by brute force: the radiance reconstructed on a fine grid, times the clamped
/// cosine, summed (no kernel, no convolution theorem).
Rgbd bruteIrradiance(const RgbSh& L, const Vec3d& n) {
  static const SphereQuadrature q = gaussLegendreSphere(160);
  std::vector<double> y(L.bands * L.bands);
  Rgbd e(0.0);
  for (std::size_t p = 0; p < q.dirs.size(); ++p) {
    const double c = dot(n, q.dirs[p]);
    if (c <= 0) continue;
    eval(L.bands, q.dirs[p], y.data());
    Rgbd v(0.0);
    for (int i = 0; i < L.bands * L.bands; ++i) v += Rgbd(L.c[i]) * y[i];
    e += v * (c * q.weights[p]);
  }
  return e;
}

}  // namespace

TEST(IrradianceEncoding, NamesRoundTripAndABadOneListsThem) {
  for (IrradianceEncoding e : kIrradianceEncodings)
    EXPECT_EQ(parseIrradianceEncoding(toString(e)), e);
  try {
    parseIrradianceEncoding("zh4");
    FAIL() << "accepted zh4";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "encoding must be l2, l2-deringed, l1, l1-windowed, "
                  "l1-geomerics, zh3, zh3-shared, zh3-optimal or zh3-hallucinated, "
                  "got 'zh4'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(storedNumbers(IrradianceEncoding::L2), 27);
  EXPECT_EQ(storedNumbers(IrradianceEncoding::ZH3), 15);
  EXPECT_EQ(storedNumbers(IrradianceEncoding::ZH3Shared), 15);
  EXPECT_EQ(storedNumbers(IrradianceEncoding::ZH3Optimal), 17);
  EXPECT_EQ(storedNumbers(IrradianceEncoding::ZH3Hallucinated), 12);
  EXPECT_EQ(storedNumbers(IrradianceEncoding::L1Geomerics), 12);
}

// The band-1 vector in the project's signs: a delta light from d has band 1 along d.
TEST(IrradianceEncoding, BandOneVectorPointsAtTheLight) {
  const Vec3d d = normalize(Vec3d(0.3, -0.5, 0.8));
  const RgbSh L = deltaLight(2, d);
  const Vec3d v = bandOneVector(L.c[1].x, L.c[2].x, L.c[3].x);
  EXPECT_NEAR(length(v), 0.48860251190291992, 1e-6);
  EXPECT_NEAR(dot(normalize(v), d), 1.0, 1e-6);
}

// l2 and l1 are the irradiance's truncations: equal to brute-force irradiance of a light with
// no more bands than they keep.
TEST(IrradianceEncoding, TruncationsEqualBruteForceIrradiance) {
  std::mt19937 rng(7);
  const RgbSh L3 = randomLight(3, rng, 0.4);
  RgbSh L2 = L3;
  L2.bands = 2;
  L2.c.resize(4);
  const EncodedIrradiance e2 = encodeIrradiance(L3, IrradianceEncoding::L2);
  const EncodedIrradiance e1 = encodeIrradiance(L2, IrradianceEncoding::L1);
  for (const Vec3d& n : {Vec3d(0, 0, 1), normalize(Vec3d(1, -2, 0.5)), Vec3d(-1, 0, 0)}) {
    const Rgbd b3 = bruteIrradiance(L3, n), b2 = bruteIrradiance(L2, n);
    const Rgbd g3 = evaluate(e2, n), g2 = evaluate(e1, n);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(g3[ch], b3[ch], 2e-4 * std::fabs(b3[ch]) + 1e-5) << ch;
      EXPECT_NEAR(g2[ch], b2[ch], 2e-4 * std::fabs(b2[ch]) + 1e-5) << ch;
    }
  }
  EXPECT_LT(encodingError(L3, e2).relativeRms, 1e-6);
  // A light with more bands: l2 loses something (the comparison can fail).
  const RgbSh L6 = randomLight(6, rng, 0.4);
  EXPECT_GT(encodingError(L6, encodeIrradiance(L6, IrradianceEncoding::L2)).relativeRms, 1e-4);
}

// ZH3's zonal coefficient is the projection of band 2 on Y₂₀ about the axis, computed here by
// quadrature of the band-2 function against Y₂₀(a·ω); and a light whose band 2 is zonal about
// its band-1 direction is kept exactly.
TEST(IrradianceEncoding, Zh3KeepsBandTwoAlongItsAxis) {
  std::mt19937 rng(11);
  const RgbSh L = randomLight(3, rng, 0.5);
  const EncodedIrradiance z = encodeIrradiance(L, IrradianceEncoding::ZH3);
  EXPECT_NEAR(length(z.axis), 1.0, 1e-12);
  const SphereQuadrature q = gaussLegendreSphere(12);
  Rgbd proj(0.0);
  std::vector<double> y(9);
  for (std::size_t p = 0; p < q.dirs.size(); ++p) {
    eval(3, q.dirs[p], y.data());
    Rgbd band2(0.0);
    for (int i = 4; i < 9; ++i) band2 += Rgbd(L.c[i]) * y[i];
    const double t = dot(z.axis, q.dirs[p]);
    proj += band2 * (q.weights[p] * std::sqrt(5 / (16 * kPi)) * (3 * t * t - 1));
  }
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(z.zonal[ch], (kPi / 4) * proj[ch], 1e-6) << ch;

  // Band 2 exactly zonal about the band-1 direction: a delta light (its band 2 is Y₂ₘ(d), zonal
  // about d) has nothing ZH3 cannot hold.
  const RgbSh delta = deltaLight(3, normalize(Vec3d(-0.2, 0.9, 0.4)));
  const EncodedIrradiance zd = encodeIrradiance(delta, IrradianceEncoding::ZH3);
  EXPECT_LT(encodingError(delta, zd).relativeRms, 1e-6);
  EXPECT_GT(encodingError(delta, encodeIrradiance(delta, IrradianceEncoding::L1)).relativeRms,
            0.05);
}

// Least squares: adding the zonal term never makes the error worse than l1's, and the best axis
// never worse than the luminance's band-1 axis; the best axis beats each of 200 random axes.
TEST(IrradianceEncoding, Zh3IsNeverWorseThanL1AndTheOptimalAxisIsBest) {
  std::mt19937 rng(3);
  int better = 0;
  for (int k = 0; k < 20; ++k) {
    const RgbSh L = randomLight(5, rng, 0.6);
    const double l1 = encodingError(L, encodeIrradiance(L, IrradianceEncoding::L1)).relativeRms;
    const double zh3 = encodingError(L, encodeIrradiance(L, IrradianceEncoding::ZH3)).relativeRms;
    const EncodedIrradiance o = encodeIrradiance(L, IrradianceEncoding::ZH3Optimal);
    const double opt = encodingError(L, o).relativeRms;
    EXPECT_LE(zh3, l1 + 1e-12) << k;
    EXPECT_LE(opt, zh3 + 1e-9) << k;
    better += opt < zh3 - 1e-4;
    if (k < 3) {
      // Random axes, uniform over the sphere, each with its own least-squares coefficient.
      std::mt19937 dirs(k);
      std::uniform_real_distribution<double> u(0, 1);
      for (int i = 0; i < 200; ++i) {
        const double z = 2 * u(dirs) - 1, phi = 2 * kPi * u(dirs), r = std::sqrt(1 - z * z);
        EncodedIrradiance trial = o;
        trial.axis = Vec3d(r * std::cos(phi), r * std::sin(phi), z);
        double y[9];
        eval(3, trial.axis, y);
        Rgbd zc(0.0);
        for (int m = 4; m < 9; ++m) zc += Rgbd(L.c[m]) * y[m];
        trial.zonal = zc * (std::sqrt(4 * kPi / 5) * kPi / 4);
        ASSERT_GE(encodingError(L, trial).relativeRms, opt - 1e-7) << k << " axis " << i;
      }
    }
  }
  EXPECT_GT(better, 10);  // the luminance axis is not the best one for random lights
}

// zh3-shared: one zonal number s shared by the channels in proportion to their L₀₀, about the
// axis where that is the least-squares best. Checked against quadrature: the projection of each
// channel's band 2 on Y₂₀(a·ω) summed over a Gauss–Legendre grid (not the addition theorem the
// encoder uses), the least-squares s from it, and 300 random axes each with its own best s.
TEST(IrradianceEncoding, Zh3SharedIsTheBestZonalOfTheLightsOwnColour) {
  const double lambda2 = kPi / 4;
  const SphereQuadrature q = gaussLegendreSphere(12);
  // ∫ band2_c(ω) Y₂₀(a·ω) dω per channel (exact for the degree-4 integrand on this grid).
  const auto project = [&](const RgbSh& L, const Vec3d& a) {
    Rgbd proj(0.0);
    std::vector<double> y(9);
    for (std::size_t p = 0; p < q.dirs.size(); ++p) {
      eval(3, q.dirs[p], y.data());
      Rgbd band2(0.0);
      for (int i = 4; i < 9; ++i) band2 += Rgbd(L.c[i]) * y[i];
      const double t = dot(a, q.dirs[p]);
      proj += band2 * (q.weights[p] * std::sqrt(5 / (16 * kPi)) * (3 * t * t - 1));
    }
    return proj;
  };
  std::mt19937 rng(17);
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    const RgbSh L = randomLight(3, rng, 0.6);
    const Rgbd l0(L.c[0]);
    const EncodedIrradiance e = encodeIrradiance(L, IrradianceEncoding::ZH3Shared);
    EXPECT_NEAR(length(e.axis), 1.0, 1e-12);
    // (a) The zonal coefficients are in the proportion of the channels' L₀₀.
    for (int ch = 1; ch < 3; ++ch)
      EXPECT_NEAR(e.zonal[ch] / l0[ch], e.zonal[0] / l0[0], 1e-12 * std::abs(e.zonal[0] / l0[0]));
    // (b) s is the least-squares best for that colour about the axis: Σ_c L₀₀,c P_c / Σ_c L₀₀,c².
    const double s = dot(project(L, e.axis), l0) / dot(l0, l0);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(e.zonal[ch], lambda2 * s * l0[ch], 1e-6) << ch;
    // ... and the axis is: no random axis, with its own best s, comes closer.
    const double got = encodingError(L, e).relativeRms;
    std::mt19937 dirs(100 + k);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 300; ++i) {
      const double z = 2 * u(dirs) - 1, phi = 2 * kPi * u(dirs), r = std::sqrt(1 - z * z);
      EncodedIrradiance trial = e;
      trial.axis = Vec3d(r * std::cos(phi), r * std::sin(phi), z);
      trial.zonal = l0 * (lambda2 * dot(project(L, trial.axis), l0) / dot(l0, l0));
      ASSERT_GE(encodingError(L, trial).relativeRms, got - 1e-7) << "axis " << i;
    }
    // Least squares never loses: no worse than l1 with the same 12 numbers.
    EXPECT_LE(got, encodingError(L, encodeIrradiance(L, IrradianceEncoding::L1)).relativeRms);
  }
}

// A light whose band 2 is exactly a zonal harmonic of one colour (its own mean's, about an axis
// band 1 does not point along) is kept exactly by zh3-shared, not by the paper's zh3.
TEST(IrradianceEncoding, Zh3SharedIsExactForAZonalBandTwoOfTheLightsColour) {
  std::mt19937 rng(23);
  RgbSh L = randomLight(3, rng, 0.3);  // bands 0 and 1 random, band 2 replaced below
  const Vec3d d = normalize(Vec3d(0.7, -0.1, 0.5));
  double y[9];
  eval(3, d, y);
  for (int i = 4; i < 9; ++i)
    for (int ch = 0; ch < 3; ++ch) L.c[i][ch] = float(0.9 * L.c[0][ch] * y[i]);
  const EncodedIrradiance e = encodeIrradiance(L, IrradianceEncoding::ZH3Shared);
  EXPECT_NEAR(std::abs(dot(e.axis, d)), 1.0, 1e-9);
  EXPECT_LT(encodingError(L, e).relativeRms, 1e-6);
  // The comparison can fail: the luminance's band-1 axis is elsewhere.
  EXPECT_GT(encodingError(L, encodeIrradiance(L, IrradianceEncoding::ZH3)).relativeRms, 1e-3);
}

// The paper's hallucination on a delta light: r = |L₁·a|/L₀ = √3, zonal = Λ₂ L₀ (0.08 r + 0.6 r²).
TEST(IrradianceEncoding, HallucinatedZh3FollowsThePapersFit) {
  const RgbSh delta = deltaLight(3, Vec3d(0, 1, 0));
  const EncodedIrradiance h = encodeIrradiance(delta, IrradianceEncoding::ZH3Hallucinated);
  const double r = std::sqrt(3.0), l0 = 0.28209479177387814;
  EXPECT_NEAR(h.zonal.x, (kPi / 4) * l0 * (0.08 * r + 0.6 * r * r), 1e-6);
  EXPECT_NEAR(dot(h.axis, Vec3d(0, 1, 0)), 1.0, 1e-6);
  // It stores no more than l1, and under a directional light it halves l1's error or better.
  const double l1 =
      encodingError(delta, encodeIrradiance(delta, IrradianceEncoding::L1)).relativeRms;
  EXPECT_LT(encodingError(delta, h).relativeRms, 0.5 * l1);
}

// The non-negative l1 forms: no negative irradiance for any light with a positive mean, where
// plain l1 has some; windowing changes nothing that was already non-negative; Hazel's form
// keeps the mean.
TEST(IrradianceEncoding, NonNegativeL1FormsNeverGoNegative) {
  std::mt19937 rng(5);
  int l1Negative = 0;
  for (int k = 0; k < 20; ++k) {
    const RgbSh L = randomLight(4, rng, 1.5);
    l1Negative += encodingError(L, encodeIrradiance(L, IrradianceEncoding::L1)).negativeShare > 0;
    for (IrradianceEncoding e : {IrradianceEncoding::L1Windowed, IrradianceEncoding::L1Geomerics})
      EXPECT_EQ(encodingError(L, encodeIrradiance(L, e)).negativeShare, 0.0) << toString(e) << k;
  }
  EXPECT_GT(l1Negative, 0);  // the lights do test something
  // A gentle light: windowed l1 is l1.
  std::mt19937 calm(9);
  const RgbSh gentle = randomLight(2, calm, 0.05);
  const EncodedIrradiance a = encodeIrradiance(gentle, IrradianceEncoding::L1);
  const EncodedIrradiance b = encodeIrradiance(gentle, IrradianceEncoding::L1Windowed);
  for (int i = 0; i < 4; ++i)
    for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(a.sh[i][ch], b.sh[i][ch]);
  // Hazel's form keeps the mean irradiance: ∫ E dn = 4π E₀.
  const RgbSh L = randomLight(3, rng, 0.8);
  const EncodedIrradiance g = encodeIrradiance(L, IrradianceEncoding::L1Geomerics);
  const SphereQuadrature q = gaussLegendreSphere(96);
  Rgbd sum(0.0);
  for (std::size_t p = 0; p < q.dirs.size(); ++p) sum += evaluate(g, q.dirs[p]) * q.weights[p];
  for (int ch = 0; ch < 3; ++ch)
    EXPECT_NEAR(sum[ch] / (4 * kPi), g.sh[0][ch] * 0.28209479177387814,
                1e-4 * g.sh[0][ch])
        << ch;
}

// Deringing l2: a light whose l2 irradiance rings below zero comes out non-negative, at some
// cost in accuracy.
TEST(IrradianceEncoding, DeringedL2IsNonNegative) {
  std::mt19937 rng(21);
  int tested = 0;
  for (int k = 0; k < 40 && tested < 5; ++k) {
    const RgbSh L = randomLight(3, rng, 1.2);
    const EncodingError plain = encodingError(L, encodeIrradiance(L, IrradianceEncoding::L2));
    if (plain.negativeShare == 0) continue;
    ++tested;
    const EncodingError d = encodingError(L, encodeIrradiance(L, IrradianceEncoding::L2Deringed));
    EXPECT_EQ(d.negativeShare, 0.0) << k;
    EXPECT_GE(d.relativeMinimum, -1e-9) << k;
    EXPECT_GT(d.relativeRms, plain.relativeRms) << k;
  }
  EXPECT_EQ(tested, 5);
}
