// Probe bakes in the browser (issue 32; docs/probes.md, docs/web.md "Probe bakes", docs/three.md
// "Probe grids"), against the library on the same bake and light:
//   * the JavaScript relighting — the page's reader and relighter, and prtkit-three's
//     ProbeGridLighting (incidentAt, shadeAt, updateLightProbe) — gives the incident SH at
//     points inside, on and outside the grid and the diffuse shading of normals there as
//     relight::relightProbes / sampleProbes / shadeDiffuse do, to 1e-5 relative, and its export
//     (irradianceVolume) is prt export --format probe-grid's (under node,
//     tests/web/probes/probe_check.mjs);
//   * prt web draws a probe bake: its ball reports the library's incident SH at its centre, is
//     darker deep in the box than by its open side, redder by the red wall than by the green one,
//     and the frame matches prt render --object of the same ball.
// Each test skips, saying why, where node, chromium or the built page is missing.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "cli/cli_harness.hpp"
#include "prt/core/json.hpp"
#include "prt/image/color.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/sh/rotate.hpp"
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

/// node with the page's dependencies, or "" (and why in `why`).
std::string node(std::string* why) {
  const std::string n = which({"node", "nodejs"});
  if (n.empty())
    *why = "no node here (apt-get install nodejs)";
  else if (!fs::exists(kSource / "web/node_modules/three/package.json"))
    *why = "web/node_modules missing (run scripts/setup.sh)";
  else if (!fs::exists(kGenerated / "constants.js"))
    *why = kGenerated.string() + "/constants.js is not built (ninja prt_web_assets)";
  else
    return n;
  return "";
}

/// A 4 x 4 x 4 grid in the Cornell box (inter-reflected, RGB, 3 bands) and the sky as a light
/// file, written once.
void probeBake() {
  static const bool done = [] {
    // 512 samples: the green wall's pull on the ball (green/red of its two sides, below) is
    // 1.26 converged (2,048 samples) and moves by ±0.05 with the noise of 64.
    Result r = prt("-q probes builtin:cornell --grid 4x4x4 --samples 512 -o probes.glb");
    EXPECT_EQ(r.rc, 0) << r.err;
    r = prt("-q light builtin:sky --bands 3 -o probes_sky.json");
    EXPECT_EQ(r.rc, 0) << r.err;
    return true;
  }();
  (void)done;
}

/// The library's relit grid of probes.glb under `light` (a spec) turned by Euler degrees.
prt::relight::ProbeLighting libraryLighting(const std::string& light,
                                            std::array<double, 3> rotate) {
  const prt::BakeFile bake = prt::readBake(path("probes.glb"));
  const prt::BakedTransfer& t = prt::pickTransfer(bake, {}, {}, "probes.glb");
  const prt::io::Lighting l = prt::io::loadLighting(light, t.transfer.bands());
  prt::sh::RgbSh turned = l.coefficients;
  prt::sh::Rotation(turned.bands, prt::rotationEulerXYZ(rotate[0], rotate[1], rotate[2]))
      .apply(l.coefficients.c.data(), turned.c.data());
  return prt::relight::relightProbes(t.transfer, turned);
}

std::vector<prt::Rgb> libraryIncident(const prt::relight::ProbeLighting& l, const Json& p) {
  std::vector<prt::Rgb> sh(l.coeffs());
  prt::relight::sampleProbes(l, prt::Vec3f(p[0].get<float>(), p[1].get<float>(), p[2].get<float>()),
                             sh.data());
  return sh;
}

/// max |js − c++| over max |c++|: the error relative to the vector's (or colour's) scale.
double relativeError(const Json& js, const std::vector<float>& cpp) {
  EXPECT_EQ(js.size(), cpp.size());
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < cpp.size() && i < js.size(); ++i) {
    err = std::max(err, std::abs(js[i].get<double>() - cpp[i]));
    scale = std::max(scale, double(std::abs(cpp[i])));
  }
  return err / std::max(scale, 1e-30);
}

std::vector<float> flat(const std::vector<prt::Rgb>& v, bool threeBasis = false) {
  std::vector<float> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    // three.js's SH basis is ours without the Condon-Shortley phase: odd m change sign.
    const float s = threeBasis && (i == 1 || i == 3 || i == 5 || i == 7) ? -1.0f : 1.0f;
    for (int c = 0; c < 3; ++c) out.push_back(s * v[i][c]);
  }
  return out;
}

constexpr double kRelative = 1e-5;

TEST(ProbesWeb, JavaScriptRelightsTheGridAsTheLibrary) {
  std::string why;
  const std::string n = node(&why);
  if (n.empty()) GTEST_SKIP() << why;
  probeBake();
  const std::array<double, 3> rotate{20, -35, 10};
  // Inside a cell, on a probe, on the grid's far corner, outside (clamped to the nearest face),
  // and beyond a corner.
  const Json query = {{"rotate", {rotate[0], rotate[1], rotate[2]}},
                      {"points",
                       {{0.1, 0.3, -0.2},
                        {-0.25, 0.75, 0.25},
                        {0.75, 1.75, 0.75},
                        {0.2, 1.1, 3.0},
                        {-4.0, -1.0, 2.5}}},
                      {"normals", {{0, 1, 0}, {0.6, 0, 0.8}, {-1, 0, 0}, {0, -0.6, -0.8}}},
                      {"albedo", {0.8, 0.5, 0.25}}};
  std::ofstream(path("probe_query.json")) << query.dump();
  const Result r = shell("'" + n + "' '" + (kSource / "tests/web/probes/probe_check.mjs").string() +
                         "' '" + kGenerated.string() + "' '" + path("probes.glb") + "' '" +
                         path("probes_sky.json") + "' '" + path("probe_query.json") + "'");
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  const Json js = Json::parse(r.out);
  const prt::relight::ProbeLighting lib = libraryLighting(path("probes_sky.json"), rotate);
  ASSERT_EQ(js["page"]["bands"], lib.bands);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(js["page"]["grid"]["count"][a], lib.grid.count[a]);
    EXPECT_EQ(js["page"]["grid"]["origin"][a].get<float>(), lib.grid.origin[a]);
    EXPECT_EQ(js["page"]["grid"]["spacing"][a].get<float>(), lib.grid.spacing[a]);
  }
  const prt::Rgb albedo(0.8f, 0.5f, 0.25f);
  double worst = 0;
  for (std::size_t p = 0; p < query["points"].size(); ++p) {
    SCOPED_TRACE("point " + query["points"][p].dump());
    const std::vector<prt::Rgb> sh = libraryIncident(lib, query["points"][p]);
    for (const char* who : {"page", "three"}) {
      SCOPED_TRACE(who);
      const double e = relativeError(js[who]["incident"][p], flat(sh));
      EXPECT_LT(e, kRelative);
      worst = std::max(worst, e);
      for (std::size_t k = 0; k < query["normals"].size(); ++k) {
        const Json& nj = query["normals"][k];
        const prt::Vec3f nrm(nj[0].get<float>(), nj[1].get<float>(), nj[2].get<float>());
        const prt::Rgb c = prt::relight::shadeDiffuse(sh.data(), lib.bands, nrm, albedo);
        const double ec = relativeError(js[who]["shade"][p][k], {c.x, c.y, c.z});
        EXPECT_LT(ec, kRelative) << "normal " << nj.dump();
        worst = std::max(worst, ec);
      }
    }
    // A LightProbe set at the point holds the same light in three.js's basis.
    EXPECT_LT(relativeError(js["three"]["lightProbe"][p], flat(sh, true)), kRelative);
  }
  std::cout << "JavaScript vs the library, incident SH and shading: worst relative error " << worst
            << "\n";
  // The exported grid is prt export --format probe-grid's (three.js) under the same light and
  // rotation, value for value, and every probe's position.
  const Result x =
      prt("-q export probes.glb --format probe-grid --light probes_sky.json --rotate 20,-35,10 "
          "-o probe_grid.json");
  ASSERT_EQ(x.rc, 0) << x.err;
  const Json cpp = Json::parse(prt::testing::slurp(scratch() / "probe_grid.json"));
  const Json& v = js["three"]["volume"];
  for (const char* key : {"engine", "coefficients"}) EXPECT_EQ(v[key], cpp[key]) << key;
  EXPECT_EQ(v["asset"]["format"], cpp["asset"]["format"]);
  EXPECT_EQ(v["light"], "probes_sky.json");
  EXPECT_EQ(v["grid"], cpp["grid"]);
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(v["rotateDegrees"][a].get<double>(), cpp["rotateDegrees"][a].get<double>(), 1e-9);
  const Json& lg = v["lightProbeGrid"];
  const Json& cg = cpp["lightProbeGrid"];
  EXPECT_EQ(lg["resolution"], cg["resolution"]);
  for (const char* key : {"width", "height", "depth"})
    EXPECT_NEAR(lg[key].get<double>(), cg[key].get<double>(), 1e-6) << key;
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(lg["position"][a].get<double>(), cg["position"][a].get<double>(), 1e-6);
  EXPECT_EQ(lg["atlas"]["size"], cg["atlas"]["size"]);
  const auto floats = [](const std::string& b64) {
    const std::vector<unsigned char> b = unbase64(b64);
    std::vector<float> f(b.size() / 4);
    std::memcpy(f.data(), b.data(), f.size() * 4);
    return f;
  };
  const std::vector<float> atlas = floats(cg["atlas"]["data"].get<std::string>());
  EXPECT_LT(relativeError(Json(floats(lg["atlas"]["data"].get<std::string>())), atlas), kRelative);
  EXPECT_LT(relativeError(Json(floats(js["three"]["atlas"].get<std::string>())), atlas), kRelative);
  ASSERT_EQ(v["probes"].size(), cpp["probes"].size());
  ASSERT_EQ(v["positions"].size(), 3 * lib.grid.probes());
  double volumeError = 0;
  for (std::size_t p = 0; p < lib.grid.probes(); ++p) {
    const prt::Vec3f at = lib.grid.position(p);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(v["positions"][3 * p + a].get<double>(), at[a], 1e-6);
    const auto probe = [&](const Json& all) {
      return Json(std::vector<Json>(all.begin() + 27 * p, all.begin() + 27 * (p + 1)));
    };
    std::vector<float> want;
    for (const Json& c : probe(cpp["probes"])) want.push_back(c.get<float>());
    volumeError = std::max(volumeError, relativeError(probe(v["probes"]), want));
    // ... and the library's relit probe in three.js's basis.
    const std::vector<prt::Rgb> sh(lib.probe(p), lib.probe(p) + lib.coeffs());
    volumeError = std::max(volumeError, relativeError(probe(v["probes"]), flat(sh, true)));
  }
  EXPECT_LT(volumeError, kRelative);
  EXPECT_TRUE(js["three"]["dressed"].get<bool>());
}

#define PRT_REQUIRE_CHROMIUM()                                                             \
  do {                                                                                     \
    if (chromium().empty()) GTEST_SKIP() << "no chromium here (apt-get install chromium)"; \
  } while (0)

/// The page's ?screenshot of the probe bake with the ball at `at`: its report.
Json probeFrame(const std::string& dir, const std::string& at, const std::string& extra = "") {
  std::string log;
  const std::string json =
      runPage(dir, "screenshot&size=320x240&exposure=-4&tonemap=clamp&at=" + at + extra, &log);
  EXPECT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 400) << "\n" << log;
  return json.empty() ? Json::object() : Json::parse(json);
}

/// The mean colour of the ball, linear (the displayed sRGB decoded): over the disc of 0.8 times
/// its radius about its centre, or (side −1, +1) over the part of the disc of 0.9 times its
/// radius left or right of half its radius — the limbs that face −x and +x, seen from the front.
prt::Rgb ballColour(const Json& frame, int side = 0) {
  const std::vector<unsigned char> rgb = unbase64(frame["rgb"].get<std::string>());
  const double cx = frame["probes"]["pixel"][0], cy = frame["probes"]["pixel"][1];
  const double radius = frame["probes"]["pixelRadius"];
  const double r = (side ? 0.9 : 0.8) * radius;
  const int w = frame["width"], h = frame["height"];
  prt::Rgb sum(0.0f);
  int n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
      if (std::hypot(dx, dy) < r && side * dx >= (side ? 0.5 * radius : 0)) {
        for (int c = 0; c < 3; ++c)
          sum[c] += prt::image::srgbToLinear(rgb[3 * (y * w + x) + c] / 255.0f);
        ++n;
      }
    }
  EXPECT_GT(n, 20) << "the ball covers no pixels";
  return n ? sum / float(n) : sum;
}

TEST(ProbesWeb, PageDrawsTheGridAndMovesTheBallThroughIt) {
  PRT_REQUIRE_CHROMIUM();
  probeBake();
  // Looking into the box through its open side.
  const std::string camera = "eye=0,1,3.4;target=0,1,0;up=0,1,0;fov=45";
  Result r = prt("-q web probes.glb --light builtin:sky --camera '" + camera + "' -o probes_page");
  if (r.rc != 0 && r.err.find("assets") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string dir = path("probes_page");
  const prt::relight::ProbeLighting lib = libraryLighting("builtin:sky", {0, 0, 0});
  // By the open side and the red wall; deep inside; by the green wall.
  const std::string open = "-0.45,0.9,0.45", deep = "0.45,1.3,-0.5", red = "-0.5,0.9,0",
                    green = "0.5,0.9,0";
  std::vector<Json> frames;
  for (const std::string& at : {open, deep, red, green}) frames.push_back(probeFrame(dir, at));
  for (const Json& f : frames) ASSERT_TRUE(f.contains("probes")) << f.dump().substr(0, 300);
  // The light at the ball's centre, relit in the browser, is the library's.
  for (const Json& f : frames)
    EXPECT_LT(relativeError(f["probes"]["incident"], flat(libraryIncident(lib, f["probes"]["at"]))),
              kRelative)
        << f["probes"]["at"].dump();
  // The ball darkens deep in the box, and the side facing a coloured wall takes its colour:
  // red over green on its left by the red wall (−x), green over red on its right by the green one.
  const auto mean = [](const prt::Rgb& x) { return (x.x + x.y + x.z) / 3; };
  const double lit = mean(ballColour(frames[0])), dark = mean(ballColour(frames[1]));
  const prt::Rgb redL = ballColour(frames[2], -1), redR = ballColour(frames[2], 1);
  const prt::Rgb greenL = ballColour(frames[3], -1), greenR = ballColour(frames[3], 1);
  const double towardRed = (redL.x / redL.y) / (redR.x / redR.y);
  const double towardGreen = (greenR.y / greenR.x) / (greenL.y / greenL.x);
  std::cout << "the ball by the open side " << lit << ", deep in the box " << dark
            << "; red/green of its side toward the red wall over the other " << towardRed
            << ", green/red toward the green wall over the other " << towardGreen << "\n";
  EXPECT_GT(lit, 3 * dark) << "the ball does not darken away from the open side";
  EXPECT_GT(towardRed, 1.2) << "the ball does not pick up the red wall's colour";
  EXPECT_GT(towardGreen, 1.2) << "the ball does not pick up the green wall's colour";
  // The frame is prt render's of the same ball (builtin:sphere, a fifth of the grid across).
  r = prt("-q render probes.glb --light builtin:sky --object builtin:sphere --at " + open +
          " --camera '" + camera +
          "' --exposure -4 --tonemap clamp --size 320x240 -o probes_ball.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  const double e =
      displayedRmse(unbase64(frames[0]["rgb"].get<std::string>()), path("probes_ball.png"));
  std::cout << "page vs prt render, probe bake with a ball: RMSE " << e << "\n";
  EXPECT_LT(e, kMatch);
  // ... which the ball elsewhere is not (the comparison can fail).
  EXPECT_GT(displayedRmse(unbase64(frames[1]["rgb"].get<std::string>()), path("probes_ball.png")),
            e + 0.004);
  // The probes show as points on request, and the frame changes.
  const Json shown = probeFrame(dir, open, "&probes");
  EXPECT_NE(shown.value("rgb", ""), frames[0].value("rgb", ""));
}

// The three.js example of a prt web folder (prtkit-three, built as an app uses it) draws a probe
// bake: its meshes lit through the grid (the three.js host's radiance stage) and a ball under the
// LightProbe the grid sets at it.
TEST(ProbesWeb, ThreeExampleDrawsAProbeBake) {
  PRT_REQUIRE_CHROMIUM();
  probeBake();
  const Result r = prt("-q web probes.glb --light builtin:sky -o probes_three");
  if (r.rc != 0 && r.err.find("assets") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.rc, 0) << r.err;
  if (!fs::exists(path("probes_three/three/example.js")))
    GTEST_SKIP() << "the three.js example is not built (node or web/node_modules missing)";
  std::string log;
  const std::string json = runPage(path("probes_three/three"), "screenshot&size=320x240", &log);
  ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 400) << "\n" << log;
  const Json j = Json::parse(json);
  EXPECT_EQ(j["meshes"], 7);  // the Cornell box's parts
  // Lit: most of the frame is neither black nor one colour.
  const std::vector<unsigned char> rgb = unbase64(j["rgb"].get<std::string>());
  std::size_t lit = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) lit += rgb[i] + rgb[i + 1] + rgb[i + 2] > 60;
  EXPECT_GT(lit, rgb.size() / 3 / 2) << "the box is not lit";
}

}  // namespace
