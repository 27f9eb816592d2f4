// `--json PATH|-`: every verb that reports something writes one JSON object of one schema style
// (apps/prt/report.hpp, docs/formats-report.md). The figures are checked against what the verb
// also wrote (the bake file, the light file), and the same object against what another verb
// says of the same thing (bake's transfer against info's).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
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

/// Every file a folder report lists is on disk with that size, is an output, and the folder
/// holds no other (its mark aside).
void expectFolderAsWritten(const std::filesystem::path& dir, const Json& report,
                           const std::string& folderName) {
  const Json& folder = report["folder"];
  EXPECT_EQ(folder["path"], folderName);
  std::size_t files = 0, total = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir / folderName))
    if (e.is_regular_file() && e.path().filename() != ".prt-output") ++files;
  ASSERT_EQ(folder["files"].size(), files);
  for (const Json& f : folder["files"]) {
    const std::string rel = f["path"];
    const std::string out = folderName + "/" + rel;
    EXPECT_EQ(f["bytes"].get<std::size_t>(), std::filesystem::file_size(dir / out)) << out;
    EXPECT_NE(std::find(report["outputs"].begin(), report["outputs"].end(), Json(out)),
              report["outputs"].end())
        << out;
    total += f["bytes"].get<std::size_t>();
  }
  EXPECT_EQ(folder["bytes"].get<std::size_t>(), total);
  EXPECT_EQ(report["outputs"].size(), files);
}

// Issue 31: export, web and demo wrote files and printed figures, but took no --json.
TEST_F(ReportCli, ExportReportsWhatItWrote) {
  bake();
  Result r = prt("-q export b.glb -o t.txt --json e.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json e = load("e.json");
  expectEnvelope(e, "export");
  EXPECT_EQ(e["inputs"], Json::array({"b.glb"}));
  EXPECT_EQ(e["outputs"], Json::array({"t.txt"}));
  EXPECT_EQ(e["format"], "games202");
  ASSERT_EQ(e["files"].size(), 1u);
  EXPECT_EQ(e["files"][0]["bytes"].get<std::size_t>(), std::filesystem::file_size(dir_ / "t.txt"));
  EXPECT_EQ(e["games202"]["layout"], "faces");
  EXPECT_EQ(e["games202"]["channel"], nullptr);
  EXPECT_EQ(e["games202"]["diffusePart"], false);
  // transport.txt: a vertex count, then the lines.
  const std::string text = slurp(dir_ / "t.txt");
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), e["games202"]["lines"].get<long>() + 1);
  r = prt("info b.glb --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["files"][0]["transfers"][0], e["transfer"]);
  EXPECT_EQ(e["games202"]["headerVertices"], e["transfer"]["rows"]["end"]);

  // Coefficient textures: a folder, its files one by one; the encoding as transfer.json has it.
  ASSERT_EQ(prt("-q bake 'builtin:cornell?grid=4' --domain texels --resolution 32 --mode "
                "unshadowed --samples 16 -o c.glb")
                .rc,
            0);
  r = prt("-q export c.glb --format png -o tex --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json x = Json::parse(r.out);  // nothing else on standard output
  expectEnvelope(x, "export");
  EXPECT_EQ(x["format"], "png");
  EXPECT_EQ(x["encoding"], "unorm16");
  expectFolderAsWritten(dir_, x, "tex");
  const Json manifest = load("tex/transfer.json");
  EXPECT_EQ(x["textures"], manifest["textures"]);
  EXPECT_EQ(x["lightmap"]["width"], 32);
  EXPECT_GT(x["maxQuantisationError"].get<double>(), 0.0);
  EXPECT_EQ(x["transfer"]["domain"], "texels");

  // A failure leaves no report; a report inside the folder written as a whole is refused.
  expectCleanFailure("export b.glb --mode interreflected -o out/t.txt --json out/e.json",
                     "holds no interreflected transfer");
  expectCleanFailure("export c.glb --format exr -o out/tex --json out/tex/r.json",
                     "inside the -o folder");
}

TEST_F(ReportCli, WebReportsTheFolderAndWhatThePageDraws) {
  bake();
  Result r = prt("-q web b.glb -o w --json w.json");
  if (r.rc != 0 && r.err.find("not built") != std::string::npos)
    GTEST_SKIP() << "the browser viewer's assets are not built: " << r.err;
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json w = load("w.json");
  expectEnvelope(w, "web");
  EXPECT_EQ(w["inputs"], Json::array({"b.glb", "builtin:sky"}));
  expectFolderAsWritten(dir_, w, "w");
  EXPECT_EQ(w["bake"]["bytes"].get<std::size_t>(), std::filesystem::file_size(dir_ / "b.glb"));
  EXPECT_EQ(w["bake"]["embedded"], true);
  ASSERT_EQ(w["environments"].size(), 1u);
  EXPECT_EQ(w["environments"][0]["source"], "builtin:sky");
  EXPECT_EQ(w["environments"][0]["light"]["bands"], 3);
  EXPECT_EQ(w["view"]["transfer"]["mode"], "shadowed");
  EXPECT_EQ(w["view"]["exposureAuto"], true);
  EXPECT_EQ(w["view"]["camera"], nullptr);
  r = prt("info b.glb --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json i = Json::parse(r.out)["files"][0];
  EXPECT_EQ(i["transfers"][0], w["transfers"][0]);
  EXPECT_EQ(i["mesh"], w["mesh"]);
  // The page's light is what prt light writes of the same environment at the bake's bands.
  ASSERT_EQ(prt("-q light builtin:sky --bands 3 -o l.json").rc, 0);
  EXPECT_EQ(w["environments"][0]["light"]["coefficients"], load("l.json")["coefficients"]);

  r = prt("-q web b.glb -o w2 --exposure 1 --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["view"]["exposureStops"], 1.0);
  expectCleanFailure("web b.glb --env out/missing.exr -o out/w --json out/w.json", "missing.exr");
}

TEST_F(ReportCli, DemoReportHoldsThePagesFigures) {
  const std::string demo =
      "demo --mesh 'builtin:sphere?subdiv=1' --env builtin:sky --bands 2 --samples 16 "
      "--reference-samples 4 --frames 0 --glossy none --size 32x24 ";
  Result r = prt("-q " + demo + "-o d --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Json d = Json::parse(r.out);  // nothing else on standard output
  expectEnvelope(d, "demo");
  EXPECT_EQ(d["inputs"], Json::array({"builtin:sphere?subdiv=1", "builtin:sky"}));
  expectFolderAsWritten(dir_, d, "d");
  EXPECT_EQ(d["bake"]["bytes"].get<std::size_t>(),
            std::filesystem::file_size(dir_ / "d/scene.glb"));
  EXPECT_EQ(d["glossy"], nullptr);
  // The bake table: the transfers as info reads them from scene.glb.
  r = prt("info d/scene.glb --json -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["files"][0]["transfers"], d["bake"]["transfers"]);
  // The validation tables: what validation/*.json holds, as numbers.
  ASSERT_EQ(d["environments"].size(), 1u);
  const Json& sky = d["environments"][0];
  EXPECT_EQ(sky["name"], "sky");
  EXPECT_EQ(sky["light"]["coefficients"],
            load("d/" + sky["lightFile"].get<std::string>())["coefficients"]);
  ASSERT_EQ(sky["modes"].size(), 3u);
  for (const Json& m : sky["modes"]) {
    const std::string mode = m["mode"];
    EXPECT_EQ(m["validation"], load("d/validation/sky_" + mode + ".json")) << mode;
    EXPECT_EQ(m["validation"]["rows"].size(), 2u);
    EXPECT_TRUE(std::filesystem::exists(dir_ / "d" / m["images"]["prt"].get<std::string>()));
  }
  // The per-texel row's figures.
  const Json& t = d["texels"];
  EXPECT_EQ(t["bands"], 2);
  for (const char* k : {"coarse", "texels", "dense"}) {
    EXPECT_GT(t[k]["bytes"].get<double>(), 0) << k;
    EXPECT_GT(t[k]["relRmse"].get<double>(), 0) << k;
  }
  EXPECT_EQ(t["texels"]["rows"], t["resolution"].get<int>() * t["resolution"].get<int>());
  // The live viewer, when its assets are built, as prt web reports it.
  EXPECT_EQ(d["web"].is_null(), !d["webMissing"].is_null());
  if (!d["web"].is_null()) {
    EXPECT_EQ(d["web"]["folder"]["path"], "d/web");
    EXPECT_EQ(d["web"]["bake"]["path"], "d/scene.glb");
    EXPECT_EQ(d["web"]["transfers"], d["bake"]["transfers"]);
  }
  expectCleanFailure(demo + "-o out/d --env out/missing.exr --json out/d.json", "missing.exr");
}

TEST_F(ReportCli, HeadlessViewReportsItsFrameAndTimings) {
  bake();
  const Result r =
      prt("-q view b.glb --headless --size 32x24 --frames 2 --stats --screenshot "
          "s.png --json -");
  if (r.rc != 0 &&
      (r.err.find("no viewer") != std::string::npos || r.err.find("EGL") != std::string::npos))
    GTEST_SKIP() << "no headless OpenGL here: " << r.err;
  ASSERT_EQ(r.rc, 0) << r.err;
  expectCleanFailure("view b.glb --json out/v.json", "add --headless");
  const Json v = Json::parse(r.out);  // --stats' lines go to stderr
  expectEnvelope(v, "view");
  EXPECT_NE(r.err.find("frame time"), std::string::npos) << r.err;
  EXPECT_EQ(v["outputs"], Json::array({"s.png"}));
  EXPECT_EQ(v["screenshot"]["bytes"].get<std::size_t>(),
            std::filesystem::file_size(dir_ / "s.png"));
  EXPECT_EQ(v["frames"], 2);
  EXPECT_EQ(v["width"], 32);
  EXPECT_EQ(v["transfer"]["mode"], "shadowed");
  EXPECT_EQ(v["environment"], "builtin:sky");
  EXPECT_GT(v["firstFrameSeconds"].get<double>(), 0.0);
  EXPECT_LE(v["minFrameSeconds"].get<double>(), v["firstFrameSeconds"].get<double>());
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
