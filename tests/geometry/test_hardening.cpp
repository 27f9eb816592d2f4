// Hostile and malformed mesh files (issue 11, docs/robustness.md): each class of failure the
// loaders once had — hangs, allocation before validation, stack overflow, silent corruption,
// extents the ray tracer cannot handle — with an input that triggered it. Every test fails if the
// class comes back: hangs end the program (finishesWithin), early allocations show in the
// allocation probe, and the messages must name the file and the problem on one line.

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>

#include "fixtures.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/load.hpp"
#include "support/hardening.hpp"

PRT_DEFINE_ALLOCATION_PROBE

namespace prt {
namespace {

using test::errorOf;
using test::finishesWithin;
using test::PeakAllocation;
using test::ScopedLimits;
using test::TempDir;

using test::gzipOf;

void expectOneLine(const std::string& e, const std::string& file, const std::string& part) {
  EXPECT_EQ(e.rfind(file + ": ", 0), 0u) << e;
  EXPECT_NE(e.find(part), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_LT(e.size(), 400u) << e;
}

const char* kPlyHead =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\n";
const char* kPlyFace = "element face 1\nproperty list uchar int vertex_indices\n";

// --- hangs ------------------------------------------------------------------------------------

TEST(Hardening, OddWhitespaceAndEmptyElementsDoNotHang) {
  TempDir dir;
  // A vertical tab or form feed ended a token but was not skipped: the OFF reader spun forever.
  for (const char* ws : {"\v", "\f", "\v\v \f\t"}) {
    const std::string off = std::string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2") + ws + "\n";
    const std::string p = dir.write("ws.off", off);
    const std::string e = finishesWithin(10, "OFF with odd whitespace",
                                         [&] { EXPECT_EQ(loadMesh(p).triangleCount(), 1u); });
    EXPECT_EQ(e, "");
    const std::string mid = dir.write(
        "mid.off", std::string("OFF\n3 1 0\n0") + ws + "0 0\n1 0 0\n0 1 0\n3" + ws + "0 1 2\n");
    EXPECT_EQ(finishesWithin(10, "OFF with odd whitespace inside lines",
                             [&] { EXPECT_EQ(loadMesh(mid).vertexCount(), 3u); }),
              "");
  }
  // An element with no properties and a count of 10^18 took 10^18 iterations to skip.
  for (const char* format : {"ascii", "binary_little_endian"}) {
    std::string ply = std::string("ply\nformat ") + format +
                      " 1.0\nelement junk 1000000000000000000\nelement vertex 3\nproperty float "
                      "x\nproperty float y\nproperty float z\n" +
                      kPlyFace + "end_header\n";
    if (std::string(format) == "ascii") {
      ply += "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    } else {
      const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
      ply.append(reinterpret_cast<const char*>(v), sizeof v);
      ply.push_back(3);
      const int idx[3] = {0, 1, 2};
      ply.append(reinterpret_cast<const char*>(idx), sizeof idx);
    }
    const std::string p = dir.write("junk.ply", ply);
    EXPECT_EQ(finishesWithin(10, std::string("PLY empty element, ") + format,
                             [&] { EXPECT_EQ(loadMesh(p).triangleCount(), 1u); }),
              "");
  }
  // A list length of 10^300 (ASCII) used to be cast to an integer and iterated.
  const std::string list =
      dir.write("list.ply", std::string(kPlyHead) + kPlyFace +
                                "end_header\n0 0 0\n1 0 0\n0 1 0\n1e300 0 1 2\n");
  expectOneLine(finishesWithin(10, "PLY huge list length", [&] { loadMesh(list); }), list,
                "list length 1e+300");
}

// --- memory spent before validation -----------------------------------------------------------

TEST(Hardening, DeclaredSizesAreCheckedBeforeAllocating) {
  TempDir dir;
  // A 400-odd byte glTF whose accessor claims 4e8 vertices took 4.5 GiB before failing: now
  // the vertex limit refuses 4e8, and a count under the limit is checked against the buffer.
  const auto withCount = [&](const std::string& count) {
    return dir.write("count" + count + ".gltf", R"({"asset":{"version":"2.0"},
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
"bufferViews":[{"buffer":0,"byteLength":36}],
"accessors":[{"bufferView":0,"componentType":5126,"count":)" +
                                                    count + R"(,"type":"VEC3"}]})");
  };
  {
    const std::string gltf = withCount("400000000");
    PeakAllocation peak;
    expectOneLine(errorOf([&] { loadMesh(gltf); }), gltf,
                  "vertex count 400000000 exceeds the limit of 134217728 (PRT_MAX_VERTICES)");
    EXPECT_LT(peak.bytes(), 1u << 20);
  }
  {
    const std::string gltf = withCount("100000000");
    PeakAllocation peak;
    expectOneLine(errorOf([&] { loadMesh(gltf); }), gltf,
                  "POSITION: accessor count 100000000 exceeds the 36 bytes of its buffer");
    EXPECT_LT(peak.bytes(), 1u << 20);
  }
  // PLY and OFF counts over the vertex cap are refused by the figure, not by bad_alloc.
  Limits small = limits();
  small.maxVertices = 2;
  {
    ScopedLimits scoped(small);
    const std::string ply = dir.write(
        "cap.ply", std::string(kPlyHead) + kPlyFace + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    expectOneLine(errorOf([&] { loadMesh(ply); }), ply,
                  "vertex count 3 exceeds the limit of 2 (PRT_MAX_VERTICES)");
    const std::string off = dir.write("cap.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    expectOneLine(errorOf([&] { loadMesh(off); }), off, "PRT_MAX_VERTICES");
  }
}

TEST(Hardening, GzipBombsStopAtTheCap) {
  TempDir dir;
  Limits small = limits();
  small.maxDecompressedBytes = 4 << 20;
  ScopedLimits scoped(small);
  // 64 MiB of a valid PLY comment inflating past a 4 MiB cap: stops at the cap.
  const std::string big = std::string("ply\ncomment ") + std::string(64 << 20, 'x') + "\n";
  const std::string p = dir.write("bomb.ply.gz", gzipOf(big));
  {
    PeakAllocation peak;
    expectOneLine(errorOf([&] { loadMesh(p); }), p,
                  "decompresses to more than 4194304 bytes (PRT_MAX_DECOMPRESSED_BYTES)");
    EXPECT_LT(peak.bytes(), 16u << 20);
  }
  // Zeros are not a PLY: refused after the first chunk, whatever the cap.
  const std::string zeros = dir.write("zeros.ply.gz", gzipOf(std::string(32 << 20, '\0')));
  {
    PeakAllocation peak;
    expectOneLine(errorOf([&] { loadMesh(zeros); }), zeros, "does not start with 'ply'");
    EXPECT_LT(peak.bytes(), 1u << 20);
  }
}

// --- crashes ----------------------------------------------------------------------------------

std::string gltfWithNodes(const std::string& nodes, const std::string& extras = "0") {
  return R"({"asset":{"version":"2.0"},"extras":)" + extras +
         R"(,"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)" + nodes +
         R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
"bufferViews":[{"buffer":0,"byteLength":36}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}]})";
}

TEST(Hardening, DeepNestingIsRefusedNotAStackOverflow) {
  TempDir dir;
  // A chain of 100 000 nodes (each the child of the one before) recursed once per level.
  std::string chain;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    if (i) chain += ',';
    chain += R"({"children":[)";
    if (i + 1 < n) chain += std::to_string(i + 1);
    chain += ']';
    if (i + 1 == n) chain += R"(,"mesh":0)";
    chain += '}';
  }
  const std::string deep = dir.write("chain.gltf", gltfWithNodes(chain));
  expectOneLine(errorOf([&] { loadMesh(deep); }), deep, "scene graph deeper than 256 levels");
  // JSON nested 20 000 deep in extras: tinygltf recursed into it and overflowed the stack.
  const std::string nested =
      dir.write("nested.gltf",
                gltfWithNodes(R"({"mesh":0})", std::string(20000, '[') + std::string(20000, ']')));
  expectOneLine(errorOf([&] { loadMesh(nested); }), nested,
                "JSON nested deeper than 256 levels (PRT_MAX_NESTING)");
  // 64 levels, each node listing the next twice: 2^64 paths through a 64-node graph.
  std::string dag;
  for (int i = 0; i < 64; ++i) {
    if (i) dag += ',';
    dag += R"({"children":[)";
    if (i + 1 < 64) dag += std::to_string(i + 1) + "," + std::to_string(i + 1);
    dag += "]}";
  }
  const std::string bomb = dir.write("dag.gltf", gltfWithNodes(dag));
  expectOneLine(finishesWithin(20, "glTF shared-subtree bomb", [&] { loadMesh(bomb); }), bomb,
                "instantiates more than");
  // Within the limits a scene still loads (the same file with a chain of 10 nodes).
  std::string shortChain;
  for (int i = 0; i < 10; ++i)
    shortChain += (i ? "," : "") + std::string(R"({"children":[)") +
                  (i + 1 < 10 ? std::to_string(i + 1) : "") + "]" +
                  (i + 1 == 10 ? R"(,"mesh":0)" : "") + "}";
  EXPECT_EQ(loadMesh(dir.write("ok.gltf", gltfWithNodes(shortChain))).triangleCount(), 1u);
}

// --- silent corruption ------------------------------------------------------------------------

TEST(Hardening, OverflowingIndicesAndNonFiniteValuesAreRejectedByName) {
  TempDir dir;
  // 2^32 + 1 wrapped to vertex 1 and was baked as a valid face.
  const std::string wrap = dir.write("wrap.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 4294967297 2 3\n");
  expectOneLine(errorOf([&] { loadMesh(wrap); }), wrap,
                "line 4: index '4294967297' is not an integer in the 32-bit range");
  const std::string wrapN =
      dir.write("wrapn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//99999999999 3//1\n");
  expectOneLine(errorOf([&] { loadMesh(wrapN); }), wrapN, "line 5: index '99999999999'");
  // Non-finite normals and texture coordinates, by line in OBJ.
  const std::string vn =
      dir.write("vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 nan 1\nf 1//1 2//1 3//1\n");
  expectOneLine(errorOf([&] { loadMesh(vn); }), vn, "line 4: normal component 'nan'");
  const std::string vt =
      dir.write("vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 1e999 0\nf 1/1 2/1 3/1\n");
  expectOneLine(errorOf([&] { loadMesh(vt); }), vt, "line 4: texture coordinate '1e999'");
  // An MTL Kd of 1e30 gave a bake with non-finite transfer.
  dir.write("big.mtl", "newmtl hot\nKd 1e30 0.5 0.5\n");
  const std::string kd =
      dir.write("kd.obj", "mtllib big.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl hot\nf 1 2 3\n");
  expectOneLine(errorOf([&] { loadMesh(kd); }), kd,
                "material 'hot': Kd (1e+30, 0.5, 0.5) is not a colour");
  // PLY and OFF: non-finite normals, uvs and colours are named with their vertex.
  const std::string plyN = dir.write(
      "n.ply", std::string(kPlyHead) + "property float nx\nproperty float ny\nproperty float nz\n" +
                   kPlyFace + "end_header\n0 0 0 0 0 1\n1 0 0 0 inf 1\n0 1 0 0 0 1\n3 0 1 2\n");
  expectOneLine(errorOf([&] { loadMesh(plyN); }), plyN, "vertex 1 has a non-finite normal");
  const std::string plyUv = dir.write(
      "uv.ply", std::string(kPlyHead) + "property float u\nproperty float v\n" + kPlyFace +
                    "end_header\n0 0 0 0 0\n1 0 0 0 0\n0 1 0 nan 0\n3 0 1 2\n");
  expectOneLine(errorOf([&] { loadMesh(plyUv); }), plyUv,
                "vertex 2 has a non-finite texture coordinate");
  const std::string offC =
      dir.write("c.off", "COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 nan 1 1\n0 1 0 1 1 1\n3 0 1 2\n");
  expectOneLine(errorOf([&] { loadMesh(offC); }), offC, "vertex 1 colour 'nan'");
}

// --- extents the ray tracer cannot handle -----------------------------------------------------

TEST(Hardening, CoordinatesBeyondTheRayTracersRangeAreRejectedWithTheFigure) {
  TempDir dir;
  // Finite but huge: Embree asserted (ray.valid()) at 1e19 and rendered black below it.
  const std::string far = dir.write("far.obj", "v 0 0 0\nv 3e13 0 0\nv 0 1 0\nf 1 2 3\n");
  expectOneLine(errorOf([&] { loadMesh(far); }), far,
                "vertex 1 at (3e+13, 0, 0) lies outside the extent the ray tracer handles "
                "(|coordinate| <= 1e+10, PRT_MAX_COORDINATE)");
  // The same scene scaled into range loads.
  EXPECT_NO_THROW(loadMesh(dir.write("near.obj", "v 0 0 0\nv 3e9 0 0\nv 0 3e9 0\nf 1 2 3\n")));
}

}  // namespace
}  // namespace prt
