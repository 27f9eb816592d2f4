// io readers that never show garbage (issue 16, items 8-10): a truncated transport.txt is not
// re-read as the other layout, a truncated light.txt is not a smaller light, and a bake file is
// held to the vertex, triangle and coordinate caps by the name it was given.

#include <gtest/gtest.h>

#include <string>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/games202_transport.hpp"
#include "prt/io/light_file.hpp"
#include "support/hardening.hpp"

namespace prt {
namespace {

using test::errorOf;

BakeFile tinyBake(double scale) {
  BakeFile b;
  b.mesh = builtinScene("builtin:sphere?subdiv=0");  // 12 vertices, 20 triangles
  for (Vec3f& p : b.mesh.positions) p = p * float(scale);
  b.mesh.source = "far.obj";  // the recorded source, not the file a user names
  BakedTransfer t;
  t.recipe.mode = TransferMode::Unshadowed;
  t.recipe.samples = 16;
  TransferShape shape;
  shape.bands = 1;
  shape.rows = {0, b.mesh.vertexCount()};
  t.transfer = Transfer::zeros(shape);
  b.transfers.push_back(t);
  return b;
}

std::span<const unsigned char> bytesOf(const std::string& s) {
  return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

TEST(ReadersIo, BakeFilesAreHeldToTheCapsByTheNameGiven) {
  const std::string ok = encodeBake(tinyBake(1.0));
  EXPECT_EQ(decodeBake(bytesOf(ok), "given.glb").mesh.vertexCount(), 12u);
  // Coordinates beyond PRT_MAX_COORDINATE: refused on reading, naming the file given.
  const std::string far = encodeBake(tinyBake(1e12));
  const std::string e = errorOf([&] { decodeBake(bytesOf(far), "given.glb"); });
  EXPECT_EQ(e.rfind("given.glb: vertex ", 0), 0u) << e;
  EXPECT_NE(e.find("PRT_MAX_COORDINATE"), std::string::npos) << e;
  EXPECT_EQ(e.find("far.obj"), std::string::npos) << e;
  // PRT_MAX_VERTICES and PRT_MAX_TRIANGLES apply to bakes as to every mesh file.
  const Limits saved = limits();
  Limits l = saved;
  l.maxVertices = 11;
  setLimits(l);
  EXPECT_EQ(errorOf([&] { decodeBake(bytesOf(ok), "given.glb"); }),
            "given.glb: vertex count 12 exceeds the limit of 11 (PRT_MAX_VERTICES)");
  l.maxVertices = 12;
  l.maxTriangles = 19;
  setLimits(l);
  EXPECT_EQ(errorOf([&] { decodeBake(bytesOf(ok), "given.glb"); }),
            "given.glb: triangle count 20 exceeds the limit of 19 (PRT_MAX_TRIANGLES)");
  l.maxTriangles = 20;
  setLimits(l);
  EXPECT_NO_THROW(decodeBake(bytesOf(ok), "given.glb"));
  setLimits(saved);
}

TEST(ReadersIo, TruncatedTransportIsNotReadAsTheOtherLayout) {
  const auto rows = [](int n, const std::string& row) {
    std::string s;
    for (int i = 0; i < n; ++i) s += row + "\n";
    return s;
  };
  // Six vertices, one line each; cut to three lines (a multiple of 3) it used to read as the
  // faces of one triangle.
  const std::string full = "6\n" + rows(6, "1 0 0 0 ");
  EXPECT_EQ(parseGames202Transport(full, "t.txt").layout, Games202Layout::Vertices);
  const std::string cut = "6\n" + rows(3, "1 0 0 0 ");
  const std::string e = errorOf([&] { parseGames202Transport(cut, "t.txt"); });
  EXPECT_EQ(e.rfind("t.txt: 3 coefficient lines: neither one per vertex (6) nor three per "
                    "triangle corner",
                    0),
            0u)
      << e;
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  // Cut inside a line: the last line has no newline, whatever the count says.
  const std::string mid = "2\n1 0 0 0 \n0.5 0 0 0.12";
  EXPECT_EQ(errorOf([&] { parseGames202Transport(mid, "m.txt"); }),
            "m.txt: the last line has no newline: the file is truncated");
  // The course's faces file (more lines than vertices) and CRLF files still read.
  EXPECT_EQ(parseGames202Transport("3\n" + rows(6, "1 0 0 0 "), "f.txt").layout,
            Games202Layout::Faces);
  EXPECT_EQ(parseGames202Transport("1\r\n1 \r\n1 \r\n1 \r\n", "c.txt").layout,
            Games202Layout::Faces);
}

TEST(ReadersIo, TruncatedLightTxtIsNotASmallerLight) {
  std::string full;
  for (int i = 0; i < 16; ++i) full += "0.5 0.25 0." + std::to_string(i + 10) + "\n";
  EXPECT_EQ(io::parseLightGames202(full, "l.txt").bands, 4);
  // Cut inside the ninth line's last number: nine complete-looking lines, a square count.
  const std::size_t ninth = [&] {
    std::size_t p = 0;
    for (int i = 0; i < 8; ++i) p = full.find('\n', p) + 1;
    return p;
  }();
  const std::string cut = full.substr(0, ninth + std::string("0.5 0.25 0.1").size());
  const std::string e = errorOf([&] { io::parseLightGames202(cut, "l.txt"); });
  EXPECT_EQ(e,
            "l.txt: line 9 has no newline: the file is truncated (every light.txt line ends "
            "with one)");
  // Complete files, with trailing blank space, CRLF, or a blank last line, still read.
  EXPECT_EQ(io::parseLightGames202(full.substr(0, ninth + 14) + "  \n", "l.txt").bands, 3);
  EXPECT_EQ(io::parseLightGames202("1 2 3\r\n", "l.txt").bands, 1);
  EXPECT_EQ(io::parseLightGames202("1 2 3\n\n", "l.txt").bands, 1);
}

}  // namespace
}  // namespace prt
