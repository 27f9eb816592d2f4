// Haar transfer in the bake file (format 8; inter-reflected rows' bounces format 9): exact round
// trip, split bakes merge, broken rows and files claiming an older version refused by name, and
// SH-only consumers told why.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "common/error_text.hpp"
#include "prt/core/error.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/bake_merge.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/haar_rows.hpp"
#include "prt/transport/bake.hpp"

namespace prt {
namespace {

BakeFile haarBake(RowRange rows = {}, bool interreflected = false) {
  BakeFile f;
  f.mesh = builtinScene("builtin:sphere-plane?grid=8&subdiv=1");
  const auto occ = makeEmbreeOccluder(f.mesh);
  BakeSettings s;
  s.mode = TransferMode::Shadowed;
  s.basis = TransferBasis::Haar;
  s.haar = {8, 20};
  s.samples = 2;
  s.rows = rows;
  if (interreflected) {
    s.mode = TransferMode::Interreflected;
    s.bounces = 1;
    s.haar.bounceBands = 3;
    s.material.diffuse = Rgb(0.9f, 0.5f, 0.3f);
  }
  BakedTransfer t;
  t.recipe = s;
  t.transfer = bake(f.mesh, *occ, s, &t.stats);
  f.transfers.push_back(std::move(t));
  return f;
}

std::span<const unsigned char> bytesOf(const std::string& s) {
  return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

TEST(BakeFileHaar, RoundTripsExactly) {
  const BakeFile b = haarBake();
  const BakeFile r = decodeBake(bytesOf(encodeBake(b)), "haar.glb");
  EXPECT_EQ(r.formatVersion, kBakeFormatVersion);
  ASSERT_EQ(r.transfers.size(), 1u);
  const Transfer& a = b.transfers[0].transfer;
  const Transfer& c = r.transfers[0].transfer;
  EXPECT_EQ(c.shape(), a.shape());
  EXPECT_TRUE(c.isHaar());
  ASSERT_EQ(c.values().size(), a.values().size());
  EXPECT_EQ(std::memcmp(c.values().data(), a.values().data(), a.values().size() * 4), 0);
  EXPECT_EQ(r.transfers[0].settings().haar, (TransferShape::HaarSize{8, 20}));
  EXPECT_NE(transferStorage(r.transfers[0]).find("_PRT_SHADOWED_HAAR_"), std::string::npos);
  // As stored: 5 bytes a row (scale, kind) and 4 a term (16-bit index and value).
  EXPECT_EQ(c.bytes(), c.rowCount() * (5 + 20 * 4));
  // Both kinds of row are there (haar_rows.hpp): the plane's open vertices store their shadow,
  // the sphere's underside, facing the plane, its window on the sky.
  int kinds[2] = {0, 0};
  for (std::size_t r = 0; r < c.rowCount(); ++r) ++kinds[c.row(r)[0] == 1.0f];
  EXPECT_GT(kinds[0], 0);
  EXPECT_GT(kinds[1], 0);
}

TEST(BakeFileHaar, InterreflectedRowsRoundTripWithTheirBounce) {
  const BakeFile b = haarBake({}, true);
  const std::string bytes = encodeBake(b);
  const BakeFile r = decodeBake(bytesOf(bytes), "ir.glb");
  const Transfer& a = b.transfers[0].transfer;
  const Transfer& c = r.transfers[0].transfer;
  EXPECT_EQ(c.shape(), a.shape());
  EXPECT_EQ(c.shape().haar.bounceBands, 3);
  EXPECT_EQ(c.channels(), 3);
  ASSERT_EQ(c.values().size(), a.values().size());
  EXPECT_EQ(std::memcmp(c.values().data(), a.values().data(), a.values().size() * 4), 0);
  // As stored: the Haar row, then its bounce as 27 floats.
  EXPECT_EQ(c.bytes(), c.rowCount() * (5 + 20 * 4 + 27 * 4));
  // Split pieces merge into the whole, bounces and all.
  const std::size_t n = b.mesh.vertexCount();
  std::vector<BakeFile> pieces;
  pieces.push_back(haarBake({0, n / 2}, true));
  pieces.push_back(haarBake({n / 2, n - n / 2}, true));
  const BakeFile merged = mergeBakes(std::move(pieces));
  const FloatArray& m = merged.transfers[0].transfer.values();
  ASSERT_EQ(m.size(), a.values().size());
  EXPECT_EQ(std::memcmp(m.data(), a.values().data(), m.size() * 4), 0);

  // A file claiming version 8 cannot hold a bounce; a bounce without bounces, or bounces without
  // one, is refused; a non-finite bounce value is refused on writing.
  const auto edited = [&](const std::string& from, const std::string& to) {
    std::string e = bytes;
    const std::size_t at = e.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) e.replace(at, from.size(), to);
    return testing::errorOf([&] { decodeBake(bytesOf(e), "ir.glb"); });
  };
  std::string e = edited("\"formatVersion\":9", "\"formatVersion\":8");
  EXPECT_NE(e.find("version 8"), std::string::npos) << e;
  e = edited("\"bounces\":1", "\"bounces\":0");
  EXPECT_NE(e.find("holds a bounce"), std::string::npos) << e;
  e = edited("\"bounceBands\":3", "\"bounceBands\":6");
  EXPECT_NE(e.find("bounceBands"), std::string::npos) << e;
  BakeFile bad = haarBake({}, true);
  Transfer& t = bad.transfers[0].transfer;
  t.mutableValues()[5 * t.stride() + t.shape().haarBounceOffset() + 4] = std::nanf("");
  e = testing::errorOf([&] { encodeBake(bad); });
  EXPECT_NE(e.find("row 5: bounce value 4 is not finite"), std::string::npos) << e;
}

TEST(BakeFileHaar, SplitBakesMergeIntoTheWhole) {
  const BakeFile whole = haarBake();
  const std::size_t n = whole.mesh.vertexCount();
  std::vector<BakeFile> pieces;
  pieces.push_back(haarBake({0, n / 3}));
  pieces.push_back(haarBake({n / 3, n - n / 3}));
  const BakeFile merged = mergeBakes(std::move(pieces));
  const FloatArray& a = whole.transfers[0].transfer.values();
  const FloatArray& b = merged.transfers[0].transfer.values();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * 4), 0);
}

TEST(BakeFileHaar, BrokenRowsAreRefusedByName) {
  BakeFile b = haarBake();
  // A row naming a coefficient past the cube: refused when written...
  float* v = b.transfers[0].transfer.mutableValues();
  const std::size_t stride = b.transfers[0].transfer.stride();
  std::size_t row = 0;
  while (v[row * stride + 2] == 0.0f) ++row;  // a row with a kept term
  const float saved = v[row * stride + 1];
  v[row * stride + 1] = 384.0f;  // 6·8² = 384 coefficients
  const std::string w = testing::errorOf([&] { encodeBake(b); });
  EXPECT_NE(w.find("row " + std::to_string(row)), std::string::npos) << w;
  // ...and when read: the 16-bit indices follow the rows' scales; mark the row's last kept term
  // with the cube's last coefficient (still ascending), find it in the file and put one past
  // the cube in its place.
  v[row * stride + 1] = saved;
  std::size_t last = 0;
  while (last + 1 < 20 && v[row * stride + 2 * (last + 1) + 2] != 0.0f) ++last;
  ASSERT_LT(v[row * stride + 1 + 2 * last], 383.0f);
  v[row * stride + 1 + 2 * last] = 383.0f;
  std::string bytes = encodeBake(b);
  const std::uint16_t mark = 383, bad = 384;
  std::size_t at = std::string::npos;
  for (std::size_t i = 0; i + 2 <= bytes.size(); i += 2)
    if (std::memcmp(&bytes[i], &mark, 2) == 0) at = i;  // the last: the binary chunk's
  ASSERT_NE(at, std::string::npos);
  std::memcpy(&bytes[at], &bad, 2);
  const std::string e = testing::errorOf([&] { decodeBake(bytesOf(bytes), "broken.glb"); });
  EXPECT_NE(e.find("broken.glb"), std::string::npos) << e;
  EXPECT_NE(e.find("row " + std::to_string(row)), std::string::npos) << e;
  EXPECT_NE(e.find("index"), std::string::npos) << e;
}

TEST(BakeFileHaar, RowsLieOnTheirQuantisationGrid) {
  // What the bake holds in memory is what the file holds: the values are already on the
  // row's 16-bit grid, so decoding gives them back bit for bit (RoundTripsExactly), and the
  // grid is fine: 1/32767 of the row's largest term.
  const BakeFile b = haarBake();
  const Transfer& t = b.transfers[0].transfer;
  for (std::size_t r = 0; r < t.rowCount(); ++r) {
    const float* p = t.row(r) + 1;  // past the kind
    float s = 0;
    for (int k = 0; k < 20; ++k) s = std::max(s, std::abs(p[2 * k + 1]));
    for (int k = 0; k < 20; ++k) {
      const int q = haar::quantizeHaarValue(p[2 * k + 1], s);
      ASSERT_EQ(haar::dequantizeHaarValue(s, q), p[2 * k + 1]) << r << " " << k;
    }
  }
}

TEST(BakeFileHaar, ShOnlyConsumersSayWhy) {
  const BakeFile b = haarBake();
  const std::string e = testing::errorOf([&] { b.requireSh("h.glb", "prt compress fits SH"); });
  EXPECT_NE(e.find("h.glb: holds Haar-wavelet transfer"), std::string::npos) << e;
  EXPECT_NE(e.find("prt compress fits SH"), std::string::npos) << e;
}

}  // namespace
}  // namespace prt
