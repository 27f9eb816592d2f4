// The kernels of compressed relighting (src/relight/cpca_*_kernels.cpp): the SIMD kernel picked
// at run time (Simd::Auto) and the portable one (Simd::Portable, forced) each equal relighting
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
#include "prt/core/cpu.hpp"
#include "prt/core/sampling.hpp"
#include "prt/relight/relight.hpp"

namespace prt {
namespace {

using testdata::randomLight;

Transfer randomCompressed(int bands, int channels, std::size_t rows, int K, int N,
                          std::uint64_t seed, TransferLayout layout = TransferLayout::Vector) {
  const TransferShape shape = testdata::shapeOf(layout, bands, channels, rows);
  const std::size_t D = shape.stride();
  CpcaRows c;
  c.clusters = K;
  c.basisCount = N;
  Pcg32 rng(seed);
  c.cluster.resize(rows);
  for (auto& k : c.cluster) k = std::min<std::uint32_t>(K - 1, rng.uniform() * K);
  const auto fill = [&](std::size_t n, float scale, float shift) {
    std::vector<float> x(n);
    for (float& v : x) v = scale * rng.uniform() + shift;
    return FloatArray(std::move(x));
  };
  c.weights = fill(rows * N, 2.0f, -1.0f);
  c.means = fill(K * D, 1.0f, 0.0f);
  c.basis = fill(K * N * D, 1.0f, -0.5f);
  return Transfer::cpca(shape, std::move(c));
}

/// Relights `t` (vectors) into `out` with one SIMD policy.
void relightWith(Simd simd, const Transfer& t, const relight::PreparedLight& light,
                 std::span<const Rgb> albedo, std::span<Rgb> out) {
  const ScopedSimd policy(simd);
  relight::relightPrepared(t, light, PreparedMaterial{}, {{}, {}, albedo}, Vec3f(0.0f), out);
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
void checkKernels(const Transfer& c, bool perVertexAlbedo, std::size_t offset, const char* what) {
  const std::size_t n = c.rowCount();
  const relight::PreparedLight light = relight::prepareLight(randomLight(c.bands(), 7), c.bands());
  std::vector<Rgb> albedo(perVertexAlbedo ? n : 1);
  Pcg32 rng(11);
  for (Rgb& a : albedo) a = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
  std::vector<Rgb> expected(n), autoBuf(n + offset), portableBuf(n + offset);
  relightWith(Simd::Portable, c.toDense(), light, albedo, expected);
  const std::span<Rgb> autoOut = std::span<Rgb>(autoBuf).subspan(offset, n);
  const std::span<Rgb> portableOut = std::span<Rgb>(portableBuf).subspan(offset, n);
  relightWith(Simd::Auto, c, light, albedo, autoOut);
  relightWith(Simd::Portable, c, light, albedo, portableOut);
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
        const Transfer c = randomCompressed(3, channels, n, 5, N, 100 + n + N);
        for (std::size_t offset : {0, 1, 2, 3})
          checkKernels(c, /*perVertexAlbedo=*/offset % 2 == 0, offset, "small");
      }
}

TEST(RelightCompressedKernels, AgreeOnAnOutputLargeEnoughToStream) {
  // 12 bytes × 400k vertices = 4.8 MB, past the non-temporal-store threshold (4 MiB).
  const Transfer c = randomCompressed(2, 1, 400'001, 16, 8, 3);
  checkKernels(c, true, 1, "large, per-vertex albedo");
  checkKernels(c, false, 0, "large, uniform albedo");
}

TEST(RelightCompressedKernels, OutputFollowsTheVertexOrder) {
  // Relighting a permuted compressed transfer gives the same values permuted: each output is its
  // own vertex's, whatever the clusters of its neighbours.
  const Transfer c = randomCompressed(3, 1, 1001, 7, 4, 9);
  const std::size_t n = c.rowCount();
  std::vector<std::size_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::reverse(perm.begin(), perm.end());
  std::rotate(perm.begin(), perm.begin() + 333, perm.end());
  CpcaRows rows = c.cpca();
  const std::size_t N = 4;
  std::vector<float> weights(n * N);
  for (std::size_t v = 0; v < n; ++v) {
    rows.cluster[v] = c.cpca().cluster[perm[v]];
    std::copy_n(c.cpca().weights.data() + perm[v] * N, N, weights.data() + v * N);
  }
  rows.weights = FloatArray(std::move(weights));
  const Transfer p = Transfer::cpca(c.shape(), std::move(rows));
  const relight::PreparedLight light = relight::prepareLight(randomLight(3, 2), 3);
  std::vector<Rgb> a(n), b(n);
  relightWith(Simd::Auto, c, light, {}, a);
  relightWith(Simd::Auto, p, light, {}, b);
  for (std::size_t v = 0; v < n; ++v)
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
  const Vec3f eye(0.5f, 3.0f, 4.0f);
  for (int bands : {5, 3})
    for (int N : {3, 8})
      for (const char* spec : {"phong?exponent=8&ks=0.4", "lambert"}) {
        const Transfer c = randomCompressed(bands, 1, n, 6, N, 40 + N, TransferLayout::Matrix);
        const relight::PreparedLight light = relight::prepareLight(randomLight(bands, 3), bands);
        const PreparedMaterial mat = prepareMaterial(parseMaterial(spec), bands);
        for (bool perVertex : {true, false}) {
          const std::span<const Rgb> alb =
              perVertex ? std::span<const Rgb>(albedo) : std::span<const Rgb>(albedo.data(), 1);
          const relight::Surface surface{pos, nrm, alb};
          std::vector<Rgb> expected(n), autoOut(n), portableOut(n);
          const auto run = [&](Simd simd, const Transfer& t, std::span<Rgb> out) {
            const ScopedSimd policy(simd);
            relight::relightPrepared(t, light, mat, surface, eye, out);
          };
          run(Simd::Portable, c.toDense(), expected);
          run(Simd::Auto, c, autoOut);
          run(Simd::Portable, c, portableOut);
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

TEST(RelightCompressedKernels, SimdPolicyFollowsTheCpuAndCanBeForcedOff) {
#if defined(__x86_64__)
  EXPECT_EQ(cpuHasAvx2Fma(), __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"));
#else
  EXPECT_FALSE(cpuHasAvx2Fma());
#endif
  {
    const ScopedSimd portable(Simd::Portable);
    EXPECT_FALSE(simdAvx2Fma());
  }
  EXPECT_EQ(simdAvx2Fma(), cpuHasAvx2Fma() && simdPolicy() == Simd::Auto);
}

}  // namespace
}  // namespace prt
