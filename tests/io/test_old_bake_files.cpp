// Bake files written before the one-Transfer redesign (format versions 1-3, tests/data/bakes/,
// made by prtkit 0.1.0 at fd07068: vector, RGB, matrix and CPCA-compressed transfer, split
// pieces and their merge) still read: their shapes and settings are what they were written with,
// they round-trip through the current writer bit for bit, and the pieces merge into exactly the
// file the old merge wrote. (Their renders and exports are checked through the binary in
// tests/cli/test_old_bake_files_cli.cpp.)

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "prt/core/error.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/bake_merge.hpp"

namespace prt {
namespace {

std::string fixture(const std::string& name) {
  return std::string(PRT_SOURCE_DIR) + "/tests/data/bakes/" + name;
}

bool sameBits(const FloatArray& a, const FloatArray& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

bool sameTransfer(const Transfer& a, const Transfer& b) {
  if (!(a.shape() == b.shape()) || a.compressed() != b.compressed()) return false;
  if (!a.compressed()) return sameBits(a.values(), b.values());
  return a.cpca().cluster == b.cpca().cluster && sameBits(a.cpca().weights, b.cpca().weights) &&
         sameBits(a.cpca().means, b.cpca().means) && sameBits(a.cpca().basis, b.cpca().basis);
}

/// Encoded with today's writer and read back: the same bake, bit for bit.
void expectRoundTrip(const BakeFile& b) {
  const std::string bytes = encodeBake(b);
  const BakeFile r =
      decodeBake({reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()}, "again.glb");
  EXPECT_EQ(r.formatVersion, kBakeFormatVersion);
  EXPECT_EQ(r.mesh.positions, b.mesh.positions);
  EXPECT_EQ(r.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(r.mesh.albedo, b.mesh.albedo);
  ASSERT_EQ(r.transfers.size(), b.transfers.size());
  for (std::size_t i = 0; i < b.transfers.size(); ++i) {
    EXPECT_EQ(r.transfers[i].recipe, b.transfers[i].recipe) << i;
    EXPECT_TRUE(sameTransfer(r.transfers[i].transfer, b.transfers[i].transfer)) << i;
  }
}

TEST(OldBakeFiles, VersionOneVectorsAndRgbReadAsWritten) {
  const BakeFile b = readBake(fixture("v1-vector.glb"));
  EXPECT_EQ(b.formatVersion, 1);
  EXPECT_TRUE(b.complete());
  EXPECT_EQ(b.mesh.vertexCount(), 91u);
  ASSERT_EQ(b.transfers.size(), 2u);
  const BakedTransfer* s = b.find(TransferMode::Shadowed);
  const BakedTransfer* i = b.find(TransferMode::Interreflected);
  ASSERT_TRUE(s && i);
  EXPECT_EQ(s->transfer.shape().describe(), "vector, 4 bands, scalar, 91 vertices");
  EXPECT_EQ(i->transfer.shape().describe(), "vector, 4 bands, RGB, 91 vertices");
  EXPECT_EQ(i->recipe.bounces, 1);
  EXPECT_EQ(i->recipe.samples, 32);
  EXPECT_EQ(i->recipe.seed, 7u);
  // Version 1 kept the bounce albedo as "albedo": it is the material's kd now.
  ASSERT_TRUE(i->recipe.material.diffuse.has_value());
  EXPECT_EQ(*i->recipe.material.diffuse, Rgb(0.9f, 0.6f, 0.3f));
  EXPECT_NO_THROW(i->transfer.check("v1"));
  expectRoundTrip(b);
}

TEST(OldBakeFiles, VersionFourInExtrasReadsAsWritten) {
  // The last version that kept its object in extras.prtkit (5 moved it to the
  // PRTKIT_radiance_transfer extension).
  const BakeFile b = readBake(fixture("v4-vector.glb"));
  EXPECT_EQ(b.formatVersion, 4);
  EXPECT_TRUE(b.complete());
  EXPECT_EQ(b.mesh.vertexCount(), 91u);
  ASSERT_EQ(b.transfers.size(), 2u);
  const BakedTransfer* i = b.find(TransferMode::Interreflected);
  ASSERT_TRUE(i);
  EXPECT_EQ(i->transfer.shape().describe(), "vector, 3 bands, scalar, 91 vertices");
  EXPECT_EQ(i->recipe.samples, 32);
  EXPECT_EQ(i->recipe.seed, 7u);
  expectRoundTrip(b);
}

TEST(OldBakeFiles, VersionTwoMatricesReadAsWritten) {
  const BakeFile b = readBake(fixture("v2-matrix.glb"));
  EXPECT_EQ(b.formatVersion, 2);
  ASSERT_EQ(b.transfers.size(), 1u);
  const BakedTransfer& t = b.transfers[0];
  EXPECT_EQ(t.transfer.shape().describe(), "matrix, 3 bands, scalar, 91 vertices");
  EXPECT_TRUE(t.transfer.values().isView());  // read in place, not copied
  // Version 2 stored the material as its spec string (6 digits); it reads as it was.
  EXPECT_EQ(t.recipe.material.spec(), "phong?exponent=8&ks=0.4&kd=0.6");
  expectRoundTrip(b);
}

TEST(OldBakeFiles, VersionThreeCompressedReadsAsWritten) {
  const BakeFile v = readBake(fixture("v3-cpca-vector.glb"));
  EXPECT_EQ(v.formatVersion, 3);
  const BakedTransfer* c = v.find(TransferMode::Interreflected);
  ASSERT_NE(c, nullptr);
  ASSERT_TRUE(c->transfer.compressed());
  EXPECT_EQ(c->transfer.cpca().clusters, 4);
  EXPECT_EQ(c->transfer.cpca().basisCount, 2);
  EXPECT_NEAR(c->compression.stats.relativeRms, 0.13627, 1e-5);
  EXPECT_FALSE(v.find(TransferMode::Shadowed)->transfer.compressed());
  expectRoundTrip(v);
  const BakeFile m = readBake(fixture("v3-cpca-matrix.glb"));
  ASSERT_TRUE(m.transfers[0].transfer.compressed());
  EXPECT_TRUE(m.transfers[0].transfer.isMatrix());
  EXPECT_EQ(m.transfers[0].transfer.cpca().basisCount, 3);
  expectRoundTrip(m);
}

TEST(OldBakeFiles, PiecesMergeIntoWhatTheOldMergeWrote) {
  const BakeFile a = readBake(fixture("v1-part0.glb")), b = readBake(fixture("v1-part1.glb"));
  EXPECT_FALSE(a.complete());
  EXPECT_EQ(a.rows(), (RowRange{0, 50}));
  EXPECT_EQ(b.rows(), (RowRange{50, 41}));
  EXPECT_THROW(a.requireComplete("v1-part0.glb"), Error);
  const BakeFile merged = mergeBakes({b, a});
  const BakeFile old = readBake(fixture("v1-merged.glb"));
  ASSERT_EQ(merged.transfers.size(), old.transfers.size());
  EXPECT_TRUE(merged.complete());
  EXPECT_TRUE(sameTransfer(merged.transfers[0].transfer, old.transfers[0].transfer));
  EXPECT_EQ(merged.transfers[0].stats.rays, old.transfers[0].stats.rays);
  EXPECT_EQ(merged.transfers[0].stats.raysPerSecond, old.transfers[0].stats.raysPerSecond);
}

}  // namespace
}  // namespace prt
