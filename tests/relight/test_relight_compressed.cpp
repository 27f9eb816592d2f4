// Relighting from CPCA-compressed transfer (prt/relight/compressed.hpp) equals relighting the
// reconstructed transfer with the uncompressed kernels (relight.hpp, glossy.hpp) to float
// rounding: vectors and matrices, scalar and RGB, light of as many and of fewer bands, per-vertex
// and uniform albedo. The compression is deliberately coarse (small N) so the reconstruction is
// far from the source and the identity is the linearity, not the fit.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/random_data.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/error.hpp"
#include "prt/core/sampling.hpp"
#include "prt/relight/compressed.hpp"
#include "prt/relight/glossy.hpp"
#include "prt/relight/relight.hpp"

namespace prt {
namespace {

using testdata::randomField;
using testdata::randomLight;

void expectClose(const std::vector<Rgb>& a, const std::vector<Rgb>& b, const char* what) {
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

TEST(RelightCompressed, VectorEqualsRelightingTheReconstruction) {
  for (int channels : {1, 3})
    for (int lightBands : {4, 2}) {
      const TransferField f = randomField(TransferLayout::Vector, 4, channels, 700, 10 + channels);
      const CompressedTransfer c = compressCpca(f, {6, 3, 1, 10});
      const TransferField r = c.reconstruct();
      std::vector<Rgb> albedo(700);
      Pcg32 rng(3);
      for (Rgb& a : albedo) a = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
      const relight::PreparedLight light = relight::prepareLight(randomLight(lightBands, 5), 4);
      for (bool perVertex : {true, false}) {
        std::span<const Rgb> alb =
            perVertex ? std::span<const Rgb>(albedo) : std::span<const Rgb>(albedo.data(), 1);
        std::vector<Rgb> expected(700), got(700);
        relight::relight(r, light, alb, expected);
        relight::relightCompressed(c, light, alb, got);
        expectClose(got, expected, "vector");
      }
    }
}

TEST(RelightCompressed, MatrixEqualsGlossyRelightingOfTheReconstruction) {
  const std::size_t n = 300;
  std::vector<Vec3f> pos(n), nrm(n);
  Pcg32 rng(9);
  for (std::size_t v = 0; v < n; ++v) {
    pos[v] = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
    nrm[v] = uniformSphere(rng.uniform(), rng.uniform());
  }
  const relight::GlossyView view{pos, nrm, Vec3f(0.5f, 3.0f, 4.0f)};
  for (int channels : {1, 3})
    for (int lightBands : {3, 2}) {
      const TransferField f = randomField(TransferLayout::Matrix, 3, channels, n, 20 + channels);
      const CompressedTransfer c = compressCpca(f, {4, 5, 2, 10});
      const TransferField r = c.reconstruct();
      const relight::PreparedLight light = relight::prepareLight(randomLight(lightBands, 6), 3);
      const relight::PreparedMaterial mat =
          relight::prepareMaterial(parseMaterial("phong?exponent=8&ks=0.4"), 3);
      const Rgb albedo(0.7f, 0.5f, 0.3f);
      std::vector<Rgb> expected(n), got(n);
      relight::relightGlossy(r, light, mat, view, {&albedo, 1}, expected);
      relight::relightCompressedGlossy(c, light, mat, view, {&albedo, 1}, got);
      expectClose(got, expected, "matrix");
    }
}

TEST(RelightCompressed, RefusesTheWrongKernelAndSizes) {
  const TransferField f = randomField(TransferLayout::Matrix, 2, 1, 50, 1);
  const CompressedTransfer c = compressCpca(f, {2, 1, 1, 5});
  const relight::PreparedLight light = relight::prepareLight(randomLight(2, 1), 2);
  std::vector<Rgb> out(50), wrong(49);
  EXPECT_THROW(relight::relightCompressed(c, light, {}, out), Error);
  const TransferField fv = randomField(TransferLayout::Vector, 2, 1, 50, 1);
  const CompressedTransfer cv = compressCpca(fv, {2, 1, 1, 5});
  EXPECT_THROW(relight::relightCompressed(cv, light, {}, wrong), Error);
  EXPECT_NO_THROW(relight::relightCompressed(cv, light, {}, out));
}

}  // namespace
}  // namespace prt
