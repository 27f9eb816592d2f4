// Probe grids through the CLI (issue 32): prt probes writes a bake over the probe domain that
// reads back with its grid (format 7); it is prt bake --domain probes, bit for bit; ranges and
// job-array shards merge bit for bit into the whole grid; prt info describes it; and every verb
// that draws a surface's transfer refuses it in one line naming the file; prt render draws the
// scene with an object lit through the grid; prt validate compares it with the reference.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "prt/io/bake_file.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using ProbesCli = CliTest;

const std::string kBox = "'builtin:cornell?grid=6'";

TEST_F(ProbesCli, ProbesWriteAGridThatReadsBackAndMergesBitExactly) {
  const std::string probes = "-q probes " + kBox + " --grid 4x3x5 --samples 64";
  ASSERT_EQ(prt(probes + " -o whole.glb").rc, 0);
  const BakeFile whole = readBake(path("whole.glb"));
  ASSERT_EQ(whole.domain(), TransferDomain::Probes);
  EXPECT_EQ(whole.formatVersion, 7);
  EXPECT_EQ(whole.probeGrid().count, (std::array<int, 3>{4, 3, 5}));
  ASSERT_EQ(whole.transfers.size(), 1u);
  const BakedTransfer& t = whole.transfers[0];
  EXPECT_EQ(t.mode(), TransferMode::Interreflected);
  EXPECT_EQ(t.transfer.layout(), TransferLayout::Matrix);
  EXPECT_EQ(t.transfer.rowCount(), 60u);
  EXPECT_EQ(t.transfer.channels(), 3);  // the box's red and green walls
  // The same bake spelled as prt bake, and in pieces.
  ASSERT_EQ(prt("-q bake " + kBox +
                " --domain probes --transfer matrix --mode interreflected --grid 4x3x5 "
                "--samples 64 -o same.glb")
                .rc,
            0);
  const BakeFile same = readBake(path("same.glb"));
  ASSERT_EQ(same.transfers.size(), 1u);
  EXPECT_EQ(same.probeGrid(), whole.probeGrid());
  {
    const FloatArray& a = same.transfers[0].transfer.values();
    ASSERT_EQ(a.size(), t.transfer.values().size());
    for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], t.transfer.values()[k]) << k;
  }
  ASSERT_EQ(prt(probes + " --range 0:25 -o a.glb").rc, 0);
  ASSERT_EQ(prt(probes + " --range 25: -o b.glb").rc, 0);
  ASSERT_EQ(prt("-q merge b.glb a.glb -o merged.glb").rc, 0);
  const BakeFile merged = readBake(path("merged.glb"));
  ASSERT_TRUE(merged.complete());
  const FloatArray& x = merged.transfers[0].transfer.values();
  const FloatArray& y = t.transfer.values();
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t k = 0; k < x.size(); ++k) ASSERT_EQ(x[k], y[k]) << k;
}

TEST_F(ProbesCli, InfoDescribesTheGridAndTheVerbsThatDrawSurfacesRefuseIt) {
  ASSERT_EQ(prt("-q probes " + kBox + " --mode shadowed --grid 3x3x3 --samples 32 -o out/p.glb").rc,
            0);
  std::filesystem::rename(path("out/p.glb"), path("p.glb"));
  const Result info = prt("info p.glb --json -");
  ASSERT_EQ(info.rc, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out)["files"][0];
  EXPECT_EQ(j["domain"], "probes");
  EXPECT_EQ(j["probeGrid"]["probes"], 27);
  const Result text = prt("info p.glb");
  EXPECT_NE(text.out.find("3 x 3 x 3 probes"), std::string::npos) << text.out;
  // prt render draws the scene with an object lit through the grid; what draws a surface's
  // transfer refuses the grid by name.
  const Result drawn = prt("-q render p.glb --light builtin:sky --object builtin:sphere -o x.png");
  ASSERT_EQ(drawn.rc, 0) << drawn.err;
  EXPECT_TRUE(std::filesystem::exists(path("x.png")));
  expectCleanFailure("render p.glb --light builtin:sky --turntable 4 -o out/x.png",
                     "p.glb: holds a probe grid");
  for (const std::string& verb :
       {std::string("export p.glb --format games202 -o out/x"),
        std::string("web p.glb -o out/page"),
        std::string("reference p.glb --light builtin:sky -o out/r.json")})
    expectCleanFailure(verb, "p.glb: holds a probe grid (3 x 3 x 3 probes");
  expectCleanFailure("probes " + kBox + " --grid 4x0x4 -o out/q.glb", "--grid");
  expectCleanFailure("probes " + kBox + " --bounds 1,1,1:0,2,2 -o out/q.glb", "--bounds");
  expectCleanFailure("bake " + kBox + " --mode shadowed --domain probes -o out/q.glb",
                     "--transfer matrix");
  expectCleanFailure("bake " + kBox + " --mode shadowed --grid 2x2x2 -o out/q.glb", "prt probes");
}

TEST_F(ProbesCli, ValidateComparesTheGridWithTheReferenceAtSixNormalsPerProbe) {
  ASSERT_EQ(prt("-q probes " + kBox + " --grid 3x3x3 --samples 64 -o p.glb").rc, 0);
  const Result r = prt("validate p.glb --light builtin:sky --vertices 5 --reference-samples 32 "
                       "--bands-list 1,3 --json v.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("5 probes x 6 normals x 32 samples"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("truncation floor"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("v.json")));
  EXPECT_EQ(j["vertices"], 30);
  ASSERT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["rows"][1]["bands"], 3);
  EXPECT_GT(j["rows"][1]["relRmse"].get<double>(), 0.0);
  // What belongs to a surface is refused by name.
  expectCleanFailure("validate p.glb --light builtin:sky --image out/e.png",
                     "p.glb: --image draws a surface's error");
  std::ofstream(path("ref.json")) << "{}";
  expectCleanFailure("validate p.glb --light builtin:sky --reference ref.json",
                     "ref.json: a probe grid is validated against a reference computed here");
}

}  // namespace
}  // namespace prt
