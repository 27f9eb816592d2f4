// The shader-ready packing of compressed transfer (prt/relight/cluster_table.hpp): the per-vertex
// texels hold exactly the cluster id and weights in the documented slots, and the shader's sum
// over the two packings (evalPackedVertex) equals relightCompressed (vectors) and the
// reconstructed matrices times the light (matrices), scalar and RGB, N = 0 .. 7 (so one and
// several texels per vertex), light of as many and of fewer bands than the transfer.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/random_data.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/error.hpp"
#include "prt/core/sampling.hpp"
#include "prt/relight/cluster_table.hpp"
#include "prt/relight/compressed.hpp"
#include "prt/relight/glossy_shader.hpp"
#include "prt/relight/relight.hpp"

namespace prt {
namespace {

using testdata::randomField;
using testdata::randomLight;

TEST(ClusterTable, VertexTexelsHoldIdAndWeightsInTheirSlots) {
  for (int N : {0, 3, 4, 7}) {
    const TransferField f = randomField(TransferLayout::Vector, 3, 1, 300, 7 + N);
    const CompressedTransfer c = compressCpca(f, {5, N, 1, 5});
    const relight::CompressedVertexTexels t = relight::packCompressedVertices(c);
    EXPECT_EQ(t.texelsPerVertex, (N + 4) / 4) << N;
    EXPECT_EQ(t.bytesPerVertex(), std::size_t(16 * ((N + 4) / 4)));
    ASSERT_EQ(t.rgba.size(), 300u * 4 * t.texelsPerVertex);
    for (std::size_t v = 0; v < 300; ++v) {
      const float* s = t.rgba.data() + v * 4 * t.texelsPerVertex;
      EXPECT_EQ(s[0], float(c.cluster[v]));
      for (int j = 0; j < N; ++j) EXPECT_EQ(s[1 + j], c.weights[v * N + j]);
      for (int p = N + 1; p < 4 * t.texelsPerVertex; ++p) EXPECT_EQ(s[p], 0.0f);
    }
  }
}

TEST(ClusterTable, VectorSumTimesAlbedoEqualsRelightCompressed) {
  for (int channels : {1, 3})
    for (int N : {0, 2, 6})
      for (int lightBands : {4, 2}) {
        SCOPED_TRACE(::testing::Message() << "C " << channels << " N " << N << " b " << lightBands);
        const std::size_t n = 500;
        const TransferField f = randomField(TransferLayout::Vector, 4, channels, n, 3 + N);
        const CompressedTransfer c = compressCpca(f, {7, N, 2, 5});
        std::vector<Rgb> albedo(n);
        Pcg32 rng(9);
        for (Rgb& a : albedo) a = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
        const relight::PreparedLight light = relight::prepareLight(randomLight(lightBands, 4), 4);
        std::vector<Rgb> want(n);
        relight::relightCompressed(c, light, albedo, want);

        const relight::CompressedVertexTexels vt = relight::packCompressedVertices(c);
        std::vector<float> table;
        relight::packClusterTable(relight::projectClusters(c, light), table);
        ASSERT_EQ(table.size(), std::size_t(4 * 7 * (N + 1)));
        double worst = 0, scale = 0;
        for (std::size_t v = 0; v < n; ++v) {
          Rgb e;
          relight::evalPackedVertex(vt, table, 1, v, &e);
          e = e * albedo[v];
          for (int k = 0; k < 3; ++k) {
            worst = std::max(worst, std::abs(double(e[k]) - want[v][k]));
            scale = std::max(scale, std::abs(double(want[v][k])));
          }
        }
        EXPECT_GT(scale, 0.1);
        EXPECT_LT(worst, 1e-5 * scale);
      }
}

TEST(ClusterTable, MatrixSumEqualsReconstructedMatrixTimesLight) {
  const int bands = 3, nB = bands * bands;
  for (int channels : {1, 3})
    for (int lightBands : {3, 2}) {
      SCOPED_TRACE(::testing::Message() << "C " << channels << " b " << lightBands);
      const std::size_t n = 200;
      const TransferField f =
          randomField(TransferLayout::Matrix, bands, channels, n, 30 + channels);
      const CompressedTransfer c = compressCpca(f, {4, 5, 2, 5});
      const TransferField r = c.reconstruct();
      const relight::PreparedLight light = relight::prepareLight(randomLight(lightBands, 8), bands);
      const relight::CompressedVertexTexels vt = relight::packCompressedVertices(c);
      std::vector<float> table;
      relight::packClusterTable(relight::projectClusters(c, light), table);
      ASSERT_EQ(table.size(), std::size_t(4 * 4 * 6 * nB));
      const int nb = lightBands * lightBands;
      double worst = 0, scale = 0;
      std::vector<Rgb> got(nB);
      for (std::size_t v = 0; v < n; ++v) {
        relight::evalPackedVertex(vt, table, nB, v, got.data());
        // (M̂_v L)_i,c = Σ_{l < b²} M̂_v[(i·B² + l)·C + c] L_l,c
        const float* m = r.vertex(v);
        for (int i = 0; i < nB; ++i)
          for (int k = 0; k < 3; ++k) {
            double want = 0;
            for (int l = 0; l < nb; ++l)
              want += double(m[(i * nB + l) * channels + (channels == 1 ? 0 : k)]) *
                      light.interleaved[3 * l + k];
            worst = std::max(worst, std::abs(got[i][k] - want));
            scale = std::max(scale, std::abs(want));
          }
      }
      EXPECT_GT(scale, 0.1);
      EXPECT_LT(worst, 2e-5 * scale);
    }
}

TEST(ClusterTable, RefusesIdsFloatsCannotHold) {
  CompressedTransfer c;
  c.clusters = (1 << 24) + 1;
  EXPECT_THROW(relight::packCompressedVertices(c), Error);
}

// The glossy kernels for the shaders (prt/relight/glossy_shader.hpp) carry the SH normalisation
// N_lm their unnormalised basis (P̃_l^|m| times A_m or B_m) leaves out; a kernel of ones gives
// N_lm itself. With the shader's P̃_1^1 = −1, P_2 = (3z² − 1)/2, P̃_2^1 = −3z, P̃_2^2 = 3 these
// must rebuild sh.hpp's constants: N_00 = 0.282095; N_1m = 0.488603 (Y_11 = −0.488603 x);
// N_20 = 0.630783 (= 2 · 0.315392); N_2±1 = 0.364174 (= 1.092548 / 3); N_2±2 = 0.182091
// (Y_22 = 0.546274 (x² − y²) = N · 3 (x² − y²)).
TEST(GlossyShader, KernelsCarryTheShNormalisation) {
  const std::vector<float> ones(9, 1.0f);
  const std::array<float, 64> k = relight::shaderKernel(ones);
  const double want[9] = {0.282095,     0.488603,     0.488603,     0.488603,    0.546274 / 3,
                          1.092548 / 3, 2 * 0.315392, 1.092548 / 3, 0.546274 / 3};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(k[i], want[i], 2e-6) << i;
  for (int i = 9; i < 64; ++i) EXPECT_EQ(k[i], 0.0f) << i;  // past the kernel's bands
}

}  // namespace
}  // namespace prt
