// Mesh readers that never show garbage (issue 16, item 9): MTL numbers tinyobjloader would zero
// without a word are refused with their line; an .off.gz bomb stops at its header, not at the
// decompression cap; PRT_MAX_VERTICES / PRT_MAX_TRIANGLES apply to builtin scenes before they
// are built, exactly.

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>

#include "fixtures.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "support/hardening.hpp"

namespace prt {
namespace {

using test::errorOf;
using test::PeakAllocation;
using test::ScopedLimits;
using test::TempDir;

using test::gzipOf;

TEST(MeshReaders, MtlNumbersAreCheckedNotZeroed) {
  TempDir dir;
  const std::string obj =
      dir.write("m.obj", "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string mtl = (dir.path() / "m.mtl").string();
  const auto refused = [&](const std::string& text, const std::string& part) {
    SCOPED_TRACE(text);
    dir.write("m.mtl", text);
    const std::string e = errorOf([&] { loadMesh(obj); });
    EXPECT_EQ(e.rfind(mtl + ": line ", 0), 0u) << e;
    EXPECT_NE(e.find(part), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  refused("newmtl a\nKd nan 0.5 0.5\n", "line 2: Kd 'nan' is not a finite number");
  refused("newmtl a\nKd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs nan\n", "line 4: Ns 'nan'");
  refused("newmtl a\nKd 0.5 1e999 0.5\n", "'1e999' is not a finite number");
  refused("newmtl a\nKd 0.5\n", "Kd needs three numbers r g b, found 1");  // read (0.5, 0, 0)
  refused("newmtl a\nKd spectral ident.rfl\n", "'spectral' is not a finite number");
  refused("newmtl a\nNs 10 20\n", "Ns needs one number, found 2");
  refused("# x\nnewmtl a\n  Ks inf 0 0  # hot\n", "line 3: Ks 'inf'");
  // Good files still load: options before a value, comments, CRLF.
  dir.write("m.mtl", "newmtl a\r\nKd 0.5 0.25 0.125 # red-ish\r\nd -halo 0.5\r\nNs 32\r\n");
  const Mesh m = loadMesh(obj);
  ASSERT_EQ(m.albedo.size(), 3u);
  EXPECT_FLOAT_EQ(m.albedo[0].y, 0.25f);
  // (The in-memory reader the fuzzer uses is replayed with such a file: fuzz/corpus/obj.)
}

TEST(MeshReaders, OffGzipBombStopsAtTheHeader) {
  TempDir dir;
  // 32 MiB of zeros as .off.gz: refused after the first chunk, whatever the cap (it used to
  // inflate to PRT_MAX_DECOMPRESSED_BYTES first).
  const std::string zeros = dir.write("zeros.off.gz", gzipOf(std::string(32 << 20, '\0')));
  {
    PeakAllocation peak;
    const std::string e = errorOf([&] { loadMesh(zeros); });
    EXPECT_EQ(e, zeros +
                     ": gzip: the decompressed data does not start with an OFF header (OFF, "
                     "COFF, NOFF, CNOFF)");
    EXPECT_LT(peak.bytes(), 1u << 20);
  }
  // Blank space and comments forever: no header within 64 KiB.
  const std::string blank =
      dir.write("blank.off.gz", gzipOf("# a comment\n" + std::string(8 << 20, ' ')));
  {
    PeakAllocation peak;
    const std::string e = errorOf([&] { loadMesh(blank); });
    EXPECT_EQ(e, blank + ": gzip: no off header in the first 64 KiB of the decompressed data");
    EXPECT_LT(peak.bytes(), 1u << 20);
  }
  // A PLY inside an .off.gz is not an OFF either.
  const std::string ply = dir.write("ply.off.gz", gzipOf("ply\nformat ascii 1.0\n"));
  EXPECT_NE(errorOf([&] { loadMesh(ply); }).find("does not start with an OFF header"),
            std::string::npos);
  // Good ones: comments before the keyword, every keyword the reader takes.
  for (const std::string key : {"OFF", "COFF", "NOFF", "CNOFF"}) {
    std::string off = "# made by hand\n\n" + key + "\n3 1 0\n";
    for (int v = 0; v < 3; ++v) {
      off += v == 0 ? "0 0 0" : v == 1 ? "1 0 0" : "0 1 0";
      if (key.find('N') != std::string::npos) off += " 0 0 1";
      if (key.find('C') != std::string::npos) off += " 255 255 255";
      off += "\n";
    }
    off += "3 0 1 2\n";
    const std::string p = dir.write("good.off.gz", gzipOf(off));
    EXPECT_EQ(loadMesh(p).triangleCount(), 1u) << key;
  }
}

TEST(MeshReaders, VertexAndTriangleCapsApplyToBuiltinScenesBeforeTheyAreBuilt) {
  for (const std::string scene : {"builtin:sphere?subdiv=3", "builtin:sphere-plane?grid=7&subdiv=1",
                                  "builtin:plane?grid=9", "builtin:cornell?grid=11"}) {
    SCOPED_TRACE(scene);
    const Mesh m = builtinScene(scene);
    Limits l = limits();
    // The prediction is exact: the scene's own counts pass, one fewer is refused.
    l.maxVertices = m.vertexCount();
    l.maxTriangles = m.triangleCount();
    {
      ScopedLimits s(l);
      EXPECT_NO_THROW(loadMesh(scene));
    }
    l.maxVertices = m.vertexCount() - 1;
    {
      ScopedLimits s(l);
      const std::string e = errorOf([&] { loadMesh(scene); });
      EXPECT_EQ(e, scene + ": vertex count " + std::to_string(m.vertexCount()) +
                       " exceeds the limit of " + std::to_string(l.maxVertices) +
                       " (PRT_MAX_VERTICES)");
    }
    l.maxVertices = m.vertexCount();
    l.maxTriangles = m.triangleCount() - 1;
    {
      ScopedLimits s(l);
      EXPECT_NE(errorOf([&] { loadMesh(scene); }).find("(PRT_MAX_TRIANGLES)"), std::string::npos);
    }
  }
  // Refused before anything is built: the largest plane (4 M vertices) under a small cap.
  Limits l = limits();
  l.maxVertices = 1000;
  ScopedLimits s(l);
  PeakAllocation peak;
  EXPECT_NE(errorOf([] { loadMesh("builtin:plane?grid=2000"); }).find("PRT_MAX_VERTICES"),
            std::string::npos);
  EXPECT_LT(peak.bytes(), 1u << 16);
}

}  // namespace
}  // namespace prt
