// `prt light --format threejs` against three.js's own LightProbeGenerator (run under node, see
// engine_light/light_probe_generator.mjs) on the same environment: six cube faces, sampled from
// one function of direction, once in prtkit's cube convention (OpenGL's, layout.hpp) and once in
// three.js's (LightProbeGenerator's own face frames: three shows a CubeTexture mirrored in x
// against OpenGL's, so the faces that show prtkit's world are its faces swapped +X/−X and
// flipped left-right). The two probes must agree coefficient by coefficient: a basis sign
// (three's SphericalHarmonics3 has no Condon–Shortley phase), an axis or a scale wrong fails.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cli/cli_harness.hpp"
#include "prt/core/json.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/image/image_io.hpp"

namespace prt::testing {
namespace {

bool have(const char* tool) {
  return std::system((std::string("command -v ") + tool + " > /dev/null 2>&1").c_str()) == 0;
}

/// A smooth, coloured environment with structure in every band (a warm blob up and toward +X,
/// a blue one toward −Z, a green one low toward +Z), kept in [0, 1] for 8-bit faces.
Rgb sky(Vec3d d) {
  const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  d = d * (1.0 / n);
  const auto blob = [&](double x, double y, double z, double k) {
    const double m = std::sqrt(x * x + y * y + z * z);
    return std::exp(k * ((d.x * x + d.y * y + d.z * z) / m - 1));
  };
  const double a = blob(0.5, 0.8, 0.2, 4), b = blob(0.1, 0.2, -1, 6), c = blob(0.3, -0.4, 0.9, 3);
  return Rgb(static_cast<float>(0.1 + 0.8 * a + 0.05 * c), static_cast<float>(0.1 + 0.4 * a + 0.7 * c),
             static_cast<float>(0.15 + 0.8 * b));
}

/// The 8-bit code of a linear value, as both sides read it (three divides by 255).
int code(float v) {
  return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

class EngineLightWeb : public CliTest {};

TEST_F(EngineLightWeb, ThreeJsMatchesLightProbeGeneratorOnTheSameFaces) {
  if (!have("node")) GTEST_SKIP() << "no node here (apt-get install nodejs)";
  const std::string three = std::string(PRT_SOURCE_DIR) + "/web/node_modules/three/package.json";
  if (!fs::exists(three)) GTEST_SKIP() << "web/node_modules missing (run scripts/setup.sh)";

  constexpr int n = 64;
  // prtkit's faces: float EXR (exact), each texel the 8-bit code three will see, over 255.
  fs::create_directories(dir_ / "faces");
  for (int f = 0; f < 6; ++f) {
    image::Image img(n, n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double s = 2 * (x + 0.5) / n - 1, t = 2 * (y + 0.5) / n - 1;
        const Rgb v = sky(envmap::cubeFaceDirection(f, s, t));
        img.at(x, y) = Rgb(code(v.x) / 255.0f, code(v.y) / 255.0f, code(v.z) / 255.0f);
      }
    image::writeImage((dir_ / "faces" / (std::string(envmap::kFaceNames[f]) + ".exr")).string(),
                      img);
  }
  // three.js's faces, in LightProbeGenerator's frames (its fromCubeTexture, face by face).
  std::vector<unsigned char> bytes;
  for (int f = 0; f < 6; ++f)
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const double col = -1 + (c + 0.5) * 2 / n, row = 1 - (r + 0.5) * 2 / n;
        const Vec3d coords[6] = {{-1, row, -col}, {1, row, col},  {-col, 1, -row},
                                 {-col, -1, row}, {-col, row, 1}, {col, row, -1}};
        const Rgb v = sky(coords[f]);
        for (float ch : {v.x, v.y, v.z}) bytes.push_back(static_cast<unsigned char>(code(ch)));
        bytes.push_back(255);
      }
  std::ofstream(dir_ / "three.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));

  const Result ours = prt("-q light faces --format threejs -o probe.json");
  ASSERT_EQ(ours.rc, 0) << ours.err;
  const Json probe = Json::parse(slurp(dir_ / "probe.json"));
  EXPECT_EQ(probe["object"]["type"], "LightProbe");
  const Json& mine = probe["object"]["sh"];
  ASSERT_EQ(mine.size(), 27u);

  const std::string script =
      std::string(PRT_SOURCE_DIR) + "/tests/web/engine_light/light_probe_generator.mjs";
  const std::string cmd = "cd '" + dir_.string() + "' && node '" + script + "' three.bin " +
                          std::to_string(n) + " > three.json 2> node.txt";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir_ / "node.txt");
  const Json theirs = Json::parse(slurp(dir_ / "three.json"));
  ASSERT_EQ(theirs.size(), 27u);
  // three weights texels by 4/|c|³ normalised to 4π, prtkit by exact solid angles: at 64² they
  // differ by far less than any sign or axis error would (those move a coefficient by its size).
  const double dc = theirs[0].get<double>();
  for (std::size_t k = 0; k < 27; ++k)
    EXPECT_NEAR(mine[k].get<double>(), theirs[k].get<double>(), 2e-3 * dc)
        << "coefficient " << k / 3 << " channel " << "rgb"[k % 3];
}

/// The rows "( r, g, b); // Llm" of a cmgen sh.txt, as flat r, g, b.
std::vector<double> cmgenRows(const std::string& text) {
  std::vector<double> v;
  for (std::size_t at = text.find('('); at != std::string::npos; at = text.find('(', at + 1)) {
    double r, g, b;
    if (std::sscanf(text.c_str() + at, "(%lf, %lf, %lf)", &r, &g, &b) == 3) v.insert(v.end(), {r, g, b});
  }
  return v;
}

TEST_F(EngineLightWeb, CmgenFormatSaysWhichWindowingItMatches) {
  // `--format cmgen` is cmgen's sh.txt with its windowing off (`-w no`); cmgen's default
  // (`-w auto`) windows the bands above 0 and band 2 by several times. The option's help and
  // docs/formats-light.md must say so, and (with cmgen here) both halves must hold.
  const Result help = prt("light --help");
  ASSERT_EQ(help.rc, 0) << help.err;
  const std::string h = help.out + help.err;
  EXPECT_NE(h.find("cmgen -w no"), std::string::npos) << h;
  EXPECT_NE(h.find("-w auto"), std::string::npos) << h;
  const std::string doc = slurp(fs::path(PRT_SOURCE_DIR) / "docs" / "formats-light.md");
  EXPECT_NE(doc.find("cmgen --sh=B --sh-output=sh.txt -w no"), std::string::npos);
  EXPECT_NE(doc.find("`-w auto`"), std::string::npos);
  if (!have("cmgen")) GTEST_SKIP() << "no cmgen here (apt-get install libfilament-tools)";
  image::Image img(512, 256);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double th = M_PI * (y + 0.5) / img.height, ph = 2 * M_PI * (x + 0.5) / img.width;
      // Three bright coloured blobs on a dim floor (contrast for cmgen's window to act on).
      const Vec3d d(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      const auto blob = [&](double x0, double y0, double z0) {
        return static_cast<float>(0.05 + 4 * std::exp(4 * (d.x * x0 + d.y * y0 + d.z * z0 - 1)));
      };
      img.at(x, y) = Rgb(blob(1, 0, 0), blob(0, 1, 0), blob(0, 0, 1));
    }
  image::writeImage((dir_ / "env.hdr").string(), img);
  ASSERT_EQ(prt("-q light env.hdr --format cmgen -o prt.txt").rc, 0);
  ASSERT_EQ(std::system(("cd '" + dir_.string() +
                         "' && cmgen --sh=3 --sh-output=no.txt -w no -q env.hdr > cmgen.log 2>&1 && "
                         "cmgen --sh=3 --sh-output=auto.txt -q env.hdr >> cmgen.log 2>&1")
                            .c_str()),
            0)
      << slurp(dir_ / "cmgen.log");
  const std::vector<double> ours = cmgenRows(slurp(dir_ / "prt.txt")),
                            no = cmgenRows(slurp(dir_ / "no.txt")),
                            autoWindow = cmgenRows(slurp(dir_ / "auto.txt"));
  ASSERT_EQ(ours.size(), 27u);
  ASSERT_EQ(no.size(), 27u);
  ASSERT_EQ(autoWindow.size(), 27u);
  // Band energies (sum of squares over m and the channels).
  const auto energy = [](const std::vector<double>& v, int l) {
    double e = 0;
    for (int i = 3 * l * l; i < 3 * (l + 1) * (l + 1); ++i) e += v[std::size_t(i)] * v[std::size_t(i)];
    return std::sqrt(e);
  };
  for (int l = 0; l < 3; ++l)
    EXPECT_NEAR(energy(ours, l), energy(no, l), 0.04 * energy(no, 0)) << "band " << l << " against -w no";
  const double ratio2 = energy(no, 2) / energy(autoWindow, 2);
  std::cout << "cmgen -w auto shrinks band 2 by " << ratio2 << "x, band 1 by "
            << energy(no, 1) / energy(autoWindow, 1) << "x\n";
  EXPECT_GT(ratio2, 1.5) << "cmgen's default windowing is not ours";
  EXPECT_GT(std::abs(energy(ours, 2) - energy(autoWindow, 2)), 0.04 * energy(no, 0));
}

}  // namespace
}  // namespace prt::testing
