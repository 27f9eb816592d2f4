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

namespace prt {
namespace {

std::string errorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

BakeFile tinyBake(double scale) {
  BakeFile b;
  b.mesh = builtinScene("builtin:sphere?subdiv=0");  // 12 vertices, 20 triangles
  for (Vec3f& p : b.mesh.positions) p = p * float(scale);
  b.mesh.source = "far.obj";  // the recorded source, not the file a user names
  b.vertexCount = b.mesh.vertexCount();
  BakedTransfer t;
  t.settings.mode = TransferMode::Unshadowed;
  t.settings.bands = 1;
  t.settings.samples = 16;
  t.settings.vertexCount = b.vertexCount;
  t.field.bands = 1;
  t.field.channels = 1;
  t.field.vertexCount = b.vertexCount;
  t.field.data.assign(b.vertexCount * t.field.stride(), 0.25f);
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

}  // namespace
}  // namespace prt
