// Readers that never show garbage (issue 16, items 5, 8, 9, 10), through the real binary: absurd
// but finite values saturate or are refused instead of rendering black or printing inf%; huge
// coordinates are refused naming the file given, before Embree or the page see them; silent
// repairs became errors or warnings; every refusal is one line naming the file the user gave.

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_harness.hpp"
#include "prt/image/image_io.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using ReadersCli = CliTest;

constexpr const char* kSphere = "'builtin:sphere?subdiv=1'";  // 42 vertices

/// The displayed value (PNG decoded to linear, then back to [0, 1] sRGB) at the image centre.
Rgb centre(const std::string& png) {
  const image::Image img = image::readImage(png);
  return img.at(img.width / 2, img.height / 2);
}

/// A 3-band SH light file whose DC term is `dc` (every other coefficient 0).
std::string shLight(const std::string& dc) {
  std::string s = "{\"bands\": 3, \"coefficients\": [[" + dc + ", " + dc + ", " + dc + "]";
  for (int i = 1; i < 9; ++i) s += ", [0, 0, 0]";
  return s + "]}\n";
}

// --- item 5: finite but absurd values ------------------------------------------------------

TEST_F(ReadersCli, AbsurdExposureAndLightRenderWhiteNotBlack) {
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere + " --mode unshadowed --samples 16 -o b.glb").rc,
            0);
  write("l20.json", shLight("1e20"));
  for (const char* tm : {"aces", "reinhard", "clamp"})
    for (const std::string& args :
         {std::string("--exposure 63"), std::string("--exposure 64"),
          std::string("--light l20.json --exposure 0"),
          std::string("--light l20.json --exposure 64")}) {
      SCOPED_TRACE(std::string(tm) + " " + args);
      const Result r = prt("-q render b.glb --size 24x16 --background none --tonemap " +
                           std::string(tm) + " " + args + " -o w.png");
      ASSERT_EQ(r.rc, 0) << r.err;
      const Rgb c = centre(path("w.png"));
      EXPECT_EQ(c.x, 1.0f);
      EXPECT_EQ(c.y, 1.0f);
      EXPECT_EQ(c.z, 1.0f);
    }
}

TEST_F(ReadersCli, OneExposureLimitEverywhere) {
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere + " --mode unshadowed --samples 16 -o b.glb").rc,
            0);
  for (const std::string& verb :
       {std::string("render b.glb -o out/x.png"), std::string("view b.glb --headless"),
        std::string("web b.glb -o out/page"),
        std::string("light builtin:sky -o out/l.json "
                    "--preview out/p.png")})
    for (const char* e : {"64.5", "-65", "1e30", "inf"}) {
      const Result r = prt("-q " + verb + " --exposure " + std::string(e));
      EXPECT_NE(r.rc, 0) << verb << " " << e;
      EXPECT_NE(r.err.find("--exposure"), std::string::npos) << r.err;
      EXPECT_TRUE(fs::is_empty(dir_ / "out")) << verb;
    }
  // At the limit: accepted.
  EXPECT_EQ(prt("-q render b.glb --size 8x6 --exposure -64 -o lo.png").rc, 0);
  const Result w = prt("-q web b.glb --exposure 64 -o page");
  if (w.err.find("assets") == std::string::npos) {
    ASSERT_EQ(w.rc, 0) << w.err;
    // The page clamps a ?exposure= to the library's limit, which the page's constants carry
    // (generated from the C++ at build time; Web.AbsurdExposureAndLightShowWhite clamps one).
    EXPECT_NE(slurp(std::filesystem::path(PRT_BINARY_DIR) / "generated" / "web" / "constants.js")
                  .find("\"maxExposureStops\":64"),
              std::string::npos);
  }
}

TEST_F(ReadersCli, ValidateAndReferenceNeverTabulateGarbage) {
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere + " --mode unshadowed --samples 16 -o b.glb").rc,
            0);
  // An all-NaN environment: nothing to validate against (it validated at 0.000 %).
  image::Image nan(16, 8);
  for (Rgb& p : nan.pixels) p = Rgb(std::nanf(""));
  image::writeImage(path("nan.exr"), nan);
  for (const std::string& verb : {std::string("validate b.glb --light nan.exr --json out/r.json"),
                                  std::string("reference b.glb --light nan.exr -o out/r.json"),
                                  std::string("render b.glb --light nan.exr -o out/x.png"),
                                  std::string("light nan.exr -o out/l.json")})
    expectCleanFailure(verb, "nan.exr: every pixel (128) is NaN or infinite");
  // Some NaN pixels: said, by validate and reference as by render.
  nan.pixels[3] = Rgb(1.0f);
  for (std::size_t i = 4; i < nan.pixels.size(); ++i) nan.pixels[i] = Rgb(0.5f);
  image::writeImage(path("some.exr"), nan);
  for (const std::string& verb :
       {std::string("validate b.glb --light some.exr --reference-samples 8 --vertices 5"),
        std::string("reference b.glb --light some.exr --samples 8 --vertices 5 -o "
                    "r.json")}) {
    const Result r = prt("-q " + verb);
    EXPECT_EQ(r.rc, 0) << r.err;
    EXPECT_NE(r.err.find("some.exr: 3 pixels with NaN/Inf set to 0"),
              std::string::npos)
        << verb << ": " << r.err;
  }
  // A black environment: the relative errors are undefined, said as such.
  image::Image black(16, 8);
  image::writeImage(path("black.exr"), black);
  const Result r =
      prt("-q validate b.glb --light black.exr --reference-samples 8 --vertices 5 --json v.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("n/a"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("0.000%"), std::string::npos) << r.out;
  EXPECT_NE(slurp(dir_ / "v.json").find("\"referenceIsZero\": true"), std::string::npos);
  // Too bright to project: refused naming the file (the message named none).
  std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n";
  for (int i = 0; i < 16 * 8; ++i) hdr += std::string(4, '\xff');
  write("bright.hdr", hdr);
  expectCleanFailure("render b.glb --light bright.hdr -o out/x.png",
                     "bright.hdr: projecting the environment onto SH overflowed");
  expectCleanFailure("validate b.glb --light bright.hdr --json out/v.json",
                     "bright.hdr: projecting the environment onto SH overflowed");
}

// --- item 8: huge coordinates ---------------------------------------------------------------

TEST_F(ReadersCli, HugeCoordinatesAreRefusedNamingTheFileGiven) {
  write("far.obj",
        "v 0 0 0\nv 1e12 0 0\nv 0 1e12 0\nv 0 0 1e12\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
        "f 2 3 4\n");
  ASSERT_EQ(
      prt("-q bake far.obj --mode unshadowed --samples 16 -o far.glb", "PRT_MAX_COORDINATE=1e13 ")
          .rc,
      0);
  fs::rename(dir_ / "far.glb", dir_ / "moved.glb");
  for (const std::string& verb :
       {std::string("render moved.glb -o out/x.png"), std::string("info moved.glb"),
        std::string("web moved.glb -o out/page"), std::string("view moved.glb --headless"),
        std::string("validate moved.glb --light builtin:sky"),
        std::string("compress moved.glb -o out/c.glb")}) {
    SCOPED_TRACE(verb);
    const Result r = prt("-q " + verb);
    EXPECT_NE(r.rc, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("moved.glb: vertex "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("PRT_MAX_COORDINATE"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("far.obj"), std::string::npos) << r.err;  // the recorded source
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_empty(dir_ / "out"));
  }
}

TEST_F(ReadersCli, CoordinateOverrideStopsWhereEmbreeStops) {
  write("far.obj",
        "v 0 0 0\nv 1e17 0 0\nv 0 1e17 0\nv 0 0 1e17\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
        "f 2 3 4\n");
  // Past the ray tracer's range the override itself is refused, at once, whatever the verb
  // (prt render aborted inside Embree: ray.valid()).
  for (const char* verb : {"bake far.obj --mode unshadowed --samples 16 -o out/f.glb",
                           "render missing.glb -o out/x.png", "info far.obj"})
    for (const char* v : {"1e18", "1e30"}) {
      SCOPED_TRACE(std::string(verb) + " " + v);
      const Result r = prt(std::string("-q ") + verb, std::string("PRT_MAX_COORDINATE=") + v + " ");
      EXPECT_EQ(r.rc, 1) << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_NE(r.err.find("PRT_MAX_COORDINATE: "), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("is beyond the ray tracer's range (at most 1e+17"), std::string::npos)
          << r.err;
      EXPECT_TRUE(fs::is_empty(dir_ / "out"));
    }
  // At the cap everything runs to the end (no abort), and the page's framing stays finite.
  const std::string cap = "PRT_MAX_COORDINATE=1e17 ";
  ASSERT_EQ(prt("-q bake far.obj --mode shadowed --samples 16 -o f.glb", cap).rc, 0);
  const Result r = prt("-q render f.glb --size 16x12 -o f.png", cap);
  EXPECT_EQ(r.rc, 0) << r.err;
  const Result w = prt("-q web f.glb -o page", cap);
  if (w.err.find("assets") == std::string::npos) {
    ASSERT_EQ(w.rc, 0) << w.err;
    const std::string js = slurp(dir_ / "page" / "prt-data.js");
    // window.PRT_DATA = {...}; — valid JSON, the framing's numbers finite (prt web writes a
    // non-finite one as null, which would fail here).
    const nlohmann::json data =
        nlohmann::json::parse(js.substr(js.find('{'), js.rfind('}') - js.find('{') + 1));
    const nlohmann::json& framing = data["view"]["framing"];
    ASSERT_TRUE(framing["radius"].is_number()) << framing.dump();
    EXPECT_TRUE(std::isfinite(framing["radius"].get<double>())) << framing.dump();
    for (const auto& x : framing["centre"]) EXPECT_TRUE(x.is_number()) << framing.dump();
  }
}

// --- item 9: silent repairs -----------------------------------------------------------------

TEST_F(ReadersCli, SilentRepairsAreRefusedByName) {
  // MTL numbers tinyobjloader read as 0.
  write("m.obj", "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("m.mtl", "newmtl a\nKd nan 0.5 0.5\n");
  expectCleanFailure("bake m.obj --mode unshadowed --samples 16 -o out/b.glb",
                     "m.mtl: line 2: Kd 'nan'");
  write("m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs nan\n");
  expectCleanFailure("bake m.obj --mode unshadowed --samples 16 -o out/b.glb",
                     "m.mtl: line 4: Ns 'nan'");
  // A material key given twice.
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere +
                " --mode unshadowed --transfer matrix "
                "--bands 2 --samples 16 -o g.glb")
                .rc,
            0);
  expectCleanFailure("render g.glb --material 'phong?exponent=16&exponent=32' -o out/x.png",
                     "parameter 'exponent' is given twice");
  // A FIFO with no writer: refused at once instead of hanging in open() (timeout(1) turns a
  // regression into a failure, exit 124, instead of a hung test).
  ASSERT_EQ(::mkfifo(path("pipe.json").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo(path("pipe.ply").c_str(), 0600), 0);
  for (const char* verb : {"render g.glb --light pipe.json -o out/x.png", "info pipe.json",
                           "bake pipe.ply --mode unshadowed -o out/b.glb"}) {
    SCOPED_TRACE(verb);
    const Result r = prt(std::string("-q ") + verb, "timeout 20 ");
    EXPECT_EQ(r.rc, 1) << r.err;
    EXPECT_NE(r.err.find(": is not a regular file (a pipe, device or socket)"), std::string::npos)
        << r.err;
  }
  // PRT_MAX_VERTICES applies to bakes and builtin scenes as to mesh files.
  {
    const Result r = prt("-q render g.glb -o out/x.png", "PRT_MAX_VERTICES=10 ");
    EXPECT_EQ(r.rc, 1);
    EXPECT_NE(r.err.find("g.glb: vertex count 42 exceeds the limit of 10 (PRT_MAX_VERTICES)"),
              std::string::npos)
        << r.err;
    const Result b = prt(std::string("-q bake ") + kSphere + " --mode unshadowed -o out/b.glb",
                         "PRT_MAX_VERTICES=10 ");
    EXPECT_EQ(b.rc, 1);
    EXPECT_NE(b.err.find("vertex count 42 exceeds the limit of 10 (PRT_MAX_VERTICES)"),
              std::string::npos)
        << b.err;
    EXPECT_TRUE(fs::is_empty(dir_ / "out"));
  }
}

// --- item 10: messages that name the file -----------------------------------------------------

TEST_F(ReadersCli, MessagesNameTheFileTheUserGave) {
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere + " --mode unshadowed --samples 16 -o b.glb").rc,
            0);
  // prt web into a place that cannot hold a folder: said before any work, naming it.
  write("notes.txt", "x");
  const Result w = prt("-q web b.glb -o notes.txt/page");
  if (w.err.find("assets") == std::string::npos) {
    EXPECT_EQ(w.rc, 1);
    EXPECT_NE(w.err.find("prt web: error: notes.txt/page: folder cannot be created: "),
              std::string::npos)
        << w.err;
    EXPECT_NE(w.err.find("notes.txt is not a folder"), std::string::npos) << w.err;
    EXPECT_EQ(w.err.find("reading the command line"), std::string::npos) << w.err;
    const Result p = prt("-q web b.glb -o /proc/prt-no-such/page");
    EXPECT_EQ(p.rc, 1);
    EXPECT_NE(p.err.find("/proc/prt-no-such/page: folder cannot be written: /proc"),
              std::string::npos)
        << p.err;
  }
  // merge: the compressed piece is the one named, whichever position it has.
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere +
                " --mode unshadowed --samples 16 --range 0:21 -o p1.glb")
                .rc,
            0);
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere +
                " --mode unshadowed --samples 16 --range 21:42 -o p2.glb")
                .rc,
            0);
  // A whole bake compressed (a piece is refused by compress itself) is still no merge input.
  ASSERT_EQ(prt("-q compress b.glb --clusters 2 --pca 1 -o c1.glb").rc, 0);
  expectCleanFailure("merge c1.glb p2.glb -o out/m.glb", "c1.glb: holds compressed transfer");
  expectCleanFailure("merge p2.glb c1.glb -o out/m.glb", "c1.glb: holds compressed transfer");
}

}  // namespace
}  // namespace prt
