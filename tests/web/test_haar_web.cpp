// Haar bakes in the browser (issue 33; docs/haar.md, docs/web.md "Haar bakes", docs/three.md),
// against the library on the same bake and environment:
//   * the JavaScript — the page's reader, its light turned from prt web's environment cube
//     (haar_light.js) and its relighting (haar_relight.js), prtkit-three's HaarLighting — reads
//     the rows io::decodeBake reads, makes haar::turnedLight's light (the same terms, values to
//     1e-5) and relights every vertex as relight::relightHaar does, to 1e-5 relative, under the
//     cube at several turns and under a Haar light file (under node,
//     tests/web/haar/haar_check.mjs) — a shadowed bake, and an inter-reflected one whose rows
//     hold their bounce in SH (coloured: RGB), relit against the light's full SH;
//   * prt web's page draws the bake as prt render draws it, unturned and turned (its light is
//     turned from the cube, prt render's from the environment), and the frame turned the other
//     way does not match;
//   * the three.js example of the same folder draws it; a per-texel bake too, each texel relit
//     at the normal prt web ships beside it and drawn per pixel;
//   * prt web refuses, in one line naming the file or option, what the page does not relight.
// Each test skips, saying why, where node, chromium or the built page is missing.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <span>
#include <string>
#include <vector>

#include "cli/cli_harness.hpp"
#include "prt/core/json.hpp"
#include "prt/haar/turned_cube.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/haar_light_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/render/texel_points.hpp"
#include "web/page_harness.hpp"

namespace {

namespace fs = std::filesystem;
using prt::Json;
using prt::testing::Result;
using namespace web_harness;

Result prt(const std::string& args) {
  return prt::testing::runPrt(scratch(), args);
}
std::string path(const std::string& name) {
  return (scratch() / name).string();
}

const fs::path kSource = PRT_SOURCE_DIR;
const fs::path kGenerated = fs::path(PRT_BINARY_DIR) / "generated" / "web";
constexpr const char* kScene = "'builtin:sphere-plane?grid=12&subdiv=2'";
constexpr const char* kCamera = "eye=1.6,2.2,3.4;target=0,0.6,0;up=0,1,0;fov=40";

/// A shadowed Haar bake over a 16² cube, its page under builtin:sky (seen from kCamera) and a
/// Haar light file of the sky, written once; "" or why the page could not be written (its assets
/// are not built).
std::string haarPage() {
  static const std::string why = [] {
    Result r = prt(std::string("-q bake ") + kScene +
                   " --mode shadowed --basis haar --resolution 16 --terms 48 --samples 2 -o "
                   "haar.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    r = prt("-q light builtin:sky --basis haar --resolution 16 --terms 300 -o haar_sky.json");
    EXPECT_EQ(r.rc, 0) << r.err;
    r = prt("-q web haar.glb --light builtin:sky --camera '" + std::string(kCamera) +
            "' -o haar_page");
    if (r.rc != 0 && r.err.find("assets") != std::string::npos) return r.err;
    EXPECT_EQ(r.rc, 0) << r.err;
    return std::string();
  }();
  return why;
}

/// An inter-reflected Haar bake of the same scene and cube (its bounce in 3 SH bands, RGB under a
/// coloured albedo), relit in JavaScript from haarPage()'s environment cube; "" or why it could
/// not be made.
std::string interreflectedHaarBake() {
  static const std::string why = [] {
    const Result r = prt(std::string("-q bake ") + kScene +
                         " --mode interreflected --bounces 1 --albedo 0.9,0.5,0.3 --basis haar "
                         "--bands 3 --resolution 16 --terms 48 --samples 2 -o haar_ir.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    return r.rc == 0 ? std::string() : r.err;
  }();
  return why;
}

/// A per-texel Haar bake of the same scene (a 48² lightmap, the 16² cube) and its page under
/// builtin:sky, which prt web writes with the texels' points beside it; "" or why not.
std::string haarTexelPage() {
  static const std::string why = [] {
    Result r = prt(std::string("-q bake ") + kScene +
                   " --mode shadowed --basis haar --domain texels --resolution 48 "
                   "--cube-resolution 16 --terms 48 -o haar_texels.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    if (r.rc != 0) return r.err;
    r = prt("-q web haar_texels.glb --light builtin:sky --camera '" + std::string(kCamera) +
            "' -o haar_texel_page");
    if (r.rc != 0 && r.err.find("assets") != std::string::npos) return r.err;
    EXPECT_EQ(r.rc, 0) << r.err;
    return r.rc == 0 ? std::string() : r.err;
  }();
  return why;
}

/// prt-data.js's object.
Json pageData(const std::string& dir) {
  const std::string s = prt::testing::slurp(fs::path(dir) / "prt-data.js");
  const std::size_t a = s.find('=');
  std::string body = s.substr(a + 1);
  while (!body.empty() && (body.back() == '\n' || body.back() == ';')) body.pop_back();
  return Json::parse(body);
}

/// The environment cube prt web wrote, decoded as the page decodes its RGBE texels
/// (environment.js decodeRgbe: (m + ½)·2^(e − 136), zero for e = 0).
prt::haar::EnvironmentCube cubeOf(const Json& haar) {
  prt::haar::EnvironmentCube c;
  c.resolution = haar["resolution"];
  const std::vector<unsigned char> b = unbase64(haar["rgbe"].get<std::string>());
  c.means.resize(b.size() / 4);
  for (std::size_t p = 0; p < c.means.size(); ++p) {
    const int e = b[4 * p + 3];
    if (e == 0) continue;
    const double f = std::ldexp(1.0, e - 136);
    for (int k = 0; k < 3; ++k) c.means[p][std::size_t(k)] = float((b[4 * p + k] + 0.5) * f);
  }
  c.sh = prt::sh::RgbSh(prt::haar::kUnshadowedBands);
  for (std::size_t i = 0; i < c.sh.c.size(); ++i)
    for (int k = 0; k < 3; ++k)
      c.sh.c[i][std::size_t(k)] = haar["sh"][i][std::size_t(k)].get<float>();
  return c;
}

/// max |js − c++| over max |c++|.
double relativeError(const Json& js, const std::vector<float>& cpp) {
  EXPECT_EQ(js.size(), cpp.size());
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < cpp.size() && i < js.size(); ++i) {
    err = std::max(err, std::abs(js[i].get<double>() - cpp[i]));
    scale = std::max(scale, double(std::abs(cpp[i])));
  }
  return err / std::max(scale, 1e-30);
}

std::vector<float> flat(const std::vector<prt::Rgb>& v) {
  std::vector<float> out;
  for (const prt::Rgb& c : v)
    for (int k = 0; k < 3; ++k) out.push_back(c[std::size_t(k)]);
  return out;
}

constexpr double kRelative = 1e-5;

/// haar_check.mjs on bake `name` (in scratch()), held to the library: the rows exactly, the light
/// turned from haarPage()'s cube and every vertex relit under it (the page and prtkit-three), and
/// under the Haar light file. Returns the script's output.
Json checkJavaScript(const std::string& node, const std::string& name) {
  const std::vector<std::array<double, 3>> turns = {{0, 0, 0}, {20, -35, 10}, {-60, 15, 140}};
  const int terms = 150;
  Json rotate = Json::array();
  for (const auto& t : turns) rotate.push_back({t[0], t[1], t[2]});
  std::ofstream(path("haar_query.json")) << Json{{"rotate", rotate}, {"terms", terms}}.dump();
  const Result r =
      shell("'" + node + "' '" + (kSource / "tests/web/haar/haar_check.mjs").string() + "' '" +
            kGenerated.string() + "' '" + path(name) + "' '" + path("haar_page/prt-data.js") +
            "' '" + path("haar_sky.json") + "' '" + path("haar_query.json") + "'");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  if (r.rc != 0) return Json();
  const Json js = Json::parse(r.out);

  // The rows: exactly io::decodeBake's (an inter-reflected row's bounce after its pairs).
  const prt::BakeFile bake = prt::readBake(path(name));
  const prt::Transfer& t = bake.transfers[0].transfer;
  EXPECT_EQ(js["page"]["transfer"]["bounceBands"], t.shape().haar.bounceBands);
  EXPECT_EQ(js["page"]["transfer"]["channels"], t.shape().channels);
  const auto values = t.values();
  EXPECT_EQ(js["page"]["rows"].size(), values.size());
  if (js["page"]["rows"].size() != values.size()) return js;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (js["page"]["rows"][i].get<float>() != values[i]) {
      ADD_FAILURE() << "row value " << i << ": " << js["page"]["rows"][i] << " vs " << values[i];
      return js;
    }

  // The light turned from prt web's cube, and every vertex relit under it.
  const prt::haar::EnvironmentCube cube =
      cubeOf(pageData(path("haar_page"))["environments"][0]["haar"]);
  // The albedo prt render relights with: the recipe's kd, else the vertices'.
  const std::vector<prt::Rgb> atVertices = prt::albedoAtVertices(bake.mesh);
  const std::span<const prt::Rgb> albedo = bake.transfers[0].recipe.material.diffuseOr(atVertices);
  double worst = 0;
  for (std::size_t k = 0; k < turns.size(); ++k) {
    SCOPED_TRACE("turn " + std::to_string(k));
    const prt::Mat3d R = prt::rotationEulerXYZ(turns[k][0], turns[k][1], turns[k][2]);
    const prt::haar::HaarLight light = prt::haar::turnedLight(cube, 16, terms, R);
    const Json& l = js["page"]["lights"][k];
    EXPECT_EQ(l["index"].size(), light.index.size());
    if (l["index"].size() != light.index.size()) return js;
    for (std::size_t i = 0; i < light.index.size(); ++i) EXPECT_EQ(l["index"][i], light.index[i]);
    EXPECT_LT(relativeError(l["value"], flat(light.value)), kRelative);
    EXPECT_LT(relativeError(l["unshadowed"], flat(light.unshadowed.c)), kRelative);
    EXPECT_EQ(l["bright"].size(), light.bright.size());
    for (std::size_t b = 0; b < light.bright.size() && b < l["bright"].size(); ++b)
      EXPECT_EQ(l["bright"][b]["texel"], light.bright[b].texel);
    EXPECT_NEAR(l["energyKept"].get<double>(), light.energyKept, 1e-6);
    const std::vector<prt::Rgb> lib =
        prt::relight::relightHaar(t, light, bake.mesh.normals, albedo);
    const double e = relativeError(js["page"]["radiance"][k], flat(lib));
    EXPECT_LT(e, kRelative);
    worst = std::max(worst, e);
    if (k == 0) {
      EXPECT_LT(relativeError(js["three"]["radiance"], flat(lib)), kRelative);
    }
  }
  // Under a Haar light file.
  const std::vector<prt::Rgb> file = prt::relight::relightHaar(
      t, prt::io::readHaarLightJson(path("haar_sky.json")).light, bake.mesh.normals, albedo);
  EXPECT_LT(relativeError(js["page"]["file"], flat(file)), kRelative);
  EXPECT_EQ(js["three"]["meshes"], 2);
  EXPECT_NE(js["three"]["refusal"].get<std::string>().find("cannot be turned"), std::string::npos)
      << js["three"]["refusal"];
  std::cout << "JavaScript vs the library, Haar light and relighting (" << name
            << "): worst relative error " << worst << "\n";
  return js;
}

TEST(HaarWeb, JavaScriptRelightsAsTheLibrary) {
  std::string why;
  const std::string n = nodeForPageSources(&why);
  if (n.empty()) GTEST_SKIP() << why;
  const std::string page = haarPage();
  if (!page.empty()) GTEST_SKIP() << page;
  checkJavaScript(n, "haar.glb");
}

TEST(HaarWeb, JavaScriptRelightsInterreflectedAsTheLibrary) {
  std::string why;
  const std::string n = nodeForPageSources(&why);
  if (n.empty()) GTEST_SKIP() << why;
  const std::string page = haarPage();
  if (!page.empty()) GTEST_SKIP() << page;
  ASSERT_EQ(interreflectedHaarBake(), "");
  // The bake holds a bounce, coloured, so the comparison covers it (it can fail).
  const prt::BakeFile bake = prt::readBake(path("haar_ir.glb"));
  ASSERT_EQ(bake.transfers.size(), 1u);
  EXPECT_EQ(bake.transfers[0].transfer.shape().haar.bounceBands, 3);
  EXPECT_EQ(bake.transfers[0].transfer.shape().channels, 3);
  const Json js = checkJavaScript(n, "haar_ir.glb");
  if (js.is_null()) return;
  EXPECT_EQ(js["page"]["transfer"]["mode"].get<std::string>(), "interreflected");
}

#define PRT_REQUIRE_CHROMIUM()                                                             \
  do {                                                                                     \
    if (chromium().empty()) GTEST_SKIP() << "no chromium here (apt-get install chromium)"; \
  } while (0)

/// The page's ?screenshot frame (320x240) for `query`: its RGB bytes and report.
std::vector<unsigned char> pageFrame(const std::string& dir, const std::string& query,
                                     Json* report = nullptr) {
  std::string log;
  const std::string json = runPage(dir, "screenshot&size=320x240&" + query, &log);
  EXPECT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 400) << "\n" << log;
  if (json.empty()) return {};
  const Json j = Json::parse(json);
  if (report) *report = j;
  return unbase64(j["rgb"].get<std::string>());
}

TEST(HaarWeb, PageDrawsTheBakeAsPrtRender) {
  PRT_REQUIRE_CHROMIUM();
  const std::string page = haarPage();
  if (!page.empty()) GTEST_SKIP() << page;
  const std::string dir = path("haar_page");
  const std::string settings =
      "--exposure -3 --tonemap clamp --size 320x240 --camera '" + std::string(kCamera) + "'";
  double first = 0;
  for (const std::string rotate : {"0,0,0", "20,-35,10"}) {
    SCOPED_TRACE(rotate);
    const Result r = prt("-q render haar.glb --light builtin:sky --rotate " + rotate + " " +
                         settings + " -o haar_render.png");
    ASSERT_EQ(r.rc, 0) << r.err;
    Json report;
    const std::vector<unsigned char> rgb =
        pageFrame(dir, "exposure=-3&tonemap=clamp&rotate=" + rotate, &report);
    ASSERT_TRUE(report.contains("haar")) << report.dump().substr(0, 300);
    EXPECT_EQ(report["haar"]["resolution"], 16);
    EXPECT_EQ(report["haar"]["lightTerms"], 200);
    const double e = displayedRmse(rgb, path("haar_render.png"));
    std::cout << "page vs prt render, Haar bake turned " << rotate << ": RMSE " << e
              << ", 90th percentile " << quantile90 << "\n";
    EXPECT_LT(e, kMatch);
    if (first == 0) {
      first = e;
    } else {
      // The unturned frame is not the turned render (the comparison can fail).
      EXPECT_GT(displayedRmse(pageFrame(dir, "exposure=-3&tonemap=clamp&rotate=0,0,0"),
                              path("haar_render.png")),
                e + 0.004);
    }
  }
}

TEST(HaarWeb, ThreeExampleDrawsTheBake) {
  PRT_REQUIRE_CHROMIUM();
  const std::string page = haarPage();
  if (!page.empty()) GTEST_SKIP() << page;
  if (!fs::exists(path("haar_page/three/example.js")))
    GTEST_SKIP() << "the three.js example is not built (node or web/node_modules missing)";
  std::string log;
  const std::string json =
      runPage(path("haar_page/three"),
              "screenshot&size=320x240&only&exposure=-3&camera=" + std::string(kCamera) +
                  "&rotate=20,-35,10",
              &log);
  ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 400) << "\n" << log;
  const Json j = Json::parse(json);
  EXPECT_EQ(j["meshes"], 2);
  EXPECT_EQ(j["terms"], 200);
  const Result r = prt(std::string("-q render haar.glb --light builtin:sky --rotate 20,-35,10 ") +
                       "--exposure -3 --tonemap clamp --background none --size 320x240 --camera '" +
                       kCamera + "' -o haar_three.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const double e = displayedRmse(unbase64(j["rgb"].get<std::string>()), path("haar_three.png"));
  std::cout << "three.js module vs prt render, Haar bake: RMSE " << e << "\n";
  EXPECT_LT(e, kMatch);
}

TEST(HaarWeb, PageAndThreeDrawAPerTexelBakeAsPrtRender) {
  // Per texel: each texel relit in JavaScript at the normal prt web ships beside the bake (its
  // texel points), the relit lightmap drawn through the SH lightmaps' per-pixel stage against a
  // unit light (web/src/haar_texels.js) — prt render's image, unturned and turned; the three.js
  // example of the same folder too.
  PRT_REQUIRE_CHROMIUM();
  const std::string page = haarTexelPage();
  if (!page.empty()) GTEST_SKIP() << page;
  const std::string dir = path("haar_texel_page");
  EXPECT_EQ(pageData(dir)["bake"]["texelPoints"]["rows"], 48 * 48);
  const std::string settings =
      "--exposure -3 --tonemap clamp --size 320x240 --camera '" + std::string(kCamera) + "'";
  double unturned = 0;
  for (const std::string rotate : {"0,0,0", "20,-35,10"}) {
    SCOPED_TRACE(rotate);
    const Result r = prt("-q render haar_texels.glb --light builtin:sky --rotate " + rotate + " " +
                         settings + " -o haar_texel_render.png");
    ASSERT_EQ(r.rc, 0) << r.err;
    const std::vector<unsigned char> rgb =
        pageFrame(dir, "exposure=-3&tonemap=clamp&rotate=" + rotate);
    const double e = displayedRmse(rgb, path("haar_texel_render.png"));
    std::cout << "page vs prt render, per-texel Haar bake turned " << rotate << ": RMSE " << e
              << ", 90th percentile " << quantile90 << "\n";
    EXPECT_LT(e, kMatch);
    if (unturned == 0) {
      unturned = e;
    } else {
      // The unturned frame is not the turned render (the comparison can fail).
      EXPECT_GT(displayedRmse(pageFrame(dir, "exposure=-3&tonemap=clamp&rotate=0,0,0"),
                              path("haar_texel_render.png")),
                e + 0.004);
    }
  }
  if (!fs::exists(fs::path(dir) / "three" / "example.js"))
    GTEST_SKIP() << "the three.js example is not built (node or web/node_modules missing)";
  std::string log;
  const std::string json =
      runPage((fs::path(dir) / "three").string(),
              "screenshot&size=320x240&only&exposure=-3&camera=" + std::string(kCamera) +
                  "&rotate=20,-35,10",
              &log);
  ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 400) << "\n" << log;
  const Result r = prt(std::string("-q render haar_texels.glb --light builtin:sky --rotate ") +
                       "20,-35,10 --exposure -3 --tonemap clamp --background none --size 320x240 "
                       "--camera '" +
                       kCamera + "' -o haar_texel_three.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const double e = displayedRmse(unbase64(Json::parse(json)["rgb"].get<std::string>()),
                                 path("haar_texel_three.png"));
  std::cout << "three.js module vs prt render, per-texel Haar bake: RMSE " << e << "\n";
  EXPECT_LT(e, kMatch);
}

TEST(HaarWeb, JavaScriptRelightsTexelsAsTheLibrary) {
  // A per-texel bake: the page's reader refuses it without the texel points prt web writes
  // beside it, and with them relights every texel (web/src/haar_texels.js) as the library does
  // at render::texelRelight's normals — a gutter texel at the neighbour whose row it copies.
  std::string why;
  const std::string n = nodeForPageSources(&why);
  if (n.empty()) GTEST_SKIP() << why;
  const std::string page = haarTexelPage();
  if (!page.empty()) GTEST_SKIP() << page;
  const std::vector<std::array<double, 3>> turns = {{0, 0, 0}, {20, -35, 10}};
  const int terms = 150;
  Json rotate = Json::array();
  for (const auto& t : turns) rotate.push_back({t[0], t[1], t[2]});
  std::ofstream(path("haar_texels_query.json"))
      << Json{{"rotate", rotate}, {"terms", terms}}.dump();
  const Result r =
      shell("'" + n + "' '" + (kSource / "tests/web/haar/haar_texels_check.mjs").string() + "' '" +
            kGenerated.string() + "' '" + path("haar_texels.glb") + "' '" +
            path("haar_texel_page/prt-data.js") + "' '" + path("haar_texels_query.json") + "'");
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  const Json js = Json::parse(r.out);
  const std::string refusal = js["refusal"].get<std::string>();
  EXPECT_EQ(refusal.rfind("haar_texels.glb: holds per-texel Haar transfer", 0), 0u) << refusal;
  EXPECT_NE(refusal.find("prt web"), std::string::npos) << refusal;

  const prt::BakeFile bake = prt::readBake(path("haar_texels.glb"));
  const prt::Transfer& t = bake.transfers[0].transfer;
  EXPECT_EQ(js["rows"], t.rowCount());
  const auto occluder = prt::makeEmbreeOccluder(bake.mesh);
  const prt::render::TexelRelight texels =
      prt::render::texelRelight(bake.mesh, *occluder, t, bake.transfers[0].recipe.material);
  const prt::haar::EnvironmentCube cube =
      cubeOf(pageData(path("haar_texel_page"))["environments"][0]["haar"]);
  for (std::size_t k = 0; k < turns.size(); ++k) {
    SCOPED_TRACE("turn " + std::to_string(k));
    const prt::Mat3d R = prt::rotationEulerXYZ(turns[k][0], turns[k][1], turns[k][2]);
    const std::vector<prt::Rgb> lib = prt::relight::relightHaar(
        t, prt::haar::turnedLight(cube, 16, terms, R), texels.points.normals,
        bake.transfers[0].recipe.material.diffuseOr({}));
    const double e = relativeError(js["radiance"][k], flat(lib));
    std::cout << "JavaScript vs the library, per-texel Haar relighting, turn " << k
              << ": worst relative error " << e << "\n";
    EXPECT_LT(e, kRelative);
  }
}

TEST(HaarWeb, PrtWebRefusesWhatThePageDoesNotRelight) {
  const std::string page = haarPage();
  if (!page.empty()) GTEST_SKIP() << page;
  const auto refused = [](const std::string& args, const std::string& says) {
    const Result r = prt("web " + args + " -o haar_refused");
    EXPECT_EQ(r.rc, 1) << args;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(path("haar_refused"))) << args;
  };
  ASSERT_EQ(prt(std::string("-q bake ") + kScene +
                " --mode unshadowed --basis haar --resolution 128 --terms 4 -o haar_128.glb")
                .rc,
            0);
  refused("haar_128.glb", "cubes up to 64²");
  ASSERT_EQ(prt("-q light builtin:sky --bands 3 -o haar_sh.json").rc, 0);
  refused("haar.glb --light haar_sh.json", "SH light file");
  refused("haar.glb --bands 3", "--bands");
  refused("haar.glb --encoding l1", "--encoding");
  refused("haar.glb --material phong", "--material");
  ASSERT_EQ(
      prt(std::string("-q bake ") + kScene + " --mode shadowed --samples 16 -o haar_sh.glb").rc, 0);
  refused("haar_sh.glb --terms 100", "--terms");
}

}  // namespace
