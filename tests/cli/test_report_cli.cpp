// `--json PATH|-`: every verb that reports something writes one JSON object of one schema style
// (apps/prt/report.hpp, docs/formats-report.md). The figures are checked against what the verb
// also wrote (the bake file, the light file), and the same object against what another verb
// says of the same thing (bake's transfer against info's).

#include <gtest/gtest.h>

#include <cmath>

#include <string>

#include "cli_harness.hpp"
#include "prt/core/json.hpp"

namespace prt::testing {
namespace {

constexpr const char* kSphere = "'builtin:sphere-plane?subdiv=1'";

class ReportCli : public CliTest {
 protected:
  Json load(const std::string& name) const { return Json::parse(slurp(dir_ / name)); }
  /// The members every report opens with.
  static void expectEnvelope(const Json& j, const std::string& verb) {
    ASSERT_TRUE(j.is_object());
    auto it = j.begin();
    EXPECT_EQ(it.key(), "verb");
    EXPECT_EQ(j.at("verb"), verb);
    EXPECT_FALSE(j.at("prtkitVersion").get<std::string>().empty());
    EXPECT_TRUE(j.at("inputs").is_array());
    EXPECT_TRUE(j.at("outputs").is_array());
  }
  void bake(const std::string& extra = "") const {
    const Result r =
        prt(std::string("-q bake ") + kSphere + " --mode shadowed --samples 16 -o b.glb" + extra);
    ASSERT_EQ(r.rc, 0) << r.err;
  }
};

TEST_F(ReportCli, BakeReportsTheTransferInfoReadsBack) {
  bake(" --json bake.json");
  const Json b = load("bake.json");
  expectEnvelope(b, "bake");
  EXPECT_EQ(b["outputs"], Json::array({"b.glb"}));
  EXPECT_EQ(b["inputs"], Json::array({"builtin:sphere-plane?subdiv=1"}));
  ASSERT_EQ(b["transfers"].size(), 1u);
  const Json& t = b["transfers"][0];
  EXPECT_EQ(t["mode"], "shadowed");
  EXPECT_EQ(t["bands"], 3);
  EXPECT_EQ(t["coefficients"], 9);
  EXPECT_EQ(t["recipe"]["samples"], 16);
  EXPECT_GT(t["stats"]["rays"].get<double>(), 0);
  EXPECT_EQ(b["rows"]["complete"], true);
  EXPECT_EQ(b["rows"]["end"], b["mesh"]["vertices"]);

  // info --json -: nothing but the report on standard output, the same objects for the same
  // things.
  const Result r = prt("info b.glb --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json i = Json::parse(r.out);
  expectEnvelope(i, "info");
  ASSERT_EQ(i["files"].size(), 1u);
  const Json& f = i["files"][0];
  EXPECT_EQ(f["kind"], "bake");
  EXPECT_EQ(f["mesh"], b["mesh"]);
  EXPECT_EQ(f["transfers"][0], t);
}

TEST_F(ReportCli, LightReportHoldsTheCoefficientsItWrote) {
  const Result r = prt("-q light builtin:sky --bands 4 -o l.json --json r.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json j = load("r.json"), l = load("l.json");
  expectEnvelope(j, "light");
  EXPECT_EQ(j["outputs"], Json::array({"l.json"}));
  EXPECT_EQ(j["light"]["bands"], 4);
  EXPECT_EQ(j["light"]["coefficients"], l["coefficients"]);
  // The sky is brightest overhead: its dominant direction points up.
  EXPECT_GT(j["light"]["dominantDirection"][1].get<double>(), 0.5);
  // And info says the same of the file.
  const Result i = prt("info l.json --json -");
  ASSERT_EQ(i.rc, 0) << i.err;
  EXPECT_EQ(Json::parse(i.out)["files"][0]["light"], j["light"]);
}

TEST_F(ReportCli, ValidateReportGoesToStandardOutputAndTheTableToStderr) {
  bake();
  const Result r =
      prt("-q validate b.glb --light builtin:sky --reference-samples 8 --vertices 12 --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json j = Json::parse(r.out);
  expectEnvelope(j, "validate");
  EXPECT_EQ(j["mode"], "shadowed");
  EXPECT_EQ(j["vertices"], 12);
  EXPECT_EQ(j["rows"].size(), 3u);
  EXPECT_NE(r.err.find("bands |"), std::string::npos) << "the table moves to stderr: " << r.err;
}

TEST_F(ReportCli, ReferenceRenderAndCompressReport) {
  bake();
  Result r =
      prt("-q reference b.glb --light builtin:sky --samples 8 --vertices 6 -o ref.json "
          "--json rr.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json ref = load("rr.json");
  expectEnvelope(ref, "reference");
  EXPECT_EQ(ref["vertices"], 6);
  EXPECT_EQ(ref["samples"], 8);
  EXPECT_EQ(ref["rays"], load("ref.json")["rays"]);

  r = prt("-q render b.glb --size 32x24 --spp 1 --turntable 2 -o f.png --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json ren = Json::parse(r.out);
  expectEnvelope(ren, "render");
  EXPECT_EQ(ren["outputs"], Json::array({"f_000.png", "f_001.png"}));
  EXPECT_EQ(ren["frames"].size(), 2u);
  EXPECT_EQ(ren["width"], 32);
  EXPECT_EQ(ren["exposureAuto"], true);
  EXPECT_DOUBLE_EQ(ren["frames"][1]["lightRotationDegreesY"].get<double>(), 180.0);

  r = prt("-q compress b.glb --clusters 2 --pca 2 -o c.glb --json c.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json c = load("c.json");
  expectEnvelope(c, "compress");
  EXPECT_EQ(c["transfer"]["representation"], "cpca");
  EXPECT_EQ(c["transfer"]["compression"]["clusters"], 2);
  EXPECT_LT(c["transfer"]["bytes"].get<double>(), c["transfer"]["denseBytes"].get<double>());
}

TEST_F(ReportCli, UnwrapAndMergeReport) {
  // The issue: unwrap printed its atlas's figures and refused --json; merge had none either.
  Result r = prt("-q unwrap " + std::string(kSphere) + " --resolution 64 -o u.glb --json u.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json u = load("u.json");
  expectEnvelope(u, "unwrap");
  EXPECT_EQ(u["outputs"], Json::array({"u.glb"}));
  EXPECT_EQ(u["atlas"]["resolution"], 64);
  EXPECT_GE(u["atlas"]["charts"].get<int>(), 1);
  EXPECT_GT(u["atlas"]["texelsCovered"].get<double>(), 0.0);
  EXPECT_LE(u["atlas"]["texelsCovered"].get<double>(), 1.0);
  EXPECT_EQ(u["mesh"]["vertices"], u["atlas"]["verticesAfter"]);
  // What info says of the written mesh.
  r = prt("info u.glb --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["files"][0]["mesh"]["vertices"], u["mesh"]["vertices"]);

  for (const char* range : {"0:20", "20:"})
    ASSERT_EQ(prt(std::string("-q bake ") + kSphere + " --mode shadowed --samples 16 --range " +
                  range + " -o p" + range[0] + ".glb")
                  .rc,
              0);
  r = prt("-q merge p2.glb p0.glb -o m.glb --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json m = Json::parse(r.out);
  expectEnvelope(m, "merge");
  EXPECT_EQ(m["inputs"], Json::array({"p2.glb", "p0.glb"}));
  EXPECT_EQ(m["rows"]["first"], 0);
  EXPECT_EQ(m["rows"]["complete"], true);
  EXPECT_EQ(m["rows"]["end"], m["mesh"]["vertices"]);
  ASSERT_EQ(m["transfers"].size(), 1u);
  r = prt("info m.glb --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["files"][0]["transfers"][0], m["transfers"][0]);
}

TEST_F(ReportCli, BadReportPathsAreRefusedBeforeAnyWork) {
  bake();
  expectCleanFailure("light builtin:sky -o out/l.json --json out/l.json", "name the same file");
  expectCleanFailure("light builtin:sky -o out/l.json --json out/r.txt", "name a .json file");
  expectCleanFailure("render b.glb --size 16x12 -o - --json -", "both name standard output");
  expectCleanFailure("info b.glb --json b.glb", "would overwrite the input");
  expectCleanFailure("validate b.glb --light builtin:sky --json out/missing/r.json", "r.json");
}

TEST_F(ReportCli, InfoDescribesAMeshBeforeItIsBaked) {
  // The mesh a bake reads, as the bake will record it: the same counts, and bounds.
  const Result r = prt("info 'builtin:plane?y=-1&size=1' --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json i = Json::parse(r.out);
  expectEnvelope(i, "info");
  const Json& f = i["files"][0];
  EXPECT_EQ(f["kind"], "mesh");
  EXPECT_EQ(f["mesh"]["bounds"]["min"][1], -1.0);
  EXPECT_EQ(f["mesh"]["bounds"]["max"][1], -1.0);
  EXPECT_EQ(f["mesh"]["bounds"]["max"][0], 1.0);
  ASSERT_EQ(prt("-q bake 'builtin:plane?y=-1&size=1' --mode unshadowed --samples 4 -o p.glb").rc,
            0);
  const Result b = prt("info p.glb --json -");
  ASSERT_EQ(b.rc, 0) << b.err;
  EXPECT_EQ(Json::parse(b.out)["files"][0]["mesh"]["vertices"], f["mesh"]["vertices"]);
  const Result text = prt("info 'builtin:plane?y=-1&size=1'");
  EXPECT_NE(text.out.find("bounds      (-1, -1, -1) .. (1, -1, 1)"), std::string::npos) << text.out;
}

// The lightmap a mesh's UV sets can hold (issue 18's rule, geometry/lightmap_uvs.hpp): the
// Cornell box's packed charts cover most of a 256² lightmap, the sphere has no UV set (said in
// one line), and a bake file keeps the lightmap set (attributes name it).
TEST_F(ReportCli, InfoJudgesAMeshsLightmapUvs) {
  Result r =
      prt("info --resolution 256 'builtin:cornell?grid=8' 'builtin:sphere?subdiv=1' --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json i = Json::parse(r.out);
  const Json& box = i["files"][0]["lightmap"];
  EXPECT_EQ(box["resolution"], 256);
  EXPECT_EQ(box["uvSet"], "lightmap UVs");
  const double coverage = box["coverage"];
  EXPECT_GT(coverage, 0.4);
  EXPECT_LT(coverage, 0.95);  // the gutter stays empty
  EXPECT_EQ(box["coveredTexels"].get<double>(), std::round(coverage * 256 * 256));
  const Json& ball = i["files"][1]["lightmap"];
  EXPECT_TRUE(ball["uvSet"].is_null());
  ASSERT_EQ(ball["refused"].size(), 1u);
  EXPECT_NE(ball["refused"][0].get<std::string>().find("lightmap UVs: the mesh has none"),
            std::string::npos);
  r = prt("info 'builtin:sphere?subdiv=1'");
  EXPECT_NE(r.out.find("lightmap    none: no UV set can hold a 512 x 512 lightmap"),
            std::string::npos)
      << r.out;
  ASSERT_EQ(prt("-q bake 'builtin:cornell?grid=4' --mode unshadowed --samples 4 -o c.glb").rc, 0);
  r = prt("info c.glb --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["files"][0]["mesh"]["attributes"],
            Json::array({"normals", "lightmapUvs", "albedo"}));
  EXPECT_NE(prt("info --resolution 0 c.glb").err.find("--resolution"), std::string::npos);
}

}  // namespace
}  // namespace prt::testing
