// prt bake / export / info through the real binary: the happy path (outputs parse and hold the
// right counts), and bad input (one error line, non-zero exit, nothing left behind).

#include <gtest/gtest.h>

#include "common/random_data.hpp"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_harness.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/bake_merge.hpp"
#include "prt/io/games202_transport.hpp"

namespace fs = std::filesystem;

namespace prt {
namespace {

using namespace prt::testing;
using BakeCli = CliTest;

// One vertex per distinct v/vt/vn triple: 5 positions, 10 course vertices, 4 triangles.
const char* kSharedObj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
vn 0 0 -1
vn 1 0 0
f 1/1/1 2/2/1 3/3/1
f 1/1/1 3/3/1 4/4/1
f 1/1/2 3/3/2 2/2/2
f 2/1/3 3/4/3 5/2/3
)";

TEST_F(BakeCli, BakeInfoExportSphere) {
  // subdiv 2: an icosahedron subdivided twice, 10·4² + 2 = 162 vertices, 20·4² = 320 triangles.
  Result r =
      prt("bake builtin:sphere?subdiv=2 --mode shadowed --mode unshadowed --bands 3 "
          "--samples 64 --seed 7 -o out/s.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("rays"), std::string::npos) << "summary on stderr: " << r.err;
  EXPECT_TRUE(r.out.empty()) << "bake prints nothing on stdout";
  const BakeFile b = readBake(path("out/s.glb"));
  EXPECT_EQ(b.mesh.vertexCount(), 162u);
  EXPECT_EQ(b.mesh.triangleCount(), 320u);
  ASSERT_EQ(b.transfers.size(), 2u);
  const BakedTransfer* sh = b.find(TransferMode::Shadowed);
  ASSERT_NE(sh, nullptr);
  EXPECT_EQ(sh->transfer.bands(), 3);
  EXPECT_EQ(sh->recipe.samples, 64);
  EXPECT_EQ(sh->recipe.seed, 7u);
  EXPECT_EQ(sh->stats.rays, 162u * 64u);  // one ray per sample per vertex (a convex sphere)

  r = prt("info out/s.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("162"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("320"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("shadowed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("unshadowed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("format version " + std::to_string(kBakeFormatVersion)), std::string::npos)
      << r.out;

  // Several modes: export must be told which.
  r = prt("-q export out/s.glb --format games202 -o out/t.txt");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("--mode"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out/t.txt"));

  r = prt("export out/s.glb --format games202 --mode shadowed -o out/t.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Games202Transport t = readGames202Transport(path("out/t.txt"));
  EXPECT_EQ(t.vertexCount, 162u);
  EXPECT_EQ(t.layout, Games202Layout::Faces);
  EXPECT_EQ(t.rowCount, 3u * 320u);
  EXPECT_EQ(t.bands, 3);
  r = prt("export out/s.glb --mode shadowed --layout vertices -o out/v.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  const Games202Transport v = readGames202Transport(path("out/v.txt"));
  ASSERT_EQ(v.rows.size(), testdata::valuesOf(sh->transfer).size());
  EXPECT_EQ(std::memcmp(v.rows.data(), testdata::valuesOf(sh->transfer).data(), v.rows.size() * 4),
            0)
      << "text export must round-trip the floats exactly";

  r = prt("info out/t.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("960 lines"), std::string::npos) << r.out;
}

TEST_F(BakeCli, ObjExportHasTheCourseVertexCount) {
  write("shared.obj", kSharedObj);
  Result r = prt("-q bake shared.obj --mode unshadowed --samples 16 -o out/o.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q export out/o.glb -o out/transport.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string text = slurp(dir_ / "out/transport.txt");
  EXPECT_EQ(text.substr(0, text.find('\n')), "10");
  const Games202Transport t = readGames202Transport(path("out/transport.txt"));
  EXPECT_EQ(t.rowCount, 12u);  // 4 triangles × 3 corners
}

TEST_F(BakeCli, PartialRangeBake) {
  Result r =
      prt("-q bake builtin:sphere?subdiv=2 --mode shadowed --samples 16 --range 100: -o out/p.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const BakeFile p = readBake(path("out/p.glb"));
  EXPECT_FALSE(p.complete());
  EXPECT_EQ(p.rows().first, 100u);
  EXPECT_EQ(p.rows().count, 62u);
  r = prt(
      "-q bake builtin:sphere?subdiv=2 --mode shadowed --samples 16 --range 0:100 -o out/q.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q bake builtin:sphere?subdiv=2 --mode shadowed --samples 16 -o out/full.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  // Split bakes merge into exactly the full bake.
  const BakeFile merged = mergeBakes({p, readBake(path("out/q.glb"))});
  const BakeFile full = readBake(path("out/full.glb"));
  ASSERT_TRUE(merged.complete());
  EXPECT_EQ(testdata::valuesOf(merged.transfers[0].transfer),
            testdata::valuesOf(full.transfers[0].transfer));
  // A partial bake cannot be exported.
  r = prt("-q export out/p.glb -o out/t.txt");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("partial"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out/t.txt"));
}

TEST_F(BakeCli, BadInputFailsCleanly) {
  write("garbage.obj", "v 1 2\nf 1 2 x\nthis is not an obj\n");
  write("past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  write("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("empty.obj", "# nothing here\n");
  write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string ok = " --mode shadowed --samples 16 -o out/x.glb";
  expectCleanFailure("bake missing.obj" + ok, "missing.obj");
  expectCleanFailure("bake garbage.obj" + ok, "garbage.obj");
  expectCleanFailure("bake past.obj" + ok, "past.obj");
  expectCleanFailure("bake nan.obj" + ok, "nan.obj");
  expectCleanFailure("bake empty.obj" + ok, "empty.obj");
  expectCleanFailure("bake builtin:nosuchscene" + ok, "nosuchscene");
  expectCleanFailure("bake tri.obj --mode shadowed --samples 0 -o out/x.glb", "--samples");
  expectCleanFailure("bake tri.obj --mode shadowed --samples 1000000000000 -o out/x.glb",
                     "samples");
  expectCleanFailure("bake tri.obj --mode shadowed --bands 0 -o out/x.glb", "--bands");
  expectCleanFailure("bake tri.obj --mode shadowed --bands 40 -o out/x.glb", "--bands");
  expectCleanFailure("bake tri.obj --mode sideways -o out/x.glb", "sideways");
  expectCleanFailure("bake tri.obj --mode shadowed --albedo 2,0,0 -o out/x.glb", "--albedo");
  expectCleanFailure("bake tri.obj --mode shadowed --range 5:9 -o out/x.glb", "--range");
  expectCleanFailure("bake tri.obj --mode shadowed -o out/x.txt", ".glb");
  expectCleanFailure("bake tri.obj --mode shadowed -o no/such/dir/x.glb", "no/such/dir");

  // Bad bake files for export and info.
  ASSERT_EQ(prt("-q bake tri.obj --mode shadowed --samples 16 -o good.glb").rc, 0);
  const std::string good = slurp(dir_ / "good.glb");
  write("cut.glb", good.substr(0, good.size() / 2));
  expectCleanFailure("export cut.glb -o out/t.txt", "truncated");
  expectCleanFailure("info cut.glb", "truncated");
  expectCleanFailure("export tri.obj -o out/t.txt", "tri.obj");
  expectCleanFailure("export good.glb --format unity -o out/t.txt", "unity");
  expectCleanFailure("export good.glb -o no/such/dir/t.txt", "no/such/dir");
  write("bad.txt", "3\n1 2 3\n");
  expectCleanFailure("info bad.txt", "bad.txt");
}

// --target-error: adaptive sampling reported as it ran, recorded in the file and described by
// prt info; refused in one line where it is not made.
TEST_F(BakeCli, TargetErrorBakesAdaptivelyAndSaysSo) {
  const Result r =
      prt("bake builtin:sphere-plane --mode shadowed --samples 2048 --target-error 0.02 -o a.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::string said = r.out + r.err;
  EXPECT_NE(said.find("adaptive sampling to a standard error of 0.02"), std::string::npos) << said;
  const BakeFile file = readBake((dir_ / "a.glb").string());
  EXPECT_EQ(file.transfers[0].recipe.targetError, 0.02);
  // Fewer rays than every row casting the cap, more than the pilot.
  const BakeStats& st = file.transfers[0].stats;
  EXPECT_GT(st.raysPerRowAndPass(), 64.0);
  EXPECT_LT(st.raysPerRowAndPass(), 2048.0);
  const Result info = prt("info a.glb");
  ASSERT_EQ(info.rc, 0) << info.err;
  EXPECT_NE(info.out.find("adaptive: at most 2048 per row, to a standard error of 0.02"),
            std::string::npos)
      << info.out;
  const std::string bake = "bake builtin:sphere-plane --mode shadowed -o out/x.glb ";
  expectCleanFailure(bake + "--target-error -0.1", "--target-error");
  expectCleanFailure(bake + "--target-error 1.5", "--target-error");
  expectCleanFailure(bake + "--target-error 0.01 --transfer matrix", "--target-error");
  expectCleanFailure(bake + "--target-error 0.01 --sampling uniform", "--target-error");
  expectCleanFailure(bake + "--target-error 0.01 --basis haar", "--target-error");
}

TEST_F(BakeCli, CtrlCCancelsWithoutOutput) {
  // ~1.7·10⁸ rays (tens of seconds): far longer than the second before SIGINT arrives.
  // --foreground: one SIGINT, to prt alone, as a terminal's Ctrl-C sends. Without it timeout
  // signals the child and then its whole process group, and on a loaded machine the second
  // copy lands after the first was handled: the "second Ctrl-C" that leaves at once.
  const Result r = prt("bake builtin:sphere --mode shadowed --samples 16384 -o out/c.glb",
                       "timeout --foreground -k 20 -s INT 1 ");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("cancelled"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir_ / "out"));
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

using namespace prt::testing;
using GlossyCli = CliTest;

// Glossy end to end through the CLI: a matrix bake states its memory, stores its material in a
// version-2 file, and the file's own MTL Ks/Ns (or glTF metallic-roughness) becomes the
// material when --material is not given.
TEST_F(GlossyCli, MatrixBakeFromMtlSpecularRendersAndValidates) {
  write("cube.mtl", "newmtl shiny\nKd 0.5 0.4 0.3\nKs 0.25 0.25 0.25\nNs 40\n");
  write("cube.obj", std::string("mtllib cube.mtl\nusemtl shiny\n") + kSharedObj);
  Result r =
      prt("bake cube.obj 'builtin:plane?y=-0.5&grid=8' --mode shadowed --transfer matrix "
          "--bands 3 --samples 64 -o out/g.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("shadowed matrix: 324 B per vertex"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("material from"), std::string::npos) << r.err;
  const BakeFile b = readBake(path("out/g.glb"));
  EXPECT_EQ(b.formatVersion, kBakeFormatVersion);
  ASSERT_EQ(b.transfers.size(), 1u);
  const Material& m = b.transfers[0].recipe.material;
  EXPECT_EQ(m.lobe.kind, LobeKind::Phong);
  EXPECT_FLOAT_EQ(float(m.lobe.exponent), 40.0f);
  EXPECT_FLOAT_EQ(m.specular.x, 0.25f);
  r = prt("info out/g.glb");
  EXPECT_NE(r.out.find("matrix (glossy)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("phong?exponent=40"), std::string::npos) << r.out;
  r =
      prt("render out/g.glb --light builtin:sky --size 64x48 --spp 1 "
          "--material 'ggx?roughness=0.4&ks=0.5' -o out/g.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("out/g.png")));
  r = prt("validate out/g.glb --light builtin:sky --reference-samples 32 --vertices 40");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("lobe energy > B"), std::string::npos) << r.out;
  // A matrix bake that would not fit a bake file is refused before any work, with the figure.
  r =
      prt("bake 'builtin:sphere?subdiv=7' --mode unshadowed --transfer matrix --bands 16 "
          "-o out/huge.glb");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("more than a bake file holds"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out/huge.glb")));
}

}  // namespace
}  // namespace prt
