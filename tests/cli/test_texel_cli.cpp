// Per-texel transfer through the CLI (issue 18): prt bake --domain texels writes a bake that
// reads back with its lightmap; split texel ranges merge bit for bit into the whole bake; prt
// render relights it per pixel and matches the per-vertex render of the same scene (and
// misses it when the lightmap is read upside down); prt export writes coefficient textures
// that decode to the transfer (float EXR exactly, 16-bit PNG within its quantisation); and
// every consumer that cannot take texels says so in one line naming the file.

#include <gtest/gtest.h>
#include <stb_image.h>
#include <tinyexr.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "common/two_chart_plane.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using TexelCli = CliTest;

const std::string kBox = "'builtin:cornell?grid=8'";

TEST_F(TexelCli, BakeWritesTheLightmapAndRangesMergeBitExactly) {
  const std::string bake = "-q bake " + kBox +
                           " --mode shadowed --domain texels --resolution 48 "
                           "--samples 32 --padding 3";
  ASSERT_EQ(prt(bake + " -o whole.glb").rc, 0);
  const BakeFile whole = readBake(path("whole.glb"));
  ASSERT_EQ(whole.domain(), TransferDomain::Texels);
  EXPECT_EQ(whole.lightmap(), (TransferShape::LightmapSize{48, 48, 3}));
  EXPECT_TRUE(whole.complete());
  EXPECT_EQ(whole.transfers[0].transfer.rowCount(), 48u * 48u);
  EXPECT_EQ(whole.mesh.lightmapUvs.size(), whole.mesh.vertexCount());

  // Three pieces (cuts inside rows of texels), merged in any order.
  ASSERT_EQ(prt(bake + " --range 1000: -o c.glb").rc, 0);
  ASSERT_EQ(prt(bake + " --range 0:700 -o a.glb").rc, 0);
  ASSERT_EQ(prt(bake + " --shard 1/2 -o half.glb").rc, 0);  // texels 1152..2303
  ASSERT_EQ(prt(bake + " --range 700:1000 -o b.glb").rc, 0);
  const Result m = prt("merge c.glb a.glb b.glb -o merged.glb");
  ASSERT_EQ(m.rc, 0) << m.err;
  EXPECT_NE(m.err.find("2304 texels 0..2303, complete"), std::string::npos) << m.err;
  const BakeFile merged = readBake(path("merged.glb"));
  const FloatArray &x = whole.transfers[0].transfer.values(),
                   &y = merged.transfers[0].transfer.values();
  ASSERT_EQ(x.size(), y.size());
  EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0);
  const BakeFile half = readBake(path("half.glb"));
  EXPECT_EQ(half.rows(), (RowRange{1152, 1152}));
  EXPECT_EQ(std::memcmp(half.transfers[0].transfer.values().data(), x.data() + 1152 * 9,
                        1152 * 9 * sizeof(float)),
            0);

  const Result info = prt("info whole.glb");
  EXPECT_NE(info.out.find("lightmap    48x48 over the lightmap UVs, padding 3"), std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("range       texels 0..2303 (complete)"), std::string::npos);
  EXPECT_NE(info.out.find("accessor _PRT_SHADOWED_TEXELS"), std::string::npos);
  EXPECT_NE(info.out.find("seams       none"), std::string::npos) << "the box has creases only";
  expectCleanFailure("merge a.glb c.glb -o out/m.glb", "leaves a gap: texels 700..999");
}

/// Mean |a − b| over the pixels either shows, relative to the mean of a there.
double relativeDifference(const image::Image& a, const image::Image& b) {
  double diff = 0, sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const Rgb p = a.pixels[i], q = b.pixels[i];
    if (p.x + p.y + p.z == 0 && q.x + q.y + q.z == 0) continue;  // background
    for (int c = 0; c < 3; ++c) {
      diff += std::abs((&p.x)[c] - (&q.x)[c]);
      sum += (&p.x)[c];
    }
  }
  return sum > 0 ? diff / sum : 1.0;
}

// The Cornell box inter-reflected per texel (a 128² lightmap) and per vertex on 64 × 64 grids,
// rendered alike: they agree to Monte Carlo error and discretisation (what is left is mostly
// the vertex render's: interpolation spreads a concave corner's darkness over a grid cell —
// 7.1% at 24 × 24 grids, 3.3% at 64 × 64). The same lightmap fetched upside down (its UVs' v
// flipped in the file) is 64% off.
TEST_F(TexelCli, RenderRelightsPerPixelAndMatchesTheVertexRender) {
  const std::string scene = "'builtin:cornell?grid=64'";
  ASSERT_EQ(prt("-q bake " + scene + " --mode interreflected --samples 256 -o v.glb").rc, 0);
  ASSERT_EQ(prt("-q bake " + scene +
                " --mode interreflected --samples 256 --domain texels "
                "--resolution 128 -o t.glb")
                .rc,
            0);
  const std::string render = " --light builtin:sky --background none --size 200x150 ";
  ASSERT_EQ(prt("-q render v.glb" + render + "-o v.exr").rc, 0);
  const Result r = prt("render t.glb" + render + "-o t.exr");
  ASSERT_EQ(r.rc, 0) << r.err;
  const image::Image v = image::readImage(path("v.exr")), t = image::readImage(path("t.exr"));
  const double d = relativeDifference(v, t);
  std::printf("per-texel vs per-vertex render, mean relative difference %.4f\n", d);
  EXPECT_LT(d, 0.05);
  EXPECT_GT(d, 0.0) << "two bakes of different points cannot render identically";

  // The lightmap read upside down: v → 1 − v in the bake (a lightmap convention error).
  BakeFile flipped = readBake(path("t.glb"));
  for (Vec2f& uv : flipped.mesh.lightmapUvs) uv.y = 1.0f - uv.y;
  writeBake(path("flipped.glb"), flipped);
  ASSERT_EQ(prt("-q render flipped.glb" + render + "-o f.exr").rc, 0);
  const double df = relativeDifference(v, image::readImage(path("f.exr")));
  std::printf("flipped lightmap vs per-vertex render, mean relative difference %.4f\n", df);
  EXPECT_GT(df, 2 * d);
}

TEST_F(TexelCli, ExportWritesCoefficientTexturesThatDecodeToTheTransfer) {
  ASSERT_EQ(prt("-q bake " + kBox +
                " --mode interreflected --domain texels --resolution 40 "
                "--samples 16 -o t.glb")
                .rc,
            0);
  const BakeFile bake = readBake(path("t.glb"));
  const Transfer& tr = bake.transfers[0].transfer;
  ASSERT_EQ(tr.channels(), 3);
  const std::size_t S = tr.stride(), texels = 40 * 40;
  ASSERT_EQ(S, 27u);
  for (const std::string format : {"exr", "png"}) {
    SCOPED_TRACE(format);
    const Result r = prt("export t.glb --format " + format + " -o tex-" + format);
    ASSERT_EQ(r.rc, 0) << r.err;
    const nlohmann::json manifest =
        nlohmann::json::parse(slurp(dir_ / ("tex-" + format) / "transfer.json"));
    EXPECT_EQ(manifest["bands"], 3);
    EXPECT_EQ(manifest["lightmap"]["width"], 40);
    EXPECT_EQ(manifest["lightmap"]["texCoord"], 0);
    ASSERT_EQ(manifest["textures"].size(), 7u);  // ⌈27 / 4⌉
    double worst = 0, bound = 0;
    for (std::size_t k = 0; k < 7; ++k) {
      const nlohmann::json& tex = manifest["textures"][k];
      const std::string file = (dir_ / ("tex-" + format) / tex["file"].get<std::string>()).string();
      std::vector<float> rgba(texels * 4);
      std::vector<double> decoded(texels * 4);
      if (format == "exr") {
        float* out = nullptr;
        int w = 0, h = 0;
        const char* err = nullptr;
        ASSERT_EQ(LoadEXR(&out, &w, &h, file.c_str(), &err), TINYEXR_SUCCESS) << file;
        ASSERT_EQ(w * h, int(texels));
        for (std::size_t i = 0; i < texels * 4; ++i) decoded[i] = out[i];
        std::free(out);
      } else {
        int w = 0, h = 0, n = 0;
        stbi_us* out = stbi_load_16(file.c_str(), &w, &h, &n, 4);
        ASSERT_NE(out, nullptr) << file;
        ASSERT_EQ(w * h, int(texels));
        for (std::size_t i = 0; i < texels; ++i)
          for (std::size_t j = 0; j < tex["channels"].size(); ++j) {
            const nlohmann::json& ch = tex["channels"][j];
            decoded[i * 4 + j] = ch["offset"].get<double>() +
                                 ch["scale"].get<double>() * double(out[i * 4 + j]) / 65535.0;
            bound = std::max(bound, ch["scale"].get<double>() / 131070.0);
          }
        stbi_image_free(out);
      }
      for (std::size_t j = 0; j < tex["channels"].size(); ++j) {
        const nlohmann::json& ch = tex["channels"][j];
        const std::size_t value = ch["value"];
        EXPECT_EQ(value, 4 * k + j);
        EXPECT_EQ(ch["coefficient"], value / 3);
        for (std::size_t i = 0; i < texels; ++i)
          worst = std::max(worst, std::abs(decoded[i * 4 + j] - double(tr.row(i)[value])));
      }
    }
    if (format == "exr")
      EXPECT_EQ(worst, 0.0);
    else
      EXPECT_LE(worst, bound * 1.001 + 1e-7);
    EXPECT_GT(bound + (format == "exr" ? 1.0 : 0.0), 0.0);
  }
  // A per-vertex bake has no textures; a texel bake no transport.txt.
  ASSERT_EQ(prt("-q bake " + kBox + " --mode shadowed --samples 8 -o v.glb").rc, 0);
  expectCleanFailure("export v.glb --format exr -o out/x", "holds per-vertex transfer");
  expectCleanFailure("export t.glb -o out/x.txt", "t.glb: holds per-texel transfer");
}

/// The last row's numbers of prt validate --json FILE.
nlohmann::json lastRow(const std::string& file) {
  return nlohmann::json::parse(slurp(file))["rows"].back();
}

// prt validate per texel: a seeded subset of the valid texels against the brute-force reference
// at their sample points, the same table as for vertices. The bake's error is what the band
// limit and the reference's noise explain; the same transfer over UVs flipped upside down (its
// rows meeting other points) is not; the error image is the lightmap.
TEST_F(TexelCli, ValidatePerTexelExplainsItsErrorAndCatchesAMisplacedLightmap) {
  ASSERT_EQ(prt("-q bake " + kBox +
                " --mode interreflected --domain texels --resolution 48 "
                "--samples 512 -o t.glb")
                .rc,
            0);
  const std::string validate = " --light builtin:sky --vertices 800 --reference-samples 256 ";
  const Result r = prt("validate t.glb" + validate + "--json t.json --image out-err.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("reference: 800 texels"), std::string::npos) << r.err;
  const nlohmann::json row = lastRow(path("t.json"));
  std::printf("per texel: rel RMSE %.3f, floor %.3f, ref std err %.3f, explained %.3f\n",
              row["relRmse"].get<double>(), row["truncationFloor"].get<double>(),
              row["refStdErr"].get<double>(), row["explained"].get<double>());
  EXPECT_GT(row["explained"].get<double>(), 0.8);
  const image::Image err = image::readImage(path("out-err.png"));
  EXPECT_EQ(err.width, 48);
  EXPECT_EQ(err.height, 48);

  BakeFile flipped = readBake(path("t.glb"));
  for (Vec2f& uv : flipped.mesh.lightmapUvs) uv.y = 1.0f - uv.y;
  writeBake(path("flipped.glb"), flipped);
  ASSERT_EQ(prt("-q validate flipped.glb" + validate + "--json f.json").rc, 0);
  const nlohmann::json bad = lastRow(path("f.json"));
  std::printf("flipped: rel RMSE %.3f, explained %.3f\n", bad["relRmse"].get<double>(),
              bad["explained"].get<double>());
  EXPECT_GT(bad["relRmse"].get<double>(), 1.5 * row["relRmse"].get<double>());
  EXPECT_LT(bad["explained"].get<double>(), 0.7);
}

// Glossy matrices per texel through every verb: ranges merge bit for bit into the whole bake;
// prt render relights each texel at its sample point seen from the camera, so the lobe adds a
// view-dependent highlight a diffuse relighting of the same file has not; CPCA through prt
// compress renders within its compression error of the dense bake; prt validate explains the
// error; the viewers refuse the file by name.
TEST_F(TexelCli, GlossyMatricesPerTexelBakeMergeRenderCompressAndValidate) {
  const std::string bake = "-q bake " + kBox +
                           " --mode interreflected --bounces 1 --transfer matrix --domain texels "
                           "--resolution 32 --bands 3 --samples 128 "
                           "--material 'phong?ks=0.4&exponent=6'";
  const Result b = prt(bake.substr(3) + " -o m.glb");
  ASSERT_EQ(b.rc, 0) << b.err;
  EXPECT_NE(b.err.find("interreflected matrix: 972 B per texel"), std::string::npos)
      << b.err;
  ASSERT_EQ(prt(bake + " --range 0:500 -o a.glb").rc, 0);
  ASSERT_EQ(prt(bake + " --range 500: -o b.glb").rc, 0);
  ASSERT_EQ(prt("-q merge b.glb a.glb -o merged.glb").rc, 0);
  const BakeFile whole = readBake(path("m.glb")), merged = readBake(path("merged.glb"));
  ASSERT_EQ(whole.transfers[0].transfer.layout(), TransferLayout::Matrix);
  ASSERT_EQ(whole.transfers[0].transfer.domain(), TransferDomain::Texels);
  const FloatArray &x = whole.transfers[0].transfer.values(),
                   &y = merged.transfers[0].transfer.values();
  ASSERT_EQ(x.size(), std::size_t(32 * 32 * 81 * 3));
  ASSERT_EQ(x.size(), y.size());
  EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0);

  const std::string render = " --light builtin:sky --background none --size 160x120 ";
  ASSERT_EQ(prt("-q render m.glb" + render + "--exposure 0 -o glossy.exr").rc, 0);
  ASSERT_EQ(prt("-q render m.glb" + render + "--exposure 0 --material lambert -o diffuse.exr").rc,
            0);
  const image::Image glossy = image::readImage(path("glossy.exr")),
                     diffuse = image::readImage(path("diffuse.exr"));
  double sumG = 0, sumD = 0;
  for (std::size_t i = 0; i < glossy.pixels.size(); ++i) {
    sumG += glossy.pixels[i].x + glossy.pixels[i].y + glossy.pixels[i].z;
    sumD += diffuse.pixels[i].x + diffuse.pixels[i].y + diffuse.pixels[i].z;
  }
  EXPECT_GT(sumD, 0.0);
  EXPECT_GT(sumG, 1.05 * sumD) << "the lobe adds the reflected light";

  const Result c = prt("compress m.glb --clusters 16 --pca 8 -o c.glb");
  ASSERT_EQ(c.rc, 0) << c.err;
  ASSERT_EQ(prt("-q render c.glb" + render + "--exposure 0 -o compressed.exr").rc, 0);
  const double dc = relativeDifference(glossy, image::readImage(path("compressed.exr")));
  std::printf("per-texel glossy matrices, CPCA K16 N8 vs dense render: %.4f\n", dc);
  EXPECT_LT(dc, 0.05);
  EXPECT_GT(dc, 0.0);

  const Result v =
      prt("validate m.glb --light builtin:sky --vertices 300 "
          "--reference-samples 256 --json v.json");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_NE(v.err.find("reference: 300 texels"), std::string::npos) << v.err;
  const nlohmann::json row = lastRow(path("v.json"));
  std::printf("per-texel glossy matrices: rel RMSE %.3f, floor %.3f, explained %.3f\n",
              row["relRmse"].get<double>(), row["truncationFloor"].get<double>(),
              row["explained"].get<double>());
  // A 6-exponent lobe at 3 bands: the error is the band limit's (measured: explained 1.01).
  EXPECT_GT(row["explained"].get<double>(), 0.8);
  EXPECT_LT(row["explained"].get<double>(), 1.25);
  // The browser viewer takes the compressed file (with the texels' points, tests/web) and refuses
  // the dense one by name.
  const Result w = prt("-q web c.glb -o page");
  ASSERT_EQ(w.rc, 0) << w.err;
  EXPECT_NE(slurp(path("page/prt-data.js")).find("\"texelPoints\":{"), std::string::npos);
  expectCleanFailure("web m.glb -o out/page", "dense glossy matrices");
}

// prt reference per texel: a seeded subset of the valid texels at their sample points, read
// back by prt validate --reference to the same table as validate computing it itself (the same
// rows, samples and seed); a reference of another lightmap is refused by name.
TEST_F(TexelCli, ReferencePerTexelIsWhatValidateComputes) {
  const std::string bake =
      "-q bake " + kBox + " --mode interreflected --domain texels --samples 256 --resolution ";
  ASSERT_EQ(prt(bake + "32 -o t.glb").rc, 0);
  ASSERT_EQ(prt(bake + "24 -o small.glb").rc, 0);
  const Result r =
      prt("reference t.glb --light builtin:sky --vertices 150 --samples 128 -o r.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("150 texels x 128 samples"), std::string::npos) << r.err;
  const nlohmann::json ref = nlohmann::json::parse(slurp(path("r.json")));
  EXPECT_EQ(ref["bake"]["lightmap"]["width"], 32);
  ASSERT_EQ(ref["texels"].size(), 150u);
  EXPECT_FALSE(ref.contains("vertices"));
  // Every row a covered texel of the lightmap, none in the gutter.
  const BakeFile t = readBake(path("t.glb"));
  const TexelSamples s = sampleTexels(t.mesh, t.mesh.lightmapUvs, 32, 32);
  for (const auto& x : ref["texels"]) ASSERT_GE(s.sampleOfTexel[x.get<std::size_t>()], 0) << x;

  const std::string validate = "validate t.glb --light builtin:sky ";
  ASSERT_EQ(prt("-q " + validate + "--vertices 150 --reference-samples 128 --json own.json").rc, 0);
  const Result v = prt(validate + "--reference r.json --json read.json");
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_NE(v.err.find("reference from r.json: 150 texels x 128 samples"), std::string::npos)
      << v.err;
  const nlohmann::json own = lastRow(path("own.json")), read = lastRow(path("read.json"));
  for (const char* key : {"relRmse", "truncationFloor", "refStdErr", "explained"})
    EXPECT_DOUBLE_EQ(own[key].get<double>(), read[key].get<double>()) << key;
  expectCleanFailure("validate small.glb --light builtin:sky --reference r.json",
                     "r.json: was computed for a 32 x 32 lightmap");
}

// --uv auto on a mesh with no UV set that can hold a lightmap: the bake unwraps it (the atlas
// prt unwrap makes, at the bake's resolution and padding), says so with the atlas's figures,
// and the file keeps the unwrapped mesh, which renders; the same atlas as prt unwrap's.
TEST_F(TexelCli, AutoUvsUnwrapAMeshWithoutALightmapSet) {
  const std::string ball = "'builtin:sphere?subdiv=3'";
  const Result b = prt("bake " + ball +
                       " --mode shadowed --domain texels --resolution 64 --samples 16 -o b.glb");
  ASSERT_EQ(b.rc, 0) << b.err;
  EXPECT_NE(b.err.find("no UV set of its own can hold the lightmap (lightmap UVs: the mesh has "
                       "none; texture UVs: the mesh has none): unwrapped it"),
            std::string::npos)
      << b.err;
  EXPECT_NE(b.err.find("a 64 x 64 lightmap over its atlas (prt unwrap)"), std::string::npos)
      << b.err;
  const BakeFile f = readBake(path("b.glb"));
  EXPECT_EQ(f.domain(), TransferDomain::Texels);
  ASSERT_EQ(f.mesh.lightmapUvs.size(), f.mesh.vertexCount());
  ASSERT_EQ(prt("-q unwrap " + ball + " --resolution 64 -o atlas.glb").rc, 0);
  ASSERT_EQ(prt("-q bake atlas.glb --mode shadowed --domain texels --resolution 64 --samples 16 "
                "-o a.glb")
                .rc,
            0);
  const BakeFile a = readBake(path("a.glb"));
  ASSERT_EQ(a.mesh.vertexCount(), f.mesh.vertexCount());
  for (std::size_t v = 0; v < a.mesh.vertexCount(); ++v)
    ASSERT_EQ(a.mesh.lightmapUvs[v], f.mesh.lightmapUvs[v]) << v;
  ASSERT_EQ(prt("-q render b.glb --light builtin:sky --size 64x48 -o b.png").rc, 0);
}

/// The two-chart plane of the seam tests (one seam, the right chart turned and at half the
/// density) as an OBJ whose texture UVs (vt) are the lightmap set: `--uv 0` bakes over them.
std::string twoChartPlaneObj() {
  const Mesh m = twoChartPlane(/*rotatedRightChart=*/true);
  std::string obj;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const Vec3f p = m.positions[v], n = m.normals[v];
    const Vec2f t = m.lightmapUvs[v];
    obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) +
           "\nvn " + std::to_string(n.x) + " " + std::to_string(n.y) + " " +
           std::to_string(n.z) + "\nvt " + std::to_string(t.x) + " " + std::to_string(t.y) + "\n";
  }
  for (const auto& t : m.triangles) {
    std::string f = "f";
    for (std::uint32_t i : t) f += " " + std::to_string(i + 1) + "/" + std::to_string(i + 1) + "/" +
                                   std::to_string(i + 1);
    obj += f + "\n";
  }
  return obj;
}

TEST_F(TexelCli, SeamFixClosesTheSeamsInBakeAndMerge) {
  write("plane.obj", twoChartPlaneObj());
  const std::string bake =
      "bake plane.obj --mode shadowed --domain texels --resolution 16 --uv 0 --samples 512";
  ASSERT_EQ(prt("-q " + bake + " -o plain.glb").rc, 0);
  const Result fixedRun = prt(bake + " --seam-fix -o fixed.glb");
  ASSERT_EQ(fixedRun.rc, 0) << fixedRun.err;
  EXPECT_NE(fixedRun.err.find("seam fix over 1 seam edges"), std::string::npos) << fixedRun.err;
  const auto seams = [&](const std::string& file) {
    const Result r = prt("info " + file + " --json -");
    EXPECT_EQ(r.rc, 0) << r.err;
    return nlohmann::json::parse(r.out)["files"][0]["lightmap"];
  };
  const nlohmann::json plain = seams("plain.glb"), fixed = seams("fixed.glb");
  EXPECT_FALSE(plain["seamsFixed"].get<bool>());
  EXPECT_TRUE(fixed["seamsFixed"].get<bool>());
  EXPECT_EQ(fixed["seams"]["edges"].get<int>(), 1);
  EXPECT_LT(fixed["seams"]["mismatch"].get<double>(),
            plain["seams"]["mismatch"].get<double>() / 4);
  EXPECT_NE(prt("info fixed.glb").out.find("after the seam fix"), std::string::npos);
  // Reported under the builtin sky's sun too (the shadow edges, where seams show most).
  const nlohmann::json& under = plain["seams"]["under"];
  ASSERT_EQ(under.size(), 2u);
  EXPECT_EQ(under[0]["light"], "white sky");
  EXPECT_EQ(under[0]["mismatch"], plain["seams"]["mismatch"]);
  EXPECT_EQ(under[1]["light"], "sun");
  EXPECT_GT(under[1]["mismatch"].get<double>(), 0.0);
  EXPECT_NE(under[1]["mismatch"], under[0]["mismatch"]);
  EXPECT_LT(fixed["seams"]["under"][1]["mismatch"].get<double>(),
            under[1]["mismatch"].get<double>());
  EXPECT_NE(prt("info plain.glb").out.find("% under the builtin sky's sun (max "),
            std::string::npos);

  // Pieces baked without it, merged with it: the same file as the whole bake with it.
  ASSERT_EQ(prt("-q " + bake + " --range 0:100 -o a.glb").rc, 0);
  ASSERT_EQ(prt("-q " + bake + " --range 100: -o b.glb").rc, 0);
  const Result m = prt("-q merge b.glb a.glb --seam-fix -o merged.glb");
  ASSERT_EQ(m.rc, 0) << m.err;
  const BakeFile whole = readBake(path("fixed.glb")), merged = readBake(path("merged.glb"));
  EXPECT_TRUE(merged.lightmap().seamsFixed);
  const FloatArray &x = whole.transfers[0].transfer.values(),
                   &y = merged.transfers[0].transfer.values();
  ASSERT_EQ(x.size(), y.size());
  EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0);

  expectCleanFailure(bake + " --seam-fix --range 0:100 -o out/x.glb",
                     "--seam-fix needs the whole lightmap");
  expectCleanFailure(bake + " --seam-fix --shard 1/2 -o out/x.glb",
                     "--seam-fix needs the whole lightmap");
  expectCleanFailure("bake plane.obj --mode shadowed --seam-fix -o out/x.glb",
                     "add --domain texels");
  ASSERT_EQ(prt("-q " + bake + " --range 100:200 -o c.glb").rc, 0);
  expectCleanFailure("merge a.glb c.glb --seam-fix -o out/x.glb", "is a partial bake");
}

TEST_F(TexelCli, WhatCannotTakeTexelsSaysSoByName) {
  ASSERT_EQ(prt("-q bake " + kBox +
                " --mode shadowed --domain texels --resolution 16 "
                "--samples 8 -o t.glb")
                .rc,
            0);
  ASSERT_EQ(prt("-q bake " + kBox + " --mode shadowed --samples 8 -o v.glb").rc, 0);
  ASSERT_EQ(prt("-q reference v.glb --light builtin:sky --samples 4 --vertices 10 -o rv.json").rc,
            0);
  expectCleanFailure("validate t.glb --light builtin:sky --reference rv.json",
                     "rv.json: holds per-vertex radiance; t.glb holds per-texel transfer");
  expectCleanFailure("render t.glb --light builtin:sky --reference rv.json -o out/x.png",
                     "--reference draws a per-vertex reference");
  // And the bake's own refusals.
  expectCleanFailure("bake " + kBox + " --mode shadowed --resolution 64 -o out/x.glb",
                     "add --domain texels");
  expectCleanFailure("bake " + kBox +
                         " --mode shadowed --domain texels --transfer matrix --bands 8 "
                         "--resolution 4096 -o out/x.glb",
                     "more than a bake file holds");
  expectCleanFailure(
      "bake 'builtin:sphere?subdiv=1' --mode shadowed --domain texels --uv 1 -o out/x.glb",
      "no UV set can hold a 512 x 512 lightmap (lightmap UVs: the mesh has none)");
  expectCleanFailure("bake " + kBox + " --mode shadowed --domain texels --uv 0 -o out/x.glb",
                     "texture UVs: the mesh has none");
  expectCleanFailure("bake " + kBox +
                         " --mode shadowed --domain texels --resolution 16 --range "
                         "0:300 -o out/x.glb",
                     "FIRST < END <= 256 (the texel count)");
  expectCleanFailure("bake " + kBox + " --mode shadowed --domain textels -o out/x.glb",
                     "unknown transfer domain 'textels'");
}

}  // namespace
}  // namespace prt
