// Relighting from CPCA-compressed transfer through the one entry point (relight.hpp) equals
// relighting the reconstructed dense transfer to float rounding: vectors and matrices, scalar and
// RGB, light of as many and of fewer bands, per-vertex and uniform albedo, and the transfer cut
// to fewer bands — one answer whatever the representation. The compression is deliberately
// coarse (small N) so the reconstruction is far from the source and the identity is the
// linearity, not the fit.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/random_data.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/cpu.hpp"
#include "prt/core/error.hpp"
#include "prt/core/sampling.hpp"
#include "prt/relight/relight.hpp"

namespace prt {
namespace {

using testdata::randomField;
using testdata::randomLight;

void expectClose(const std::vector<Rgb>& a, const std::vector<Rgb>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  double scale = 0, worst = 0;
  for (std::size_t v = 0; v < a.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      scale = std::max(scale, std::abs(double(b[v][c])));
      worst = std::max(worst, std::abs(double(a[v][c]) - b[v][c]));
    }
  EXPECT_GT(scale, 0.1) << what;
  EXPECT_LT(worst, 2e-5 * scale) << what;
}

CpcaOptions opts(int clusters, int basis, std::uint64_t seed, int iterations) {
  CpcaOptions o;
  o.clusters = clusters, o.basisCount = basis, o.seed = seed, o.maxIterations = iterations;
  return o;
}

/// Positions and unit normals of n random points.
struct Points {
  std::vector<Vec3f> positions, normals;
  explicit Points(std::size_t n) : positions(n), normals(n) {
    Pcg32 rng(9);
    for (std::size_t v = 0; v < n; ++v) {
      positions[v] = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
      normals[v] = uniformSphere(rng.uniform(), rng.uniform());
    }
  }
};

TEST(RelightCompressed, VectorEqualsRelightingTheReconstruction) {
  for (Simd simd : {Simd::Auto, Simd::Portable})
    for (int channels : {1, 3})
      for (int lightBands : {4, 2}) {
        const ScopedSimd policy(simd);
        const Transfer f = randomField(TransferLayout::Vector, 4, channels, 700, 10 + channels);
        const Transfer c = compressCpca(f, opts(6, 3, 1, 10));
        const Transfer r = c.toDense();
        std::vector<Rgb> albedo(700);
        Pcg32 rng(3);
        for (Rgb& a : albedo) a = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
        const sh::RgbSh light = randomLight(lightBands, 5);
        for (bool perVertex : {true, false}) {
          const std::span<const Rgb> alb =
              perVertex ? std::span<const Rgb>(albedo) : std::span<const Rgb>(albedo.data(), 1);
          const auto expected = relight::relight(r, light, Material{}, {{}, {}, alb}, Vec3f(0.0f));
          const auto got = relight::relight(c, light, Material{}, {{}, {}, alb}, Vec3f(0.0f));
          expectClose(got, expected, "vector");
        }
      }
}

TEST(RelightCompressed, MatrixEqualsGlossyRelightingOfTheReconstruction) {
  const std::size_t n = 300;
  const Points p(n);
  const Vec3f eye(0.5f, 3.0f, 4.0f);
  const Material mat = parseMaterial("phong?exponent=8&ks=0.4&kd=0.7,0.5,0.3");
  for (Simd simd : {Simd::Auto, Simd::Portable})
    for (int channels : {1, 3})
      for (int lightBands : {3, 2}) {
        const ScopedSimd policy(simd);
        const Transfer f = randomField(TransferLayout::Matrix, 3, channels, n, 20 + channels);
        const Transfer c = compressCpca(f, opts(4, 5, 2, 10));
        const sh::RgbSh light = randomLight(lightBands, 6);
        const relight::Surface s{p.positions, p.normals, {}};
        expectClose(relight::relight(c, light, mat, s, eye),
                    relight::relight(c.toDense(), light, mat, s, eye), "matrix");
      }
}

// Cutting to fewer bands gives one answer for both representations: relighting the compressed
// transfer cut to b bands equals relighting its reconstruction cut to b bands.
TEST(RelightCompressed, FewerBandsGiveOneAnswerForBothRepresentations) {
  const std::size_t n = 400;
  const Points p(n);
  const Vec3f eye(0.5f, 3.0f, 4.0f);
  const Material mat = parseMaterial("ggx?roughness=0.5&ks=0.3");
  for (TransferLayout layout : {TransferLayout::Vector, TransferLayout::Matrix}) {
    const Transfer f = randomField(layout, 4, 1, n, 31);
    const Transfer c = compressCpca(f, opts(5, 4, 3, 10));
    const sh::RgbSh light = randomLight(4, 7);
    const relight::Surface s{p.positions, p.normals, {}};
    for (int b : {1, 2, 3}) {
      const std::string what = std::string(toString(layout)) + " at " + std::to_string(b);
      expectClose(relight::relight(c.cut(b), light, mat, s, eye),
                  relight::relight(c.toDense().cut(b), light, mat, s, eye), what);
    }
  }
}

TEST(RelightCompressed, RefusesMismatchedSizes) {
  const Transfer fv = randomField(TransferLayout::Vector, 2, 1, 50, 1);
  const Transfer cv = compressCpca(fv, opts(2, 1, 1, 5));
  const sh::RgbSh light = randomLight(2, 1);
  std::vector<Rgb> out(50), wrong(49);
  EXPECT_THROW(relight::relight(cv, light, Material{}, {}, Vec3f(0.0f), wrong), Error);
  EXPECT_NO_THROW(relight::relight(cv, light, Material{}, {}, Vec3f(0.0f), out));
  const Transfer fm = randomField(TransferLayout::Matrix, 2, 1, 50, 1);
  const Transfer cm = compressCpca(fm, opts(2, 1, 1, 5));
  EXPECT_THROW(relight::relight(cm, light, Material{}, {}, Vec3f(0.0f), out), Error);  // no normals
}

}  // namespace
}  // namespace prt
