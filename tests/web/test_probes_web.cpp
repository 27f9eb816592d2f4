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
//     and the frame matches prt render --object of the same ball;
//   * three.js r187's own LightProbeGridWebGL, filled from prt export --format probe-grid
//     (JSON and .glb), shades every pixel of white spheres as the library's relit grid does.
// Each test skips, saying why, where node, chromium or the built page is missing.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli/cli_harness.hpp"
#include "prt/core/base64.hpp"
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
  const std::string n = nodeForPageSources(&why);
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

// prt export --format probe-grid --engine threejs drawn by three.js's own LightProbeGridWebGL
// (r187; docs/probes.md "Exports"): the page tests/web/probe_grid builds the grid as an app
// would — LightProbeGridWebGL(width, height, depth, nx, ny, nz) at `position`, the atlas as an
// RGBA float Data3DTexture, linearly filtered — from the JSON and from the .glb (read by three's
// GLTFLoader), and renders white Lambert spheres lit by it alone into a float target with the
// pixels' world positions and normals. Each pixel must be what three's shader is meant to give
// from the library's relit grid: ρ E(n)/π (three's max(·, 0)) of the trilinear blend of the
// probes at p + n·s/2 — three samples half a cell out along the normal
// (lightprobes_pars_fragment), where prt render samples at p, so the frame is checked against
// the library pixel by pixel rather than against prt render's. The same spheres under the
// atlas shifted by one cell, and under r184–r186's corner convention (size (n − 1)·s), must fail.

/// A float RGBA frame's linear RGB against `want` at the covered pixels: the RMS of the error
/// over the mean of `want`.
double relativeRms(const std::vector<float>& frame, const std::vector<prt::Rgb>& want,
                   const std::vector<std::size_t>& covered) {
  double sum = 0, mean = 0;
  for (std::size_t k = 0; k < covered.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const double d = frame[4 * covered[k] + std::size_t(c)] - want[k][c];
      sum += d * d;
      mean += want[k][c];
    }
  const double n = 3.0 * double(covered.size());
  return std::sqrt(sum / n) / std::max(mean / n, 1e-30);
}

std::vector<float> floatsOf(const std::string& b64) {
  const std::vector<unsigned char> b = unbase64(b64);
  std::vector<float> f(b.size() / 4);
  std::memcpy(f.data(), b.data(), f.size() * 4);
  return f;
}

TEST(ProbesWeb, ThreeLightProbeGridDrawsTheExport) {
  PRT_REQUIRE_CHROMIUM();
  if (which({"node", "nodejs"}).empty()) GTEST_SKIP() << "no node here (apt-get install nodejs)";
  const fs::path modules = kSource / "web/node_modules";
  if (!fs::exists(modules / "three/examples/jsm/lighting/LightProbeGridWebGL.js") ||
      !fs::exists(modules / ".bin/esbuild"))
    GTEST_SKIP() << "web/node_modules lacks three r187's LightProbeGridWebGL or esbuild "
                    "(run scripts/setup.sh)";
  probeBake();
  for (const char* out : {"grid.json", "grid.glb"}) {
    const Result x = prt(std::string("-q export probes.glb --format probe-grid --engine threejs "
                                     "--light builtin:sky -o ") +
                         out);
    ASSERT_EQ(x.rc, 0) << x.err;
  }
  // The page, bundled with three.js from web/node_modules as an app bundles it.
  const fs::path page = scratch() / "probe_grid_page";
  fs::create_directories(page);
  fs::copy_file(kSource / "tests/web/probe_grid/index.html", page / "index.html",
                fs::copy_options::overwrite_existing);
  const Result b =
      shell("NODE_PATH='" + modules.string() + "' '" + (modules / ".bin/esbuild").string() + "' '" +
            (kSource / "tests/web/probe_grid/page.mjs").string() +
            "' --bundle --format=iife --log-level=warning --outfile='" +
            (page / "page.js").string() + "'");
  ASSERT_EQ(b.rc, 0) << b.out << b.err;

  const Json grid = Json::parse(prt::testing::slurp(scratch() / "grid.json"));
  const Json& g = grid["lightProbeGrid"];
  const prt::relight::ProbeLighting lib = libraryLighting("builtin:sky", {0, 0, 0});
  ASSERT_EQ(lib.bands, 3);
  // The mistakes the check must catch: every probe moved one cell along x (the atlas' texel x
  // takes probe x + 1's, the last repeated), and r184–r186's box through the probes, not
  // around their cells.
  Json shifted = grid;
  {
    std::vector<float> atlas = floatsOf(g["atlas"]["data"].get<std::string>());
    const int nx = g["atlas"]["size"][0];
    for (std::size_t row = 0; row < atlas.size() / 4 / std::size_t(nx); ++row)
      for (int x = 0; x + 1 < nx; ++x)
        std::memcpy(&atlas[(row * std::size_t(nx) + std::size_t(x)) * 4],
                    &atlas[(row * std::size_t(nx) + std::size_t(x) + 1) * 4], 16);
    shifted["lightProbeGrid"]["atlas"]["data"] = prt::base64(
        std::string_view(reinterpret_cast<const char*>(atlas.data()), atlas.size() * 4));
  }
  Json corners = grid;
  for (const auto& [key, axis] : {std::pair{"width", 0}, {"height", 1}, {"depth", 2}})
    corners["lightProbeGrid"][key] = g[key].get<double>() *
                                     (g["resolution"][axis].get<double>() - 1) /
                                     g["resolution"][axis].get<double>();
  const std::string glb = prt::testing::slurp(scratch() / "grid.glb");
  // Looking into the box through its open side at four balls: by the open side, deep inside,
  // low by the red wall, high by the green one.
  const Json input = {
      {"width", 256},
      {"height", 192},
      {"camera", {{"eye", {0, 1, 3.4}}, {"target", {0, 1, 0}}, {"up", {0, 1, 0}}, {"fov", 45}}},
      {"radius", 0.2},
      {"spheres", {{-0.45, 0.9, 0.45}, {0.45, 1.3, -0.5}, {-0.5, 0.45, 0.0}, {0.5, 1.55, 0.1}}},
      {"grids",
       {{{"name", "json"}, {"json", grid}},
        {{"name", "glb"}, {"glb", prt::base64(glb)}},
        {{"name", "shifted"}, {"json", shifted}},
        {{"name", "corners"}, {"json", corners}}}}};
  std::ofstream(page / "grid-data.js") << "window.PRT_PROBE_GRID = " << input.dump() << ";\n";
  std::string log;
  const std::string json = runPage(page.string(), "", &log);
  ASSERT_NE(json.find("\"ok\":true"), std::string::npos) << json.substr(0, 600) << "\n" << log;
  const Json j = Json::parse(json);
  EXPECT_EQ(j["three"], "187");
  const std::vector<float> position = floatsOf(j["position"]), normal = floatsOf(j["normal"]);
  // The library's shading of every covered pixel, at three's sample point and (to show that
  // the point matters) at the pixel itself.
  const prt::Vec3f s = lib.grid.spacing;
  std::vector<std::size_t> covered;
  std::vector<prt::Rgb> want, atPixel;
  std::vector<prt::Rgb> sh(lib.coeffs());
  const auto shade = [&](const prt::Vec3f& at, const prt::Vec3f& n) {
    prt::relight::sampleProbes(lib, at, sh.data());
    const prt::Rgb c = prt::relight::shadeDiffuse(sh.data(), lib.bands, n, prt::Rgb(1.0f));
    return prt::Rgb(std::max(c.x, 0.0f), std::max(c.y, 0.0f), std::max(c.z, 0.0f));
  };
  for (std::size_t i = 0; i < position.size() / 4; ++i) {
    if (position[4 * i + 3] < 0.5f) continue;
    const prt::Vec3f p(position[4 * i], position[4 * i + 1], position[4 * i + 2]);
    const prt::Vec3f n(normal[4 * i], normal[4 * i + 1], normal[4 * i + 2]);
    covered.push_back(i);
    want.push_back(shade(p + n * s * 0.5f, n));
    atPixel.push_back(shade(p, n));
  }
  ASSERT_GT(covered.size(), 2000u) << "the spheres cover too few pixels";
  std::map<std::string, double> error;
  for (const char* name : {"json", "glb", "shifted", "corners"})
    error[name] = relativeRms(floatsOf(j["frames"][name]), want, covered);
  const double pixelPoint = relativeRms(floatsOf(j["frames"]["json"]), atPixel, covered);
  std::cout << "three.js r" << j["three"].get<std::string>() << " LightProbeGridWebGL from prt "
            << "export, " << covered.size() << " pixels, relative RMS error against the library: "
            << "JSON " << error["json"] << ", .glb " << error["glb"] << "; the library at the "
            << "pixel (no normal offset) " << pixelPoint << "; atlas shifted one cell "
            << error["shifted"] << ", r184-r186 corners " << error["corners"] << "\n";
  // The harness renders with SwiftShader, which filters float textures in float (1e-6
  // measured); 1e-3 leaves room for fixed-point filter weights. The mistakes give 0.17–0.7.
  constexpr double kGrid = 1e-3, kWrong = 0.05;
  EXPECT_LT(error["json"], kGrid) << "OES_texture_float_linear: " << j["floatLinear"];
  EXPECT_EQ(j["frames"]["glb"], j["frames"]["json"]) << "the .glb draws another grid";
  EXPECT_GT(error["shifted"], kWrong);
  EXPECT_GT(error["corners"], kWrong);
  EXPECT_GT(pixelPoint, kWrong) << "three's half-cell step along the normal is not seen";
}

}  // namespace
