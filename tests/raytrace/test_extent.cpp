// The Embree occluder refuses scenes whose coordinates it cannot trace (Embree asserts on ray
// origins beyond 1.844e18 and squared distances overflow floats far below), naming the figure,
// for meshes that never went through a loader (built in code, read from a bake file).

#include <gtest/gtest.h>

#include <string>

#include "prt/core/error.hpp"
#include "prt/raytrace/occluder.hpp"

namespace prt {
namespace {

TEST(EmbreeOccluder, RefusesCoordinatesBeyondTheTraceableExtent) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1e20f, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  m.source = "huge";
  std::string e;
  try {
    makeEmbreeOccluder(m);
  } catch (const Error& err) {
    e = err.what();
  }
  EXPECT_NE(e.find("huge: vertex 1 at (1e+20, 0, 0) lies outside the extent the ray tracer "
                   "handles (|coordinate| <= 1e+10, PRT_MAX_COORDINATE)"),
            std::string::npos)
      << e;
  m.positions[1].x = 1e6f;
  EXPECT_NO_THROW(makeEmbreeOccluder(m));
}

}  // namespace
}  // namespace prt
