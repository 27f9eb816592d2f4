// Probe grids through the CLI (issue 32): prt probes writes a bake over the probe domain that
// reads back with its grid (format 7); it is prt bake --domain probes, bit for bit; ranges and
// job-array shards merge bit for bit into the whole grid; prt info describes it; and every verb
// that draws a surface's transfer refuses it in one line naming the file; prt render draws the
// scene with an object lit through the grid; prt validate compares it with the reference.

#include <gtest/gtest.h>
#include <tinyexr.h>

#include <cmath>
#include <map>
#include <cstring>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "common/glb_reader.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"

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
  EXPECT_EQ(whole.formatVersion, kBakeFormatVersion);
  EXPECT_GE(whole.formatVersion, kFirstProbeVersion);
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
        std::string("reference p.glb --light builtin:sky -o out/r.json")})
    expectCleanFailure(verb, "p.glb: holds a probe grid (3 x 3 x 3 probes");
  // prt web draws the scene and a ball lit through the grid (tests/web/test_probes_web.cpp),
  // shaded diffusely: a material is refused by name.
  const Result page = prt("-q web p.glb -o page");
  if (page.err.find("assets") == std::string::npos) {  // (the page is built where node is)
    EXPECT_EQ(page.rc, 0) << page.err;
    EXPECT_TRUE(std::filesystem::exists(path("page/prt-data.js")));
    expectCleanFailure("web p.glb --material phong -o out/page",
                       "p.glb: holds a probe grid, which lights what moves through it diffusely");
  }
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

/// Probe p's SH from a probe-grid export: coefficient k, channel c at probes[(p K + k) 3 + c].
sh::RgbSh probeSh(const nlohmann::json& j, std::size_t p) {
  const std::size_t K = j["coefficients"]["count"];
  sh::RgbSh f(int(std::lround(std::sqrt(double(K)))));
  for (std::size_t k = 0; k < K; ++k)
    for (int c = 0; c < 3; ++c) f.c[k][c] = j["probes"][(p * K + k) * 3 + c].get<float>();
  return f;
}

/// Little-endian float32s from base64 (RFC 4648), decoded here independently of the writer.
std::vector<float> floatsFromBase64(const std::string& text) {
  std::string bytes;
  unsigned v = 0;
  int n = 0;
  for (char ch : text) {
    if (ch == '=') break;
    const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    v = (v << 6) | unsigned(std::strchr(k, ch) - k);
    if ((n += 6) >= 8) bytes += char((v >> (n -= 8)) & 0xff);
  }
  std::vector<float> out(bytes.size() / 4);
  std::memcpy(out.data(), bytes.data(), out.size() * 4);
  return out;
}

TEST_F(ProbesCli, ProbeGridExportsAreTheRelitGridInEachEnginesConvention) {
  ASSERT_EQ(prt("-q probes " + kBox + " --grid 4x3x2 --samples 64 -o p.glb").rc, 0);
  ASSERT_EQ(prt("-q export p.glb --format probe-grid --engine prtkit --rotate 0,40,0 -o ours.json")
                .rc,
            0);
  ASSERT_EQ(prt("-q export p.glb --format probe-grid --rotate 0,40,0 -o three.json").rc, 0);
  ASSERT_EQ(prt("-q export p.glb --format probe-grid --engine unity --rotate 0,40,0 -o unity.json")
                .rc,
            0);
  ASSERT_EQ(prt("-q export p.glb --format probe-grid --engine prtkit --rotate 0,40,0 --exposure 1 "
                "-o bright.json")
                .rc,
            0);
  const auto read = [&](const char* name) { return nlohmann::json::parse(slurp(path(name))); };
  const nlohmann::json ours = read("ours.json"), three = read("three.json"),
                       unity = read("unity.json"), bright = read("bright.json");
  const BakeFile bake = readBake(path("p.glb"));
  const ProbeGrid& g = bake.transfers[0].transfer.shape().probes;
  ASSERT_EQ(ours["probes"].size(), g.probes() * 9 * 3);
  ASSERT_EQ(three["probes"].size(), g.probes() * 9 * 3);
  // three.js r187's LightProbeGrid over the same points (getProbePosition: position − size/2 +
  // (i + 0.5) size/res, a probe at each cell's centre).
  const nlohmann::json& lpg = three["lightProbeGrid"];
  for (std::size_t p = 0; p < g.probes(); ++p) {
    const auto cell = g.cell(p);
    for (int a = 0; a < 3; ++a) {
      const double size = lpg[a == 0 ? "width" : a == 1 ? "height" : "depth"];
      const double at = lpg["position"][a].get<double>() - size / 2 +
                        (cell[a] + 0.5) * size / lpg["resolution"][a].get<int>();
      EXPECT_NEAR(at, g.position(p)[a], 1e-6) << p << " axis " << a;
    }
  }
  // The atlas LightProbeGridNode samples: seven RGBA sub-volumes of nz + 2 slices along z,
  // probe layer z at slice t (nz + 2) + 1 + z, the edge layers repeated in the padding; the 27
  // floats of a probe then a 0, four to a texel.
  const nlohmann::json& atlas = lpg["atlas"];
  const int nx = g.count[0], ny = g.count[1], nz = g.count[2], block = nz + 2;
  ASSERT_EQ(atlas["size"], nlohmann::json({nx, ny, 7 * block}));
  const std::vector<float> tex = floatsFromBase64(atlas["data"]);
  ASSERT_EQ(tex.size(), std::size_t(nx) * ny * 7 * block * 4);
  const auto texel = [&](int x, int y, int slice, int c) {
    return tex[((std::size_t(slice) * ny + y) * nx + x) * 4 + c];
  };
  for (std::size_t p = 0; p < g.probes(); ++p) {
    const auto [x, y, z] = g.cell(p);
    for (int t = 0; t < 7; ++t)
      for (int c = 0; c < 4; ++c) {
        const int i = 4 * t + c;  // of the 27 floats and a trailing 0
        const float want = i < 27 ? three["probes"][p * 27 + i].get<float>() : 0.0f;
        EXPECT_FLOAT_EQ(texel(x, y, t * block + 1 + z, c), want) << p << " t " << t;
        if (z == 0) {
          EXPECT_FLOAT_EQ(texel(x, y, t * block, c), want);
        }
        if (z == nz - 1) {
          EXPECT_FLOAT_EQ(texel(x, y, t * block + nz + 1, c), want);
        }
      }
  }
  const Vec3f dirs[] = {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}, {0.6f, 0.0f, -0.8f},
                        {-0.36f, 0.48f, 0.8f}, {0, -1, 0}};
  for (std::size_t p = 0; p < g.probes(); p += 5) {
    const sh::RgbSh L = probeSh(ours, p), T = probeSh(three, p), U = probeSh(unity, p);
    const sh::RgbSh twice = probeSh(bright, p);
    for (std::size_t k = 0; k < L.c.size(); ++k)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(twice.c[k][c], 2 * L.c[k][c], 1e-5);
    for (const Vec3f& d : dirs) {
      // three.js's SphericalHarmonics3.getAt (no Condon–Shortley phase) is our radiance.
      const float x = d.x, y = d.y, z = d.z;
      const float basis[9] = {0.282095f,           0.488603f * y,       0.488603f * z,
                              0.488603f * x,       1.092548f * x * y,   1.092548f * y * z,
                              0.315392f * (3 * z * z - 1), 1.092548f * x * z,
                              0.546274f * (x * x - y * y)};
      const Rgb want = sh::reconstruct(L, d);
      Rgb got(0.0f);
      for (int k = 0; k < 9; ++k) got += T.c[k] * basis[k];
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-4 * (1 + std::abs(want[c])));
      // Unity's ShadeSH9 on a Unity-space normal (x negated) is E(n)/π of our radiance.
      const double ux = -d.x, uy = d.y, uz = d.z;
      const Rgb shade = sh::irradianceQuadratic(L, d) * float(1 / M_PI);
      for (int c = 0; c < 3; ++c) {
        const auto u = [&](int k) { return double(U.c[k][c]); };
        const double shade9 = u(0) - u(6) + u(3) * ux + u(1) * uy + u(2) * uz + u(4) * ux * uy +
                              u(5) * uy * uz + 3 * u(6) * uz * uz + u(7) * ux * uz +
                              u(8) * (ux * ux - uy * uy);
        EXPECT_NEAR(shade9, shade[c], 1e-4 * (1 + std::abs(shade[c])));
      }
    }
  }
  // What does not fit is refused by name, and nothing is written.
  ASSERT_EQ(prt("-q bake " + kBox + " --mode shadowed --samples 16 -o s.glb").rc, 0);
  expectCleanFailure("export s.glb --format probe-grid -o out/g.json",
                     "s.glb: holds vertices transfer: --format probe-grid relights a probe bake");
  expectCleanFailure("export p.glb --format probe-grid --engine cmgen -o out/g.json",
                     "--engine cmgen: cmgen's text holds one light, not a grid");
  expectCleanFailure("export p.glb --format probe-grid --encoding l1 -o out/g.json", "--encoding");
}

TEST_F(ProbesCli, ProbeGridAsGltfHoldsTheJsonExportsValuesInAccessors) {
  ASSERT_EQ(prt("-q probes " + kBox + " --grid 3x2x4 --samples 32 -o p.glb").rc, 0);
  for (const std::string engine : {"threejs", "unity", "prtkit"}) {
    SCOPED_TRACE(engine);
    ASSERT_EQ(prt("-q export p.glb --format probe-grid --engine " + engine + " -o g.json").rc, 0);
    ASSERT_EQ(prt("-q export p.glb --format probe-grid --engine " + engine + " -o g.glb").rc, 0);
    const nlohmann::json json = nlohmann::json::parse(slurp(path("g.json")));
    const Glb glb = splitGlb(slurp(path("g.glb")));
    const nlohmann::json& gltf = glb.json;
    EXPECT_EQ(gltf["asset"]["version"], "2.0");
    EXPECT_EQ(gltf["extensionsUsed"], nlohmann::json({"PRTKIT_probe_grid"}));
    const nlohmann::json& ext = gltf["extensions"]["PRTKIT_probe_grid"];
    EXPECT_EQ(ext["grid"], json["grid"]);
    EXPECT_EQ(ext["engine"], engine);
    EXPECT_EQ(ext["coefficients"], json["coefficients"]);
    const std::vector<float> probes = accessorFloats(glb, ext["probes"]);
    ASSERT_EQ(probes.size(), json["probes"].size());
    for (std::size_t i = 0; i < probes.size(); ++i)
      ASSERT_EQ(probes[i], json["probes"][i].get<float>()) << i;
    if (engine == "threejs") {
      const std::vector<float> atlas =
          accessorFloats(glb, ext["lightProbeGrid"]["atlas"]["accessor"]);
      EXPECT_EQ(atlas, floatsFromBase64(json["lightProbeGrid"]["atlas"]["data"]));
    }
  }
  expectCleanFailure("export p.glb --format probe-grid -o out/g.txt", "out/g.txt: --format "
                                                                       "probe-grid writes .json");
}

/// A multi-channel float EXR read with tinyexr's low-level API: each channel's plane by name,
/// and the header's string attributes.
struct ExrVolume {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> planes;
  std::map<std::string, std::string> attributes;
};
ExrVolume readExrVolume(const std::string& bytes) {
  ExrVolume v;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  EXRVersion version;
  EXPECT_EQ(ParseEXRVersionFromMemory(&version, data, bytes.size()), TINYEXR_SUCCESS);
  EXRHeader header;
  InitEXRHeader(&header);
  const char* err = nullptr;
  EXPECT_EQ(ParseEXRHeaderFromMemory(&header, &version, data, bytes.size(), &err), TINYEXR_SUCCESS)
      << (err ? err : "");
  for (int i = 0; i < header.num_custom_attributes; ++i) {
    const EXRAttribute& a = header.custom_attributes[i];
    if (std::string(a.type) == "string")
      v.attributes[a.name] = std::string(reinterpret_cast<const char*>(a.value), std::size_t(a.size));
  }
  EXRImage image;
  InitEXRImage(&image);
  EXPECT_EQ(LoadEXRImageFromMemory(&image, &header, data, bytes.size(), &err), TINYEXR_SUCCESS)
      << (err ? err : "");
  v.width = image.width;
  v.height = image.height;
  for (int c = 0; c < header.num_channels && image.images; ++c) {
    EXPECT_EQ(header.pixel_types[c], TINYEXR_PIXELTYPE_FLOAT);
    const float* p = reinterpret_cast<const float*>(image.images[c]);
    v.planes[header.channels[c].name] =
        std::vector<float>(p, p + std::size_t(image.width) * std::size_t(image.height));
  }
  FreeEXRImage(&image);
  FreeEXRHeader(&header);
  return v;
}

// -o grid.exr: nx x (ny nz) texels, probe (x, y, z) at column x, row z ny + y, a layer per
// coefficient (shK.R/G/B), the JSON's description in the header; the values are the JSON
// export's, for an engine's 9 coefficients and prtkit's B^2.
TEST_F(ProbesCli, ProbeGridAsExrVolumeHoldsTheJsonExportsValues) {
  ASSERT_EQ(prt("-q probes " + kBox + " --grid 3x2x4 --bands 4 --samples 32 -o p.glb").rc, 0);
  for (const std::string engine : {"threejs", "unity", "prtkit"}) {
    SCOPED_TRACE(engine);
    ASSERT_EQ(prt("-q export p.glb --format probe-grid --engine " + engine + " -o g.json").rc, 0);
    ASSERT_EQ(prt("-q export p.glb --format probe-grid --engine " + engine + " -o g.exr").rc, 0);
    const nlohmann::json json = nlohmann::json::parse(slurp(path("g.json")));
    const ExrVolume exr = readExrVolume(slurp(path("g.exr")));
    const int K = json["coefficients"]["count"];
    EXPECT_EQ(K, engine == "prtkit" ? 16 : 9);
    ASSERT_EQ(exr.width, 3);
    ASSERT_EQ(exr.height, 2 * 4);
    ASSERT_EQ(exr.planes.size(), std::size_t(3 * K));
    const nlohmann::json described = nlohmann::json::parse(exr.attributes.at("prtkit"));
    EXPECT_EQ(described["grid"], json["grid"]);
    EXPECT_EQ(described["engine"], engine);
    EXPECT_EQ(described["coefficients"], json["coefficients"]);
    EXPECT_FALSE(described.contains("probes"));
    const char* channel[3] = {"R", "G", "B"};
    for (int z = 0; z < 4; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
          const std::size_t probe = std::size_t(x + 3 * (y + 2 * z));
          const std::size_t texel = std::size_t((z * 2 + y) * 3 + x);
          for (int k = 0; k < K; ++k)
            for (int c = 0; c < 3; ++c)
              ASSERT_EQ(exr.planes.at("sh" + std::to_string(k) + "." + channel[c])[texel],
                        json["probes"][(probe * std::size_t(K) + std::size_t(k)) * 3 + std::size_t(c)]
                            .get<float>())
                  << x << y << z << " sh" << k << channel[c];
        }
  }
  // 300 z slices of 300 rows pass the 65,535 rows an EXR holds: refused by name, nothing
  // written.
  ASSERT_EQ(prt("-q probes " + kBox + " --grid 1x300x300 --bands 1 --samples 1 -o big.glb").rc, 0);
  expectCleanFailure("export big.glb --format probe-grid -o out/big.exr",
                     "out/big.exr: an EXR volume stacks the grid's 300 z slices of 300 rows");
}

}  // namespace
}  // namespace prt
