// prt compress end to end: the written bake holds the compressed transfer with the stats the
// command printed, its reconstruction matches an in-process compression bit for bit, prt info
// shows it, prt render relights from it, --target-error meets its target, --sweep writes the
// table and the plot, and bad options are refused with one line and nothing written.

#include <gtest/gtest.h>

#include "common/random_data.hpp"

#include <algorithm>
#include <filesystem>
#include <string>

#include "cli_harness.hpp"
#include "prt/compress/cpca.hpp"
#include "prt/io/bake_file.hpp"

namespace fs = std::filesystem;

namespace prt {
namespace {

using namespace prt::testing;
using CompressCli = CliTest;

int lines(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

TEST_F(CompressCli, CompressInfoRenderSweepTarget) {
  ASSERT_EQ(prt("bake builtin:sphere-plane --mode shadowed --bands 3 --samples 64 -o b.glb").rc, 0);
  const Result c = prt("compress b.glb --clusters 8 --pca 3 --seed 5 -o c.glb");
  ASSERT_EQ(c.rc, 0) << c.err;
  EXPECT_NE(c.out.find("K 8 N 3: relative RMS error"), std::string::npos) << c.out;

  const BakeFile src = readBake(path("b.glb"));
  const BakeFile out = readBake(path("c.glb"));
  EXPECT_EQ(out.formatVersion, kBakeFormatVersion);
  ASSERT_EQ(out.transfers.size(), 1u);
  const BakedTransfer& t = out.transfers[0];
  ASSERT_TRUE(t.transfer.compressed());
  // The same compression in process: bit-identical (deterministic for the seed, any threads).
  CpcaStats s;
  CpcaOptions o;
  o.clusters = 8, o.basisCount = 3, o.seed = 5, o.maxIterations = 30;
  const Transfer ref = compressCpca(src.transfers[0].transfer, o, &s);
  EXPECT_EQ(t.transfer.cpca().cluster, ref.cpca().cluster);
  EXPECT_EQ(testdata::valuesOf(t.transfer), testdata::valuesOf(ref));
  EXPECT_EQ(t.compression.stats.squaredError, s.squaredError);

  const Result i = prt("info c.glb");
  ASSERT_EQ(i.rc, 0) << i.err;
  EXPECT_NE(i.out.find("compressed: CPCA, 8 clusters x 3 components"), std::string::npos) << i.out;
  const Result r = prt("render c.glb --light builtin:sky --size 64x48 -o c.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_TRUE(fs::exists(fs::path(path("c.png"))));

  const Result tg = prt("compress b.glb --target-error 0.02 --sweep-clusters 1,4,16 -o t.glb");
  ASSERT_EQ(tg.rc, 0) << tg.err;
  const BakeFile tb = readBake(path("t.glb"));
  EXPECT_LE(tb.transfers[0].compression.stats.relativeRms, 0.02);
  // Measured afresh against the source, not trusted from the file.
  EXPECT_LE(measureCpca(src.transfers[0].transfer, tb.transfers[0].transfer).relativeRms, 0.02);

  const Result sw = prt("compress b.glb --sweep s.png --sweep-clusters 1,4 --max-pca 3");
  ASSERT_EQ(sw.rc, 0) << sw.err;
  EXPECT_EQ(lines(sw.out), 1 + 2 * 4) << sw.out;  // header + K × (N = 0..3)
  EXPECT_TRUE(fs::exists(fs::path(path("s.png"))));
}

TEST_F(CompressCli, BadOptionsAreRefusedWithOneLine) {
  ASSERT_EQ(prt("bake builtin:sphere-plane --mode shadowed --bands 2 --samples 16 -o b.glb").rc, 0);
  for (const char* args :
       {"compress b.glb --pca 5 -o x.glb", "compress b.glb --clusters 0 -o x.glb",
        "compress b.glb -o b.glb", "compress b.glb --target-error 0.1 --pca 2 -o x.glb",
        "compress b.glb", "compress b.glb --sweep s.jpg", "compress b.glb --pca 1 -o x.png",
        "compress missing.glb -o x.glb", "compress b.glb --target-error 2 -o x.glb"}) {
    const Result r = prt(std::string("-q ") + args);
    EXPECT_NE(r.rc, 0) << args;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find("prt compress: error: "), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(fs::path(path("x.glb")))) << args;
  }
  // Compressing twice is refused by name.
  ASSERT_EQ(prt("compress b.glb --pca 1 --clusters 2 -o c.glb").rc, 0);
  const Result twice = prt("compress c.glb --pca 1 -o x.glb");
  EXPECT_NE(twice.err.find("already compressed"), std::string::npos) << twice.err;
}

TEST_F(CompressCli, APieceOfASplitBakeIsRefusedUntilMerged) {
  // The issue: a ranged bake compressed alone gave a file prt merge could not join (each piece
  // its own clusters). Refused by name, nothing written; the merged bake compresses.
  ASSERT_EQ(prt("-q bake builtin:sphere --mode unshadowed --bands 3 --samples 16 --range 0:5000 "
                "-o a.glb").rc,
            0);
  ASSERT_EQ(prt("-q bake builtin:sphere --mode unshadowed --bands 3 --samples 16 --range 5000:10242 "
                "-o b.glb").rc,
            0);
  const Result r = prt("compress a.glb --clusters 4 --pca 2 -o c.glb");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("a.glb: is a partial bake: it holds transfer for vertices 0..4999 of 10242 "
                       "only (merge the pieces with prt merge first)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_FALSE(fs::exists(fs::path(path("c.glb"))));
  ASSERT_EQ(prt("-q merge a.glb b.glb -o m.glb").rc, 0);
  const Result m = prt("-q compress m.glb --clusters 4 --pca 2 -o c.glb");
  EXPECT_EQ(m.rc, 0) << m.err;
  EXPECT_TRUE(readBake(path("c.glb")).transfers.at(0).transfer.compressed());
}

}  // namespace
}  // namespace prt
