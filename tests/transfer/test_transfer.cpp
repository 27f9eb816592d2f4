// The one transfer value (prt/transfer/transfer.hpp): its shape, band cut (one answer for both
// representations, bit for bit), reconstruction, row access, memory size, checks, and the
// copy-on-write storage under it (prt/core/float_array.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "common/random_data.hpp"
#include "prt/core/error.hpp"
#include "prt/core/float_array.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {
namespace {

using testdata::randomField;
using testdata::shapeOf;

bool sameBits(const FloatArray& a, const FloatArray& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

/// A compressed transfer with arbitrary numbers (the operations under test are linear algebra
/// on the arrays, not the fit).
Transfer randomCpca(TransferLayout layout, int bands, int channels, std::size_t rows, int K, int N,
                    std::uint64_t seed) {
  const TransferShape shape = shapeOf(layout, bands, channels, rows);
  Pcg32 rng(seed);
  const auto fill = [&](std::size_t n) {
    std::vector<float> x(n);
    for (float& v : x) v = 2.0f * rng.uniform() - 1.0f;
    return FloatArray(std::move(x));
  };
  CpcaRows c;
  c.clusters = K, c.basisCount = N;
  for (std::size_t r = 0; r < rows; ++r) c.cluster.push_back(rng.next() % K);
  c.weights = fill(rows * N);
  c.means = fill(K * shape.stride());
  c.basis = fill(K * N * shape.stride());
  return Transfer::cpca(shape, std::move(c));
}

TEST(TransferShape, SizesOfEachLayout) {
  TransferShape s = shapeOf(TransferLayout::Vector, 3, 3, 10);
  EXPECT_EQ(s.rowSize(), 9u);
  EXPECT_EQ(s.stride(), 27u);
  EXPECT_EQ(s.denseBytes(), 10u * 27 * 4);
  s.layout = TransferLayout::Matrix;
  EXPECT_EQ(s.rowSize(), 81u);
  EXPECT_EQ(s.stride(), 243u);
  s.rows.count = std::numeric_limits<std::size_t>::max() / 4;
  EXPECT_EQ(s.denseBytes(), std::numeric_limits<std::size_t>::max());  // saturates
  EXPECT_THROW(shapeOf(TransferLayout::Vector, 0, 1, 1).check("x"), Error);
  EXPECT_THROW(shapeOf(TransferLayout::Vector, 33, 1, 1).check("x"), Error);
  EXPECT_THROW(shapeOf(TransferLayout::Vector, 3, 2, 1).check("x"), Error);
  EXPECT_EQ(shapeOf(TransferLayout::Matrix, 5, 3, 7).describe(),
            "matrix, 5 bands, RGB, 7 vertices");
}

TEST(Transfer, DenseCutKeepsTheLeadingCoefficientsAndBlock) {
  const Transfer v = randomField(TransferLayout::Vector, 4, 3, 5, 1);
  const Transfer cv = v.cut(2);
  EXPECT_EQ(cv.bands(), 2);
  for (std::size_t r = 0; r < 5; ++r)
    for (std::size_t i = 0; i < 4 * 3; ++i) ASSERT_EQ(cv.row(r)[i], v.row(r)[i]);
  const Transfer m = randomField(TransferLayout::Matrix, 3, 1, 4, 2);
  const Transfer cm = m.cut(2);
  ASSERT_EQ(cm.stride(), 16u);
  for (std::size_t r = 0; r < 4; ++r)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) ASSERT_EQ(cm.row(r)[i * 4 + j], m.row(r)[i * 9 + j]);
  EXPECT_TRUE(sameBits(m.cut(3).values(), m.values()));  // a cut to all bands is the transfer
}

TEST(Transfer, CompressedCutEqualsTheCutOfTheReconstructionBitForBit) {
  for (TransferLayout layout : {TransferLayout::Vector, TransferLayout::Matrix})
    for (int channels : {1, 3})
      for (int b : {1, 2, 3}) {
        SCOPED_TRACE(::testing::Message() << toString(layout) << " C " << channels << " b " << b);
        const Transfer c = randomCpca(layout, 4, channels, 50, 3, 5, 7 + channels);
        const Transfer cut = c.cut(b);
        ASSERT_TRUE(cut.compressed());
        EXPECT_EQ(cut.cpca().cluster, c.cpca().cluster);              // ids kept
        EXPECT_TRUE(sameBits(cut.cpca().weights, c.cpca().weights));  // weights kept
        EXPECT_TRUE(sameBits(cut.toDense().values(), c.toDense().cut(b).values()));
        EXPECT_LT(cut.bytes(), c.bytes());
      }
}

TEST(Transfer, ReconstructRowAndBytes) {
  const Transfer c = randomCpca(TransferLayout::Vector, 3, 1, 20, 4, 2, 3);
  // x̂ = M_k + Σ_j w_j B_kj, row by row.
  std::vector<float> row(9);
  for (std::size_t r = 0; r < 20; ++r) {
    c.reconstructRow(r, row.data());
    const std::size_t k = c.cpca().cluster[r];
    for (int i = 0; i < 9; ++i) {
      float want = c.clusterMean(k)[i];
      for (int j = 0; j < 2; ++j) want += c.cpca().weights[r * 2 + j] * c.basisVector(k, j)[i];
      ASSERT_EQ(row[i], want);
    }
  }
  // uint16 ids and 2 weights per row, 4 × 3 vectors of 9 floats.
  EXPECT_EQ(c.bytes(), 20u * (2 + 8) + 4u * 3 * 9 * 4);
  const Transfer d = c.toDense();
  EXPECT_FALSE(d.compressed());
  EXPECT_EQ(d.bytes(), 20u * 9 * 4);
  EXPECT_TRUE(sameBits(d.toDense().values(), d.values()));  // dense: itself, shared
  EXPECT_EQ(d.toDense().values().data(), d.values().data());
}

TEST(Transfer, ChecksNameWhatIsWrong) {
  EXPECT_THROW(Transfer::dense(shapeOf(TransferLayout::Vector, 2, 1, 3), FloatArray::zeros(11)),
               Error);
  Transfer t = randomField(TransferLayout::Vector, 2, 1, 3, 4);
  EXPECT_NO_THROW(t.check("t"));
  t.mutableValues()[5] = std::numeric_limits<float>::quiet_NaN();
  try {
    t.check("t.glb");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.glb: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("row 1"), std::string::npos) << e.what();
  }
  CpcaRows bad = randomCpca(TransferLayout::Vector, 2, 1, 3, 2, 1, 5).cpca();
  bad.cluster[2] = 7;
  const Transfer c = Transfer::cpca(shapeOf(TransferLayout::Vector, 2, 1, 3), bad);
  EXPECT_THROW(c.check("c"), Error);
  bad.weights = FloatArray::zeros(2);  // 3 rows need 3 weights
  EXPECT_THROW(Transfer::cpca(shapeOf(TransferLayout::Vector, 2, 1, 3), bad), Error);
}

TEST(FloatArray, CopiesShareUntilOneIsWritten) {
  FloatArray a(std::vector<float>{1, 2, 3});
  FloatArray b = a;
  EXPECT_EQ(a.data(), b.data());  // shared
  b.mutableData()[0] = 9;         // copy on write
  EXPECT_NE(a.data(), b.data());
  EXPECT_EQ(a[0], 1.0f);
  EXPECT_EQ(b[0], 9.0f);
  // A sole owner writes in place.
  const float* before = a.data();
  a.mutableData()[1] = 5;
  EXPECT_EQ(a.data(), before);
  // A view is never written: the first write copies.
  auto keeper = std::make_shared<std::vector<float>>(std::vector<float>{4, 5});
  FloatArray v = FloatArray::view(keeper, keeper->data(), 2);
  EXPECT_TRUE(v.isView());
  v.mutableData()[0] = 0;
  EXPECT_FALSE(v.isView());
  EXPECT_EQ((*keeper)[0], 4.0f);
}

TEST(Transfer, WithFirstRowPlacesTheSameRows) {
  const Transfer t = randomField(TransferLayout::Vector, 2, 1, 6, 8);
  const Transfer moved = t.withFirstRow(100);
  EXPECT_EQ(moved.rows().first, 100u);
  EXPECT_EQ(moved.rowCount(), 6u);
  EXPECT_EQ(moved.values().data(), t.values().data());
}

}  // namespace
}  // namespace prt
