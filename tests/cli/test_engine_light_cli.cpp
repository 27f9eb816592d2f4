// `prt light --format threejs|gltf-ibl|cmgen|unity` (io/engine_light.hpp): each file against
// the engine's own code or tool. Filament's cmgen (Debian's libfilament-tools) runs here on the
// same HDR; Unity's and Babylon.js's evaluation is written out below from their shader and basis
// code; three.js's LightProbeGenerator runs under node in tests/web (test_engine_light_web.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "prt/core/json.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/light_file.hpp"
#include "prt/sh/convolve.hpp"

namespace prt::testing {
namespace {

bool have(const char* tool) {
  return std::system((std::string("command -v ") + tool + " > /dev/null 2>&1").c_str()) == 0;
}

/// A lat-long HDR with a red light toward +X, green up, blue toward +Z and a white one off every
/// axis: every coefficient of three bands is non-zero and a swapped axis or sign shows.
void writeBlobs(const fs::path& path, int w) {
  image::Image img(w, w / 2);
  const auto blob = [](const Vec3d& d, Vec3d a, double k) {
    a = a * (1 / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z));
    return std::exp(k * (d.x * a.x + d.y * a.y + d.z * a.z - 1));
  };
  for (int y = 0; y < w / 2; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec3d d = envmap::latLongDirection(w, w / 2, x, y);
      const double white = 3 * blob(d, {0.6, 0.3, -0.74}, 5);
      img.at(x, y) = Rgb(static_cast<float>(0.05 + 4 * blob(d, {1, 0, 0}, 4) + white),
                         static_cast<float>(0.05 + 4 * blob(d, {0, 1, 0}, 4) + white),
                         static_cast<float>(0.05 + 4 * blob(d, {0, 0, 1}, 4) + white));
    }
  image::writeImage(path.string(), img);
}

/// The rows "( r, g, b); // Llm" of a cmgen sh.txt.
std::vector<Rgbd> readShTxt(const std::string& text) {
  std::vector<Rgbd> rows;
  static const std::regex row(R"(\(\s*(\S+),\s*(\S+),\s*(\S+)\);\s*//\s*L(\d+)(-?\d+))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), row); it != std::sregex_iterator();
       ++it)
    rows.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])});
  return rows;
}

class EngineLightCli : public CliTest {};

TEST_F(EngineLightCli, CmgenMatchesFilamentsCmgenOnTheSameHdr) {
  writeBlobs(dir_ / "env.hdr", 1024);
  const Result r = prt("-q light env.hdr --format cmgen --bands 3 -o sh.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::vector<Rgbd> mine = readShTxt(slurp(dir_ / "sh.txt"));
  ASSERT_EQ(mine.size(), 9u) << slurp(dir_ / "sh.txt");
  if (!have("cmgen")) GTEST_SKIP() << "no cmgen here (apt-get install libfilament-tools)";
  const std::string cmd = "cd '" + dir_.string() +
                          "' && cmgen --sh=3 --sh-output=cmgen.txt -w no -q env.hdr > cmgen.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir_ / "cmgen.log");
  const std::vector<Rgbd> theirs = readShTxt(slurp(dir_ / "cmgen.txt"));
  ASSERT_EQ(theirs.size(), 9u) << slurp(dir_ / "cmgen.txt");
  // cmgen resamples the image onto a 256² cube first (bilinear): the coefficients agree to
  // about 1% of the mean; a sign or an axis wrong moves one by a third of it or more.
  const double dc = theirs[0].x;
  for (std::size_t k = 0; k < 9; ++k)
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(mine[k][ch], theirs[k][ch], 0.025 * dc) << "L" << k << " channel " << ch;
}

/// Our 3-band radiance of the same HDR, read back from our own JSON.
sh::RgbSh ourLight(const std::string& dir) {
  EXPECT_EQ(std::system(("cd '" + dir + "' && '" PRT_CLI_PATH "' -q light env.hdr -o ours.json")
                            .c_str()),
            0);
  return io::readLightJson(dir + "/ours.json").coefficients;
}

TEST_F(EngineLightCli, UnityIsWhatShadeSH9EvaluatesInUnitysAxes) {
  writeBlobs(dir_ / "env.hdr", 256);
  const sh::RgbSh L = ourLight(dir_.string());
  ASSERT_EQ(prt("-q light env.hdr --format unity -o unity.json").rc, 0);
  const Json u = Json::parse(slurp(dir_ / "unity.json"));
  ASSERT_EQ(u["sh"].size(), 27u);
  const auto sh = [&](int channel, int i) { return u["sh"][9 * channel + i].get<double>(); };
  for (const Vec3f d : {Vec3f(0, 1, 0), Vec3f(1, 0, 0), Vec3f(0, 0, 1), Vec3f(0.6f, 0.0f, -0.8f),
                        Vec3f(-0.36f, 0.48f, 0.8f), Vec3f(0, -1, 0)}) {
    // Unity's ShadeSH9 on a Unity-space normal: glTF's x negated (glTFast, UnityGLTF).
    const double x = -d.x, y = d.y, z = d.z;
    const Rgb want = sh::irradianceQuadratic(L, d) * static_cast<float>(1 / M_PI);
    for (int c = 0; c < 3; ++c) {
      const double shade9 = sh(c, 0) - sh(c, 6) + sh(c, 3) * x + sh(c, 1) * y + sh(c, 2) * z +
                            sh(c, 4) * x * y + sh(c, 5) * y * z + 3 * sh(c, 6) * z * z +
                            sh(c, 7) * x * z + sh(c, 8) * (x * x - y * y);
      EXPECT_NEAR(shade9, want[c], 1e-5 + 1e-5 * want[c]) << d.x << "," << d.y << "," << d.z;
    }
  }
}

TEST_F(EngineLightCli, GltfIblIsTheIrradianceBabylonEvaluates) {
  writeBlobs(dir_ / "env.hdr", 256);
  const sh::RgbSh L = ourLight(dir_.string());
  ASSERT_EQ(prt("-q light env.hdr --format gltf-ibl -o ibl.json").rc, 0);
  const Json j = Json::parse(slurp(dir_ / "ibl.json"));
  const Json& e = j["extensions"]["EXT_lights_image_based"]["lights"][0]["irradianceCoefficients"];
  ASSERT_EQ(e.size(), 9u);
  // Babylon.js's SH basis (its SH3ylmBasisConstants, with the Condon–Shortley signs, times its
  // trigonometric terms 1, y, z, x, xy, yz, 3z²−1, xz, x²−y²) on glTF's axes.
  const double k[9] = {std::sqrt(1 / (4 * M_PI)),  -std::sqrt(3 / (4 * M_PI)),
                       std::sqrt(3 / (4 * M_PI)),  -std::sqrt(3 / (4 * M_PI)),
                       std::sqrt(15 / (4 * M_PI)), -std::sqrt(15 / (4 * M_PI)),
                       std::sqrt(5 / (16 * M_PI)), -std::sqrt(15 / (4 * M_PI)),
                       std::sqrt(15 / (16 * M_PI))};
  for (const Vec3f d : {Vec3f(0, 1, 0), Vec3f(1, 0, 0), Vec3f(0, 0, 1), Vec3f(0.6f, 0.0f, -0.8f),
                        Vec3f(-0.36f, 0.48f, 0.8f)}) {
    const double x = d.x, y = d.y, z = d.z;
    const double terms[9] = {1, y, z, x, x * y, y * z, 3 * z * z - 1, x * z, x * x - y * y};
    const Rgb want = sh::irradianceQuadratic(L, d);
    for (int c = 0; c < 3; ++c) {
      double e9 = 0;
      for (int i = 0; i < 9; ++i) e9 += e[i][c].get<double>() * k[i] * terms[i];
      EXPECT_NEAR(e9, want[c], 1e-5 + 1e-5 * want[c]);
    }
  }
}

TEST_F(EngineLightCli, TheExtensionMustBeTheFormats) {
  writeBlobs(dir_ / "env.hdr", 64);
  expectCleanFailure("light env.hdr -o out/x.npy", "unknown light file extension '.npy'");
  expectCleanFailure("light env.hdr --format threejs -o out/x.txt", "writes a .json file");
  expectCleanFailure("light env.hdr --format cmgen -o out/x.json", "writes a .txt file");
  expectCleanFailure("light env.hdr --format unreal -o out/x.json", "--format must be one of");
  // Fewer bands than the engine holds: zeros above, the same light.
  ASSERT_EQ(prt("-q light env.hdr --bands 2 --format threejs -o p.json").rc, 0);
  const Json p = Json::parse(slurp(dir_ / "p.json"));
  ASSERT_EQ(p["object"]["sh"].size(), 27u);
  for (std::size_t k = 12; k < 27; ++k) EXPECT_EQ(p["object"]["sh"][k], 0.0);
  // To standard output, any format.
  const Result r = prt("-q light env.hdr --format cmgen -o -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(readShTxt(r.out).size(), 9u);
}

}  // namespace
}  // namespace prt::testing
