// The diffuse kernels of compressed relighting (src/relight/compressed_diffuse.cpp): the SIMD
// kernel picked at run time (CompressedKernel::Auto) and the portable one each equal relighting
// the reconstructed transfer to float rounding, and agree with each other, for the shapes their
// code treats differently: vertex counts that are not a multiple of the 4-vertex groups,
// ranges that start at unaligned output addresses, odd and even N (the pairwise weight loads),
// scalar and RGB transfer, per-vertex and uniform albedo, and an output large enough for the
// non-temporal stores; and the glossy (matrix) kernels likewise. The compressed transfers are built
// directly (random ids, weights, means and bases): the identity under test is linearity, which
// needs no orthonormal basis.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "common/random_data.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/sampling.hpp"
#include "prt/relight/compressed.hpp"
#include "prt/relight/glossy.hpp"
#include "prt/relight/relight.hpp"

namespace prt {
namespace {

using testdata::randomLight;

CompressedTransfer randomCompressed(int bands, int channels, std::size_t rows, int K, int N,
                                    std::uint64_t seed,
                                    TransferLayout layout = TransferLayout::Vector) {
  CompressedTransfer c;
  c.layout = layout;
  c.bands = bands;
  c.channels = channels;
  c.vertexCount = rows;
  c.clusters = K;
  c.basisCount = N;
  Pcg32 rng(seed);
  c.cluster.resize(rows);
  for (auto& k : c.cluster) k = std::min<std::uint32_t>(K - 1, rng.uniform() * K);
  c.weights.resize(rows * N);
  for (float& w : c.weights) w = 2.0f * rng.uniform() - 1.0f;
  c.means.resize(K * c.stride());
  for (float& m : c.means) m = rng.uniform();
  c.basis.resize(K * N * c.stride());
  for (float& b : c.basis) b = rng.uniform() - 0.5f;
  return c;
}

// max |a − b| over all values, relative to max |b|.
double relativeDifference(std::span<const Rgb> a, std::span<const Rgb> b) {
  double scale = 0, worst = 0;
  for (std::size_t v = 0; v < a.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      scale = std::max(scale, std::abs(double(b[v][c])));
      worst = std::max(worst, std::abs(double(a[v][c]) - b[v][c]));
    }
  return scale > 0 ? worst / scale : (worst > 0 ? 1.0 : 0.0);
}

// Relights `c` with both kernels into outputs shifted by `offset` values (so the kernel's
// ranges start at different output alignments) and checks both against the dense
// relighting of the reconstruction and against each other.
void checkKernels(const CompressedTransfer& c, bool perVertexAlbedo, std::size_t offset,
                  const char* what) {
  const std::size_t n = c.vertexCount;
  const relight::PreparedLight light = relight::prepareLight(randomLight(c.bands, 7), c.bands);
  const relight::ClusterLight projected = relight::projectClusters(c, light);
  std::vector<Rgb> albedo(perVertexAlbedo ? n : 1);
  Pcg32 rng(11);
  for (Rgb& a : albedo) a = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
  std::vector<Rgb> expected(n), autoBuf(n + offset), portableBuf(n + offset);
  relight::relight(c.reconstruct(), light, albedo, expected);
  const std::span<Rgb> autoOut = std::span<Rgb>(autoBuf).subspan(offset, n);
  const std::span<Rgb> portableOut = std::span<Rgb>(portableBuf).subspan(offset, n);
  relight::relightCompressed(c, projected, albedo, autoOut, relight::CompressedKernel::Auto);
  relight::relightCompressed(c, projected, albedo, portableOut,
                             relight::CompressedKernel::Portable);
  double scale = 0;
  for (const Rgb& e : expected) scale = std::max({scale, double(e.x), double(e.y), double(e.z)});
  EXPECT_GT(scale, 0.1) << what;  // a relighting of zeros would agree with anything
  EXPECT_LT(relativeDifference(autoOut, expected), 2e-5) << what << " (auto kernel)";
  EXPECT_LT(relativeDifference(portableOut, expected), 2e-5) << what << " (portable kernel)";
  EXPECT_LT(relativeDifference(autoOut, portableOut), 2e-5) << what << " (auto vs portable)";
}

TEST(RelightCompressedKernels, AgreeWithTheReconstructionForOddShapes) {
  // Counts around the 4-vertex groups and the 4096-vertex task grain; N odd and even.
  for (std::size_t n : {1, 3, 5, 8, 4099})
    for (int N : {0, 1, 3, 8})
      for (int channels : {1, 3}) {
        const CompressedTransfer c = randomCompressed(3, channels, n, 5, N, 100 + n + N);
        for (std::size_t offset : {0, 1, 2, 3})
          checkKernels(c, /*perVertexAlbedo=*/offset % 2 == 0, offset, "small");
      }
}

TEST(RelightCompressedKernels, AgreeOnAnOutputLargeEnoughToStream) {
  // 12 bytes × 400k vertices = 4.8 MB, past the non-temporal-store threshold (4 MiB).
  const CompressedTransfer c = randomCompressed(2, 1, 400'001, 16, 8, 3);
  checkKernels(c, true, 1, "large, per-vertex albedo");
  checkKernels(c, false, 0, "large, uniform albedo");
}

TEST(RelightCompressedKernels, OutputFollowsTheVertexOrder) {
  // Relighting a permuted compressed transfer gives the same values permuted: each output is its
  // own vertex's, whatever the clusters of its neighbours.
  const CompressedTransfer c = randomCompressed(3, 1, 1001, 7, 4, 9);
  std::vector<std::size_t> perm(c.vertexCount);
  std::iota(perm.begin(), perm.end(), 0);
  std::reverse(perm.begin(), perm.end());
  std::rotate(perm.begin(), perm.begin() + 333, perm.end());
  CompressedTransfer p = c;
  const std::size_t N = 4;
  for (std::size_t v = 0; v < c.vertexCount; ++v) {
    p.cluster[v] = c.cluster[perm[v]];
    std::copy_n(c.weights.data() + perm[v] * N, N, p.weights.data() + v * N);
  }
  const relight::PreparedLight light = relight::prepareLight(randomLight(3, 2), 3);
  std::vector<Rgb> a(c.vertexCount), b(c.vertexCount);
  relight::relightCompressed(c, light, {}, a);
  relight::relightCompressed(p, light, {}, b);
  for (std::size_t v = 0; v < c.vertexCount; ++v)
    for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(b[v][ch], a[perm[v]][ch]) << v;
}

TEST(RelightCompressedKernels, GlossyKernelsAgreeWithTheReconstruction) {
  // Matrices at 5 bands (the AVX2 kernel's 25 → 32-float planes) and 3 (9 → 16), odd and even
  // N, a glossy and a diffuse-only material, per-vertex and uniform albedo.
  const std::size_t n = 517;
  std::vector<Vec3f> pos(n), nrm(n);
  Pcg32 rng(4);
  for (std::size_t v = 0; v < n; ++v) {
    pos[v] = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
    nrm[v] = uniformSphere(rng.uniform(), rng.uniform());
  }
  std::vector<Rgb> albedo(n);
  for (Rgb& a : albedo) a = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
  const relight::GlossyView view{pos, nrm, Vec3f(0.5f, 3.0f, 4.0f)};
  for (int bands : {5, 3})
    for (int N : {3, 8})
      for (const char* spec : {"phong?exponent=8&ks=0.4", "lambert"}) {
        const CompressedTransfer c =
            randomCompressed(bands, 1, n, 6, N, 40 + N, TransferLayout::Matrix);
        const relight::PreparedLight light = relight::prepareLight(randomLight(bands, 3), bands);
        const relight::PreparedMaterial mat = relight::prepareMaterial(parseMaterial(spec), bands);
        for (bool perVertex : {true, false}) {
          const std::span<const Rgb> alb =
              perVertex ? std::span<const Rgb>(albedo) : std::span<const Rgb>(albedo.data(), 1);
          std::vector<Rgb> expected(n), autoOut(n), portableOut(n);
          relight::relightGlossy(c.reconstruct(), light, mat, view, alb, expected);
          relight::relightCompressedGlossy(c, light, mat, view, alb, autoOut,
                                           relight::CompressedKernel::Auto);
          relight::relightCompressedGlossy(c, light, mat, view, alb, portableOut,
                                           relight::CompressedKernel::Portable);
          double scale = 0;
          for (const Rgb& e : expected)
            scale = std::max({scale, std::abs(double(e.x)), std::abs(double(e.y))});
          EXPECT_GT(scale, 0.1) << spec;
          EXPECT_LT(relativeDifference(autoOut, expected), 2e-5) << bands << " " << N << spec;
          EXPECT_LT(relativeDifference(portableOut, expected), 2e-5) << bands << " " << N << spec;
          EXPECT_LT(relativeDifference(autoOut, portableOut), 2e-5) << bands << " " << N << spec;
        }
      }
}

TEST(RelightCompressedKernels, ReportsWhetherASimdKernelIsUsed) {
#if defined(__x86_64__)
  EXPECT_EQ(relight::compressedSimdAvailable(),
            __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"));
#else
  EXPECT_FALSE(relight::compressedSimdAvailable());
#endif
}

}  // namespace
}  // namespace prt
