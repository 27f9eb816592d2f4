// Clustered PCA (prt/compress/cpca.hpp): exact identities (full basis reproduces the rows,
// K = 1 is PCA as Eigen's SVD computes it independently), the Lloyd monotonicity of the
// iteration, and bit-identical results for any thread count.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "common/random_data.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"

namespace prt {
namespace {

/// Rows drawn from `groups` clusters, each a random mean plus a random rank-3 subspace plus a
/// little isotropic noise: the structure CPCA is meant to find.
Transfer clusteredField(TransferLayout layout, int bands, int channels, std::size_t rows,
                        int groups, std::uint64_t seed) {
  Transfer f = Transfer::zeros(testdata::shapeOf(layout, bands, channels, rows));
  const std::size_t D = f.stride();
  float* values = f.mutableValues();
  Pcg32 rng(seed);
  auto g = [&] { return 2.0f * rng.uniform() - 1.0f; };
  std::vector<float> means(groups * D), dirs(groups * 3 * D);
  for (float& m : means) m = g();
  for (float& d : dirs) d = g();
  for (std::size_t p = 0; p < rows; ++p) {
    const std::size_t k = rng.next() % groups;
    const float a = g(), b = g(), c = g();
    for (std::size_t i = 0; i < D; ++i)
      values[p * D + i] = means[k * D + i] + a * dirs[(k * 3) * D + i] +
                          0.5f * b * dirs[(k * 3 + 1) * D + i] +
                          0.25f * c * dirs[(k * 3 + 2) * D + i] + 0.01f * g();
  }
  return f;
}

double maxAbsDiff(const Transfer& a, const Transfer& b) {
  const Transfer x = a.toDense(), y = b.toDense();
  double m = 0;
  for (std::size_t i = 0; i < x.values().size(); ++i)
    m = std::max(m, std::abs(double(x.values()[i]) - y.values()[i]));
  return m;
}

CpcaOptions opts(int clusters, int basis, std::uint64_t seed, int iterations) {
  CpcaOptions o;
  o.clusters = clusters;
  o.basisCount = basis;
  o.seed = seed;
  o.maxIterations = iterations;
  return o;
}

TEST(Cpca, FullBasisReproducesVectorRows) {
  const Transfer f = clusteredField(TransferLayout::Vector, 3, 1, 600, 5, 1);
  CpcaStats s;
  const Transfer c = compressCpca(f, opts(4, 9, 7, 30), &s);
  c.check("test");
  EXPECT_TRUE(c.compressed());
  EXPECT_LT(maxAbsDiff(f, c.toDense()), 1e-5);
  EXPECT_LT(s.relativeRms, 1e-6);
}

TEST(Cpca, FullBasisReproducesRgbMatrixRowsBothPcaPaths) {
  // D = 2⁴·3 = 48. 3 clusters of ~100 rows use the D×D covariance; 30 clusters of ~10 rows
  // (fewer rows than D) use the Gram matrix.
  const Transfer f = clusteredField(TransferLayout::Matrix, 2, 3, 300, 4, 2);
  ASSERT_EQ(f.stride(), 48u);
  for (int K : {3, 30}) {
    const Transfer c = compressCpca(f, opts(K, 48, 3, 30));
    EXPECT_LT(maxAbsDiff(f, c.toDense()), 1e-5) << K << " clusters";
  }
}

TEST(Cpca, OneClusterEqualsPcaBySvd) {
  const Transfer f = clusteredField(TransferLayout::Vector, 3, 3, 800, 3, 3);
  const std::size_t D = f.stride(), n = f.rowCount();  // 27
  // Independent reference: SVD of the mean-centred data; rank-N error = Σ_{i≥N} σ_i².
  Eigen::MatrixXd X(n, D);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t i = 0; i < D; ++i) X(p, i) = f.row(p)[i];
  const Eigen::RowVectorXd mean = X.colwise().mean();
  X.rowwise() -= mean;
  Eigen::BDCSVD<Eigen::MatrixXd> svd(X, Eigen::ComputeThinV);
  const Eigen::VectorXd sigma = svd.singularValues();
  for (int N : {0, 1, 4, 10, 26}) {
    CpcaStats s;
    const Transfer c = compressCpca(f, opts(1, N, 0, 30), &s);
    double expected = 0;
    for (Eigen::Index i = N; i < sigma.size(); ++i) expected += sigma[i] * sigma[i];
    EXPECT_NEAR(s.squaredError, expected, 1e-4 * expected + 1e-6) << "N = " << N;
    // Same subspace: the projectors onto our basis and onto the top N right singular vectors.
    Eigen::MatrixXd B(N, D);
    for (int j = 0; j < N; ++j)
      for (std::size_t i = 0; i < D; ++i) B(j, i) = c.basisVector(0, j)[i];
    const Eigen::MatrixXd V = svd.matrixV().leftCols(N);
    EXPECT_LT((B.transpose() * B - V * V.transpose()).norm(), 1e-4) << "N = " << N;
    for (std::size_t i = 0; i < D; ++i) EXPECT_NEAR(c.clusterMean(0)[i], mean[i], 1e-5);
  }
}

TEST(Cpca, LanczosPathsEqualPcaBySvd) {
  // Operators larger than 128 are solved for their top N only (Spectra's Lanczos): the D × D
  // covariance when the cluster has at least D rows, else the m × m Gram matrix. D = 9²·3 = 243;
  // 700 rows take the covariance path, 180 the Gram path (180 > 128 both ways).
  for (std::size_t rows : {700, 180}) {
    const Transfer f = clusteredField(TransferLayout::Vector, 9, 3, rows, 3, 8);
    const std::size_t D = f.stride(), n = f.rowCount();
    ASSERT_EQ(D, 243u);
    Eigen::MatrixXd X(n, D);
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t i = 0; i < D; ++i) X(p, i) = f.row(p)[i];
    X.rowwise() -= X.colwise().mean();
    Eigen::BDCSVD<Eigen::MatrixXd> svd(X, Eigen::ComputeThinV);
    const Eigen::VectorXd sigma = svd.singularValues();
    for (int N : {1, 3, 8}) {
      CpcaStats s;
      const Transfer c = compressCpca(f, opts(1, N, 0, 30), &s);
      double expected = 0;
      for (Eigen::Index i = N; i < sigma.size(); ++i) expected += sigma[i] * sigma[i];
      EXPECT_NEAR(s.squaredError, expected, 1e-4 * expected) << rows << " rows, N = " << N;
      if (N == 8) continue;  // beyond the rank-3 structure the noise directions are near-degenerate
      Eigen::MatrixXd B(N, D);
      for (int j = 0; j < N; ++j)
        for (std::size_t i = 0; i < D; ++i) B(j, i) = c.basisVector(0, j)[i];
      const Eigen::MatrixXd V = svd.matrixV().leftCols(N);
      EXPECT_LT((B.transpose() * B - V * V.transpose()).norm(), 1e-4) << rows << " rows, N = " << N;
    }
  }
}

TEST(Cpca, ErrorNeverIncreasesWithBasisSize) {
  const Transfer f = clusteredField(TransferLayout::Vector, 4, 1, 1000, 6, 4);
  // K = 1: nested PCA subspaces, independent runs.
  double last = INFINITY;
  for (int N = 0; N <= 16; ++N) {
    CpcaStats s;
    compressCpca(f, opts(1, N, 5, 30), &s);
    EXPECT_LE(s.squaredError, last * (1 + 1e-6) + 1e-9) << "K = 1, N = " << N;
    last = s.squaredError;
  }
  // K > 1, each N warm-started from the previous clustering (what --sweep does): the first
  // refit with one more direction cannot lose, and Lloyd iterations only descend.
  last = INFINITY;
  Transfer prev;
  for (int N = 0; N <= 16; ++N) {
    CpcaStats s;
    Transfer c = compressCpca(f, opts(8, N, 5, 30), &s, N ? &prev : nullptr);
    EXPECT_LE(s.squaredError, last * (1 + 1e-5) + 1e-9) << "K = 8, N = " << N;
    last = s.squaredError;
    prev = std::move(c);
  }
}

TEST(Cpca, IterationsNeverIncreaseError) {
  const Transfer f = clusteredField(TransferLayout::Vector, 3, 1, 2000, 12, 5);
  double last = INFINITY;
  for (int it = 0; it <= 8; ++it) {
    CpcaStats s;
    compressCpca(f, opts(10, 2, 11, it), &s);
    EXPECT_LE(s.squaredError, last * (1 + 1e-5)) << "iterations " << it;
    last = s.squaredError;
  }
}

TEST(Cpca, VectorQuantisationFindsDistinctRows) {
  // Exactly 5 distinct rows, repeated: K = 5, N = 0 (k-means) must find them (zero error).
  std::vector<float> values(250 * 4);
  for (std::size_t p = 0; p < 250; ++p)
    for (std::size_t i = 0; i < 4; ++i) values[p * 4 + i] = float((p % 5) * 10 + i);
  const Transfer f = testdata::denseTransfer(TransferLayout::Vector, 2, 1, values);
  CpcaStats s;
  const Transfer c = compressCpca(f, opts(5, 0, 9, 30), &s);
  EXPECT_EQ(s.squaredError, 0.0);
  EXPECT_TRUE(c.cpca().weights.empty());
  for (std::size_t p = 5; p < 250; ++p) EXPECT_EQ(c.cpca().cluster[p], c.cpca().cluster[p % 5]);
}

TEST(Cpca, BitIdenticalForAnyThreadCount) {
  const Transfer f = clusteredField(TransferLayout::Vector, 3, 3, 6000, 20, 6);
  auto run = [&](int threads) {
    ThreadLimit limit(threads);
    return compressCpca(f, opts(16, 3, 42, 30));
  };
  const Transfer a = run(1), b = run(4);
  const auto same = [](const FloatArray& x, const FloatArray& y) {
    return x.size() == y.size() && std::equal(x.data(), x.data() + x.size(), y.data());
  };
  EXPECT_EQ(a.cpca().cluster, b.cpca().cluster);
  EXPECT_TRUE(same(a.cpca().weights, b.cpca().weights));
  EXPECT_TRUE(same(a.cpca().means, b.cpca().means));
  EXPECT_TRUE(same(a.cpca().basis, b.cpca().basis));
  // The same where clusters are large enough for the Lanczos path (D = 243, ~500 rows each).
  const Transfer big = clusteredField(TransferLayout::Vector, 9, 3, 2000, 4, 7);
  auto runBig = [&](int threads) {
    ThreadLimit limit(threads);
    return compressCpca(big, opts(4, 5, 42, 30));
  };
  const Transfer c = runBig(1), d = runBig(4);
  EXPECT_EQ(c.cpca().cluster, d.cpca().cluster);
  EXPECT_TRUE(same(c.cpca().weights, d.cpca().weights));
  EXPECT_TRUE(same(c.cpca().basis, d.cpca().basis));
  // And the seed matters.
  const Transfer other = compressCpca(f, opts(16, 3, 43, 0));
  const Transfer again = compressCpca(f, opts(16, 3, 42, 0));
  EXPECT_NE(other.cpca().cluster, again.cpca().cluster);
}

TEST(Cpca, RefusesBadOptions) {
  const Transfer f = clusteredField(TransferLayout::Vector, 2, 1, 10, 2, 7);
  EXPECT_THROW(compressCpca(f, opts(0, 1, 0, 30)), Error);
  EXPECT_THROW(compressCpca(f, opts(11, 1, 0, 30)), Error);
  EXPECT_THROW(compressCpca(f, opts(2, 5, 0, 30)), Error);  // D = 4
  EXPECT_THROW(compressCpca(f, opts(2, -1, 0, 30)), Error);
  const Transfer empty = Transfer::zeros(testdata::shapeOf(TransferLayout::Vector, 2, 1, 0));
  EXPECT_THROW(compressCpca(empty, opts(1, 1, 0, 30)), Error);
  // A compressed source is refused.
  EXPECT_THROW(compressCpca(compressCpca(f, opts(2, 1, 0, 30)), opts(2, 1, 0, 30)), Error);
}

TEST(Cpca, CompressionRatioCountsStoredBytes) {
  const Transfer f = clusteredField(TransferLayout::Vector, 3, 1, 1000, 3, 8);
  CpcaStats s;
  const Transfer c = compressCpca(f, opts(4, 2, 1, 5), &s);
  // 1000 rows × (2-byte id + 2 floats) + 4 × 3 × 9 floats, against 1000 × 9 floats.
  EXPECT_EQ(c.bytes(), 1000u * 10 + 4u * 3 * 9 * 4);
  EXPECT_DOUBLE_EQ(s.compressionRatio, 36000.0 / c.bytes());
}

}  // namespace
}  // namespace prt
