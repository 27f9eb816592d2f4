// The shader-ready form of a transfer (prt/relight/shader_transfer.hpp): the path each layout and
// representation takes; the per-vertex texels of every path hold exactly the documented slots;
// the shader's sum over the compressed packings (evalPackedRow) equals relighting (vectors) and
// the reconstructed matrices times the light (matrices), scalar and RGB, N = 0 .. 7 (so one and
// several texels per vertex), light of as many and of fewer bands than the transfer; per-texel
// rows relit per pixel (evalPerPixel, the fragment stage's sum) equal the texels relit on the CPU
// and fetched bilinearly, as prt render fetches them.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/random_data.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/error.hpp"
#include "prt/core/sampling.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/relight/cluster_projection.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/shader_transfer.hpp"

namespace prt {
namespace {

using relight::ShaderPath;
using testdata::randomField;
using testdata::randomLight;

CpcaOptions opts(int clusters, int basis, std::uint64_t seed, int iterations) {
  CpcaOptions o;
  o.clusters = clusters, o.basisCount = basis, o.seed = seed, o.maxIterations = iterations;
  return o;
}

TEST(ShaderTransfer, EachLayoutAndRepresentationHasItsPath) {
  const Transfer v = randomField(TransferLayout::Vector, 3, 1, 40, 1);
  const Transfer m = randomField(TransferLayout::Matrix, 3, 1, 40, 2);
  const Transfer cv = compressCpca(v, opts(2, 1, 1, 5)), cm = compressCpca(m, opts(2, 1, 1, 5));
  EXPECT_EQ(relight::shaderPath(v, false), ShaderPath::DenseVector);
  EXPECT_EQ(relight::shaderPath(v, true), ShaderPath::DenseVector);
  EXPECT_EQ(relight::shaderPath(m, false), ShaderPath::CpuRadiance);
  EXPECT_EQ(relight::shaderPath(m, true), ShaderPath::DenseMatrix);
  EXPECT_EQ(relight::shaderPath(cv, false), ShaderPath::CpcaVector);
  EXPECT_EQ(relight::shaderPath(cm, false), ShaderPath::CpuRadiance);
  EXPECT_EQ(relight::shaderPath(cm, true), ShaderPath::CpcaMatrix);
  // What the shaders cannot hold is refused with one line: RGB matrices and more than 8 bands
  // in the vertex shader.
  EXPECT_THROW(relight::shaderPath(randomField(TransferLayout::Matrix, 2, 3, 4, 3), true), Error);
  EXPECT_THROW(relight::shaderPath(randomField(TransferLayout::Matrix, 9, 1, 2, 3), true), Error);
  EXPECT_NO_THROW(relight::shaderPath(randomField(TransferLayout::Matrix, 9, 1, 2, 3), false));
}

TEST(ShaderTransfer, DenseRowsHoldTheirValuesInTheDocumentedTexels) {
  for (int channels : {1, 3}) {
    const Transfer v = randomField(TransferLayout::Vector, 3, channels, 20, 5 + channels);
    const relight::ShaderRows rows = relight::packShaderRows(v, ShaderPath::DenseVector);
    // Scalar: 9 coefficients in ⌈9/4⌉ = 3 texels, zero-padded; RGB: one (r, g, b, 0) texel each.
    ASSERT_EQ(rows.texelsPerRow, channels == 1 ? 3 : 9);
    for (std::size_t r = 0; r < 20; ++r) {
      const float* t = rows.rgba.data() + r * 4 * rows.texelsPerRow;
      for (int i = 0; i < 9; ++i)
        for (int c = 0; c < channels; ++c)
          ASSERT_EQ(channels == 1 ? t[i] : t[4 * i + c], v.row(r)[i * channels + c]);
      if (channels == 1)
        for (int i = 9; i < 12; ++i) EXPECT_EQ(t[i], 0.0f);
      else
        for (int i = 0; i < 9; ++i) EXPECT_EQ(t[4 * i + 3], 0.0f);
    }
  }
  const Transfer m = randomField(TransferLayout::Matrix, 3, 1, 10, 9);
  const relight::ShaderRows rows = relight::packShaderRows(m, ShaderPath::DenseMatrix);
  ASSERT_EQ(rows.texelsPerRow, 9 * 3);  // 9 matrix rows of ⌈9/4⌉ texels
  for (std::size_t r = 0; r < 10; ++r)
    for (int i = 0; i < 9; ++i)
      for (int j = 0; j < 12; ++j)
        ASSERT_EQ(rows.rgba[(r * 27 + i * 3) * 4 + j], j < 9 ? m.row(r)[i * 9 + j] : 0.0f);
  EXPECT_TRUE(relight::packShaderRows(m, ShaderPath::CpuRadiance).rgba.empty());
}

TEST(ClusterTable, VertexTexelsHoldIdAndWeightsInTheirSlots) {
  for (int N : {0, 3, 4, 7}) {
    const Transfer f = randomField(TransferLayout::Vector, 3, 1, 300, 7 + N);
    const Transfer c = compressCpca(f, opts(5, N, 1, 5));
    const relight::ShaderRows t = relight::packShaderRows(c, ShaderPath::CpcaVector);
    EXPECT_EQ(t.texelsPerRow, (N + 4) / 4) << N;
    EXPECT_EQ(t.bytesPerRow(), std::size_t(16 * ((N + 4) / 4)));
    ASSERT_EQ(t.rgba.size(), 300u * 4 * t.texelsPerRow);
    for (std::size_t v = 0; v < 300; ++v) {
      const float* s = t.rgba.data() + v * 4 * t.texelsPerRow;
      EXPECT_EQ(s[0], float(c.cpca().cluster[v]));
      for (int j = 0; j < N; ++j) EXPECT_EQ(s[1 + j], c.cpca().weights[v * N + j]);
      for (int p = N + 1; p < 4 * t.texelsPerRow; ++p) EXPECT_EQ(s[p], 0.0f);
    }
  }
}

TEST(ClusterTable, VectorSumTimesAlbedoEqualsRelightCompressed) {
  for (int channels : {1, 3})
    for (int N : {0, 2, 6})
      for (int lightBands : {4, 2}) {
        SCOPED_TRACE(::testing::Message() << "C " << channels << " N " << N << " b " << lightBands);
        const std::size_t n = 500;
        const Transfer f = randomField(TransferLayout::Vector, 4, channels, n, 3 + N);
        const Transfer c = compressCpca(f, opts(7, N, 2, 5));
        std::vector<Rgb> albedo(n);
        Pcg32 rng(9);
        for (Rgb& a : albedo) a = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
        const relight::PreparedLight light = relight::prepareLight(randomLight(lightBands, 4), 4);
        std::vector<Rgb> want(n);
        relight::relightPrepared(c, light, PreparedMaterial{}, {{}, {}, albedo}, Vec3f(0.0f), want);

        const relight::ShaderRows vt = relight::packShaderRows(c, ShaderPath::CpcaVector);
        std::vector<float> table;
        relight::packClusterTable(relight::projectClusters(c, light), table);
        ASSERT_EQ(table.size(), std::size_t(4 * 7 * (N + 1)));
        double worst = 0, scale = 0;
        for (std::size_t v = 0; v < n; ++v) {
          Rgb e;
          relight::evalPackedRow(vt, table, 1, v, &e);
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
      const Transfer f = randomField(TransferLayout::Matrix, bands, channels, n, 30 + channels);
      const Transfer c = compressCpca(f, opts(4, 5, 2, 5));
      const Transfer r = c.toDense();
      const relight::PreparedLight light = relight::prepareLight(randomLight(lightBands, 8), bands);
      const relight::ShaderRows vt = relight::packShaderRows(c, ShaderPath::CpcaMatrix);
      std::vector<float> table;
      relight::packClusterTable(relight::projectClusters(c, light), table);
      ASSERT_EQ(table.size(), std::size_t(4 * 4 * 6 * nB));
      const int nb = lightBands * lightBands;
      double worst = 0, scale = 0;
      std::vector<Rgb> got(nB);
      for (std::size_t v = 0; v < n; ++v) {
        relight::evalPackedRow(vt, table, nB, v, got.data());
        // (M̂_v L)_i,c = Σ_{l < b²} M̂_v[(i·B² + l)·C + c] L_l,c
        const float* m = r.row(v);
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
  CpcaRows c;
  c.clusters = (1 << 24) + 1;
  c.cluster.assign(std::size_t(1 << 24) + 1, 0);
  c.means = FloatArray::zeros(c.cluster.size());
  const Transfer t =
      Transfer::cpca(testdata::shapeOf(TransferLayout::Vector, 1, 1, c.cluster.size()), c);
  EXPECT_THROW(relight::packShaderRows(t, ShaderPath::CpcaVector), Error);
}

// The glossy kernels for the shaders (relight::shaderKernel) carry the SH normalisation
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

/// A random per-texel vector transfer over a W × H lightmap.
Transfer randomTexels(int bands, int channels, int w, int h, std::uint64_t seed) {
  TransferShape s = testdata::shapeOf(TransferLayout::Vector, bands, channels, std::size_t(w) * h);
  s.domain = TransferDomain::Texels;
  s.lightmap = {w, h, 1};
  Transfer f = Transfer::zeros(s);
  Pcg32 rng(seed);
  float* x = f.mutableValues();
  for (std::size_t i = 0; i < f.values().size(); ++i) x[i] = rng.uniform() - 0.3f;
  return f;
}

TEST(ShaderTransfer, PerTexelRowsRelitPerPixelAreTheBilinearFetchOfTheRelitTexels) {
  const int W = 7, H = 5, B = 4;
  for (int channels : {1, 3})
    for (bool compressed : {false, true})
      for (int b : {4, 3}) {
        SCOPED_TRACE(::testing::Message()
                     << "C " << channels << " cpca " << compressed << " b " << b);
        Transfer t = randomTexels(B, channels, W, H, 40 + channels);
        if (compressed) t = compressCpca(t, opts(3, 2, 4, 5));
        EXPECT_EQ(relight::shaderPath(t, false),
                  compressed ? ShaderPath::CpcaVector : ShaderPath::DenseVector);
        const relight::ShaderRows rows = relight::packShaderRows(
            t, compressed ? ShaderPath::CpcaVector : ShaderPath::DenseVector);
        ASSERT_TRUE(rows.perPixel);
        EXPECT_EQ(rows.lightmap, t.shape().lightmap);
        // What the fragment stage reads per frame: the packed light, or the cluster table.
        const sh::RgbSh light = randomLight(B, 11);
        relight::LightPacker packer;
        packer.setLight(light);
        packer.pack(Mat3d::identity(), b);
        const std::span<const float> packed(packer.data(), packer.bytes() / sizeof(float));
        const Transfer shown = t.cut(b);
        std::vector<float> table;
        if (compressed)
          relight::packClusterTable(
              relight::projectClusters(shown, relight::prepareLight(packer.rotated(), b)), table);
        // The reference: every texel relit (white), fetched bilinearly (render's fetch).
        std::vector<Rgb> texels(shown.rowCount());
        relight::relight(shown, light.truncated(b), Material{}, relight::Surface{}, Vec3f(0.0f),
                         texels);
        Pcg32 rng(3);
        double worst = 0, scale = 0;
        for (int k = 0; k < 400; ++k) {
          // Inside and a little outside [0, 1]² (clamped to the edge texels).
          const Vec2f uv(rng.uniform() * 1.2f - 0.1f, rng.uniform() * 1.2f - 0.1f);
          const TexelTaps taps = bilinearTaps(uv, W, H);
          Rgb want(0.0f);
          for (int q = 0; q < 4; ++q) want += texels[taps.texel[q]] * taps.weight[q];
          const Rgb got = relight::evalPerPixel(rows, packed, b, table, uv);
          for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(double(got[c]) - want[c]));
            scale = std::max(scale, std::abs(double(want[c])));
          }
        }
        EXPECT_GT(scale, 0.1);
        EXPECT_LT(worst, 1e-5 * scale);
      }
  // Matrices per texel are refused by name.
  TransferShape m = testdata::shapeOf(TransferLayout::Matrix, 2, 1, 4);
  m.domain = TransferDomain::Texels;
  m.lightmap = {2, 2, 0};
  try {
    relight::shaderPath(Transfer::zeros(m), true);
    ADD_FAILURE() << "a per-texel matrix transfer was given a path";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(relight::kPerTexelMatricesRefusal), std::string::npos);
  }
}

TEST(ShaderTransfer, RadianceLightmapDrawnAgainstTheLightsFirstCoefficientIsTheRadiance) {
  // A per-texel Haar bake is relit on the CPU into one radiance a texel; the viewer draws it
  // through the dense per-pixel path as a one-band transfer R / L'_00 against the turned light:
  // at any turn what the stage computes is the bilinear fetch of R (render's).
  const TransferShape::LightmapSize lm{6, 4, 0};
  Pcg32 rng(17);
  std::vector<Rgb> radiance(lm.texels());
  for (Rgb& r : radiance) r = Rgb(rng.uniform() * 3.0f, rng.uniform(), rng.uniform() - 0.1f);
  sh::RgbSh light = randomLight(3, 5);
  light.c[0] = Rgb(2.5f, 0.75f, 0.0f);  // a black channel: its radiance is zero too
  for (std::size_t i = 0; i < radiance.size(); ++i) radiance[i].z = 0.0f;
  const TransferShape shape = relight::radianceLightmapShape(lm);
  EXPECT_EQ(shape.rowCount(), lm.texels());
  EXPECT_EQ(shape.bands, 1);
  EXPECT_EQ(shape.channels, 3);
  for (const Mat3d& turn : {Mat3d::identity(), rotationEulerXYZ(20, 130, -40)}) {
    relight::LightPacker packer;
    packer.setLight(light);
    packer.pack(turn, 1);
    const relight::ShaderRows rows =
        relight::packRadianceLightmap(radiance, lm, packer.rotated()[0]);
    ASSERT_TRUE(rows.perPixel);
    EXPECT_EQ(rows.path, ShaderPath::DenseVector);
    EXPECT_EQ(rows.texelsPerRow, 1);
    const std::span<const float> packed(packer.data(), packer.bytes() / sizeof(float));
    double worst = 0;
    for (int k = 0; k < 200; ++k) {
      const Vec2f uv(rng.uniform() * 1.2f - 0.1f, rng.uniform() * 1.2f - 0.1f);
      const TexelTaps taps = bilinearTaps(uv, lm.width, lm.height);
      Rgb want(0.0f);
      for (int q = 0; q < 4; ++q) want += radiance[taps.texel[q]] * taps.weight[q];
      const Rgb got = relight::evalPerPixel(rows, packed, 1, {}, uv);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(got[c]) - want[c]));
    }
    EXPECT_LT(worst, 1e-5);
  }
  EXPECT_THROW(relight::packRadianceLightmap(std::vector<Rgb>(5), lm, Rgb(1.0f)), Error);
}

}  // namespace
}  // namespace prt
