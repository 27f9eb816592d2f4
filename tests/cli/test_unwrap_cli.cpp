// prt unwrap (issue 18): the mesh with a generated lightmap UV set as a plain glTF binary that
// prtkit's loader reads back exactly (positions, the atlas as TEXCOORD_1) and a per-texel bake
// takes as it is; figures on stderr, none with -q; and every refusal in one line with no
// output left behind.

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "prt/core/limits.hpp"
#include "prt/core/units.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/unwrap/charts.hpp"
#include "prt/unwrap/unwrap.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using UnwrapCli = CliTest;

TEST_F(UnwrapCli, WritesAPlainGltfThatLoadsBackWithTheAtlas) {
  const Result r = prt("unwrap builtin:sphere --resolution 256 --padding 3 -o atlas.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << "figures go to stderr";
  for (const char* figure : {"charts", "wasted", "texel density", "L2 stretch", "wrote atlas.glb"})
    EXPECT_NE(r.err.find(figure), std::string::npos) << figure << " missing in: " << r.err;
  // A plain glTF: no prtkit extension.
  EXPECT_EQ(slurp(dir_ / "atlas.glb").find("PRTKIT"), std::string::npos);

  const Mesh loaded = loadMesh(path("atlas.glb"));
  UnwrapSettings s;
  s.resolution = 256;
  s.padding = 3;
  const UnwrapResult expected = unwrap(loadMesh("builtin:sphere"), s);
  ASSERT_EQ(loaded.vertexCount(), expected.mesh.vertexCount());
  EXPECT_EQ(loaded.positions, expected.mesh.positions);
  EXPECT_EQ(loaded.triangles, expected.mesh.triangles);
  EXPECT_EQ(loaded.lightmapUvs, expected.mesh.lightmapUvs);
  // Without a texture set of its own, TEXCOORD_0 carries the atlas too (glTF numbers sets from 0).
  EXPECT_EQ(loaded.uvs, expected.mesh.lightmapUvs);
  EXPECT_NO_THROW(checkLightmapUvs(loaded, loaded.lightmapUvs, 256, 256, "TEXCOORD_1"));
  // prt info takes it for the mesh it is, and finds the atlas.
  const Result info = prt("info atlas.glb --resolution 256");
  ASSERT_EQ(info.rc, 0) << info.err;
  EXPECT_NE(info.out.find("atlas.glb: mesh"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("lightmap UVs at 256x256"), std::string::npos) << info.out;
  // The atlas is what a per-texel bake needs: it takes the file as it is.
  const Result b =
      prt("-q bake atlas.glb --mode unshadowed --domain texels --resolution 256 "
          "--padding 3 --samples 4 -o texels.glb");
  ASSERT_EQ(b.rc, 0) << b.err;
  const BakeFile bake = readBake(path("texels.glb"));
  EXPECT_EQ(bake.domain(), TransferDomain::Texels);
  EXPECT_EQ(bake.mesh.lightmapUvs, expected.mesh.lightmapUvs);
}

TEST_F(UnwrapCli, KeepsTheTextureSetAndIsQuietWithQ) {
  // A cube whose OBJ texture coordinates put every face on the same square (overlapping: no
  // lightmap can use them); the atlas is new, the texture set kept vertex for vertex.
  write("cube.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "f 1/1 4/4 3/3 2/2\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\n"
        "f 3/1 4/2 8/3 7/4\nf 2/1 3/2 7/3 6/4\nf 4/1 1/2 5/3 8/4\n");
  const Result r = prt("-q unwrap cube.obj -o cube.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const Mesh in = loadMesh(path("cube.obj"));
  const UnwrapResult expected = unwrap(in);
  const Mesh out = loadMesh(path("cube.glb"));
  EXPECT_EQ(expected.stats.charts, 6u) << "a cube is six charts";
  ASSERT_EQ(out.vertexCount(), expected.mesh.vertexCount());
  EXPECT_EQ(out.uvs, expected.mesh.uvs);
  for (std::size_t v = 0; v < out.vertexCount(); ++v)
    EXPECT_EQ(out.uvs[v], in.uvs[expected.sourceVertex[v]]);
  EXPECT_EQ(out.lightmapUvs, expected.mesh.lightmapUvs);
  EXPECT_NO_THROW(checkLightmapUvs(out, out.lightmapUvs, 512, 512, "TEXCOORD_1"));
}

TEST_F(UnwrapCli, RefusesInOneLineAndWritesNothing) {
  expectCleanFailure("unwrap missing.obj -o out/x.glb", "missing.obj");
  expectCleanFailure("unwrap builtin:sphere --resolution 0 -o out/x.glb", "--resolution");
  expectCleanFailure("unwrap builtin:sphere --resolution many -o out/x.glb", "--resolution");
  expectCleanFailure("unwrap builtin:sphere --padding 65 -o out/x.glb", "--padding");
  expectCleanFailure("unwrap builtin:sphere --max-cone 90 -o out/x.glb", "--max-cone");
  expectCleanFailure("unwrap builtin:sphere --max-chart-triangles -1 -o out/x.glb",
                     "--max-chart-triangles");
  expectCleanFailure("unwrap builtin:sphere -o out/x.png", "must end in .glb");
  expectCleanFailure("unwrap builtin:sphere --resolution 8 -o out/x.glb", "raise the resolution");
  // Over its own input: refused, the input untouched.
  ASSERT_EQ(prt("-q unwrap builtin:plane -o plane.glb").rc, 0);
  const std::string before = slurp(dir_ / "plane.glb");
  expectCleanFailure("unwrap plane.glb -o ./plane.glb", "would overwrite the input");
  EXPECT_EQ(slurp(dir_ / "plane.glb"), before);
}

// Issue 31: one line stating the peak memory before the heavy work, then progress lines with an
// ETA over the whole run, their percentages only ever rising; neither with -q.
TEST_F(UnwrapCli, StatesItsMemoryFirstThenProgressUnlessQuiet) {
  const std::string args = "-j 1 unwrap builtin:sphere?subdiv=4 -o s.glb";
  Result r = prt(args, "PRT_PROGRESS_INTERVAL=0 ");
  ASSERT_EQ(r.rc, 0) << r.err;
  // The figure is the library's estimate for this mesh, its charts and one thread.
  const Mesh mesh = loadMesh("builtin:sphere?subdiv=4");
  const TriangleAdjacency adj = buildAdjacency(mesh);
  const UnwrapSettings s;
  const ChartSegmentation seg = boundCharts(
      mesh, adj, growCharts(adj, s.maxConeDegrees * M_PI / 180.0, s.minChartTriangles),
      s.maxChartTriangles);
  std::vector<std::size_t> sizes(seg.count, 0);
  for (std::uint32_t c : seg.chartOfTriangle) ++sizes[c];
  const UnwrapFootprint f = unwrapFootprint(mesh, sizes, 1);
  const std::string memory = "about " + bytesText(f.bytes()) + " of memory at peak";
  const std::size_t at = r.err.find(memory);
  ASSERT_NE(at, std::string::npos) << memory << " missing in: " << r.err;
  // Progress lines "unwrap: 35% (0 s, ETA 1 s)", all after the memory line, rising.
  std::vector<int> pct;
  std::size_t first = std::string::npos;
  for (std::size_t p = r.err.find("unwrap: "); p != std::string::npos;
       p = r.err.find("unwrap: ", p + 1)) {
    const char* c = r.err.c_str() + p + 8;
    if (!std::isdigit(static_cast<unsigned char>(*c))) continue;
    char* end = nullptr;
    const long v = std::strtol(c, &end, 10);
    if (*end != '%') continue;
    if (first == std::string::npos) first = p;
    pct.push_back(int(v));
  }
  ASSERT_GE(pct.size(), 3u) << "progress over the phases, not one jump: " << r.err;
  EXPECT_LT(at, first) << "the memory line comes before the work: " << r.err;
  for (std::size_t i = 1; i < pct.size(); ++i) EXPECT_LT(pct[i - 1], pct[i]) << r.err;
  EXPECT_GE(pct.back(), 90) << "the progress covers the whole run: " << r.err;
  EXPECT_NE(r.err.find(", ETA "), std::string::npos) << r.err;
  // -q: neither the memory line nor progress, nothing at all.
  r = prt("-q " + args, "PRT_PROGRESS_INTERVAL=0 ");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  // The policy the estimate is held to (the bake's): refused above 90% of the machine.
  EXPECT_TRUE(fitsInMemory(f.bytes()));
  EXPECT_FALSE(fitsInMemory(physicalMemoryBytes()));
}

}  // namespace
}  // namespace prt
