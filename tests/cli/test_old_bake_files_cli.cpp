// Bake files written before the one-Transfer redesign (tests/data/bakes/, format versions 1-3)
// render and export as they did: the images prtkit 0.1.0 rendered from them and the
// transport.txt it exported, beside the files. Dense vectors render bit for bit; matrices and
// compressed rows within float rounding (the old renderer applied the identity rotation as a
// rotation, which rounds; today an unturned light is not rotated).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "cli_harness.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/render/camera.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using OldBakeFilesCli = CliTest;

std::string fixture(const std::string& name) {
  return std::string(PRT_SOURCE_DIR) + "/tests/data/bakes/" + name;
}

/// max |a − b| / max |b| over the pixels.
double relativeDifference(const image::Image& a, const image::Image& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  double worst = 0, peak = 0;
  for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, double(std::abs(a.pixels[i][c] - b.pixels[i][c])));
      peak = std::max(peak, double(std::abs(b.pixels[i][c])));
    }
  return worst / std::max(peak, 1e-30);
}

TEST_F(OldBakeFilesCli, RenderAsTheyDid) {
  struct Case {
    std::string bake, options, expected;
    double tolerance;  // relative to the brightest pixel; 0: bit for bit
    std::string camera = "";  // "": the whole mesh framed, as versions 1-3 were rendered
  };
  for (const Case& c : {Case{"v1-vector", "", "v1-vector.render.exr", 0},
                        Case{"v1-vector", "--mode shadowed", "v1-vector.shadowed.render.exr", 0},
                        Case{"v2-matrix", "", "v2-matrix.render.exr", 1e-5},
                        Case{"v3-cpca-vector", "", "v3-cpca-vector.render.exr", 1e-5},
                        Case{"v3-cpca-matrix", "", "v3-cpca-matrix.render.exr", 1e-5},
                        Case{"v4-vector", "", "v4-vector.render.exr", 0,
                             "eye=0,3,6;target=0,0.5,0"}}) {
    SCOPED_TRACE(c.bake + " " + c.options);
    // The camera these were rendered with: the whole mesh framed (the default framed every part
    // until it learnt to leave a ground plane out).
    const Mesh mesh = readBake(fixture(c.bake + ".glb")).mesh;
    render::Framing f;
    f.centre = computeBounds(mesh).centre();
    f.radius = 0;
    for (const Vec3f& p : mesh.positions) f.radius = std::max(f.radius, length(p - f.centre));
    const render::Camera cam = render::frameCamera(f, 40, 30);
    char camera[256];
    std::snprintf(camera, sizeof camera, "--camera 'eye=%.9g,%.9g,%.9g;target=%.9g,%.9g,%.9g' ",
                  cam.eye.x, cam.eye.y, cam.eye.z, cam.target.x, cam.target.y, cam.target.z);
    if (!c.camera.empty()) std::snprintf(camera, sizeof camera, "--camera '%s' ", c.camera.c_str());
    const Result r = prt("-q render '" + fixture(c.bake + ".glb") + "' " + c.options + " " +
                         std::string(camera) + "--light builtin:sky --size 40x30 --spp 1 -o out/now.exr");
    ASSERT_EQ(r.rc, 0) << r.err;
    const image::Image now = image::readImage(path("out/now.exr"));
    const image::Image then = image::readImage(fixture(c.expected));
    const double d = relativeDifference(now, then);
    if (c.tolerance == 0)
      EXPECT_EQ(d, 0.0);
    else
      EXPECT_LT(d, c.tolerance);
    std::printf("%s %s: relative difference %.3g\n", c.bake.c_str(), c.options.c_str(), d);
  }
}

TEST_F(OldBakeFilesCli, ExportAsTheyDid) {
  Result r = prt("-q export '" + fixture("v1-vector.glb") +
                 "' --mode shadowed --layout vertices -o out/s.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "out/s.txt"), slurp(fixture("v1-vector.shadowed.transport.txt")));
  r = prt("-q export '" + fixture("v3-cpca-vector.glb") +
          "' --mode interreflected --channel luminance --layout vertices -o out/c.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "out/c.txt"),
            slurp(fixture("v3-cpca-vector.interreflected.transport.txt")));
}

TEST_F(OldBakeFilesCli, InfoDescribesThem) {
  for (const char* name : {"v1-vector.glb", "v2-matrix.glb", "v3-cpca-vector.glb",
                           "v3-cpca-matrix.glb", "v1-part0.glb", "v4-vector.glb"}) {
    const Result r = prt("info '" + fixture(name) + "'");
    EXPECT_EQ(r.rc, 0) << name << ": " << r.err;
    EXPECT_NE(r.out.find("format version"), std::string::npos) << r.out;
  }
}

}  // namespace
}  // namespace prt
