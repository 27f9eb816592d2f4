// Core pieces of "readers that never show garbage" (issue 16): the coordinate cap cannot be
// raised past what Embree traces, a spec key given twice is refused, a FIFO is refused instead
// of blocking in open(), and an internal error names a source file relative to the tree.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "common/scratch.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/core/spec.hpp"
#include "support/hardening.hpp"

namespace prt {
namespace {

using test::errorOf;

TEST(ReadersCore, CoordinateCapStopsWhereEmbreeStops) {
  // Embree aborts (ray.valid()) on origins past 1.844e18; the camera stands several radii out.
  EXPECT_LE(kMaxTraceableCoordinate * 10, 1.844e18);
  ::setenv("PRT_MAX_COORDINATE", "1e17", 1);
  EXPECT_EQ(limitsFromEnvironment().maxCoordinate, 1e17);
  for (const char* beyond : {"1.1e17", "1e19", "1e30", "3e38"}) {
    ::setenv("PRT_MAX_COORDINATE", beyond, 1);
    const std::string e = errorOf([] { limitsFromEnvironment(); });
    EXPECT_EQ(e.rfind("PRT_MAX_COORDINATE: ", 0), 0u) << e;
    EXPECT_NE(e.find("beyond the ray tracer's range (at most 1e+17"), std::string::npos) << e;
  }
  ::unsetenv("PRT_MAX_COORDINATE");
  const Limits saved = limits();
  Limits l = saved;
  l.maxCoordinate = 1e18;
  EXPECT_NE(errorOf([&] { setLimits(l); }).find("ray tracer's range"), std::string::npos);
  EXPECT_EQ(limits().maxCoordinate, saved.maxCoordinate);  // refused, not applied
  l.maxCoordinate = kMaxTraceableCoordinate;
  EXPECT_NO_THROW(setLimits(l));
  setLimits(saved);
}

TEST(ReadersCore, SpecKeyGivenTwiceIsRefused) {
  const std::string e = errorOf([] { Spec("phong?exponent=16&exponent=32"); });
  EXPECT_EQ(e, "phong?exponent=16&exponent=32: parameter 'exponent' is given twice");
  EXPECT_NE(errorOf([] {
              Spec("builtin:sphere?subdiv=1&r=2&subdiv=1", "builtin:");
            }).find("'subdiv' is given twice"),
            std::string::npos);
  Spec ok("phong?exponent=16&ks=0.5");
  EXPECT_EQ(ok.number("exponent", 1, 0, 100), 16);
}

TEST(ReadersCore, FifoIsRefusedNotWaitedFor) {
  prt::testing::ScratchDir dir;
  const std::string fifo = dir / "light.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // No writer: open() on the FIFO would block forever; a regression ends the program with a
  // failure instead of hanging it.
  const std::string e =
      test::finishesWithin(10, "readFileBytes on a FIFO", [&] { readFileBytes(fifo); });
  EXPECT_EQ(e, fifo + ": is not a regular file (a pipe, device or socket); give a file");
  EXPECT_NE(errorOf([] { readFileBytes("/dev/null"); }).find("not a regular file"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { readFileBytes(dir.path().string()); }).find("is a directory"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { readFileBytes(dir / "missing.bin"); }).find("cannot open"),
            std::string::npos);
}

// mapFile refuses what readFileBytes refuses, by the same words, and maps what it reads.
TEST(ReadersCore, MappingAFileRefusesWhatReadingRefuses) {
  prt::testing::ScratchDir dir;
  const std::string fifo = dir / "bake.glb";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto map = [](const std::string& path, std::uint64_t cap = 1 << 20) {
    return mapFile(path, cap, "the test's cap");
  };
  EXPECT_EQ(test::finishesWithin(10, "mapFile on a FIFO", [&] { map(fifo); }),
            fifo + ": is not a regular file (a pipe, device or socket); give a file");
  EXPECT_NE(errorOf([&] { map("/dev/null"); }).find("not a regular file"), std::string::npos);
  EXPECT_NE(errorOf([&] { map(dir.path().string()); }).find("is a directory"), std::string::npos);
  EXPECT_NE(errorOf([&] { map(dir / "missing.bin"); }).find("cannot open"), std::string::npos);
  const std::string five = dir.write("five.bin", "12345");
  EXPECT_NE(errorOf([&] { map(five, 4); }).find("the test's cap"), std::string::npos);
  const auto mapped = map(five);
  EXPECT_EQ(std::string(mapped->bytes().begin(), mapped->bytes().end()), "12345");
  EXPECT_TRUE(map(dir.write("empty.bin", ""))->bytes().empty());
}

TEST(ReadersCore, InternalErrorsNameSourcesRelativeToTheTree) {
  const std::string e = errorOf([] { PRT_CHECK(1 + 1 == 3, "arithmetic"); });
  EXPECT_NE(e.find("internal error: arithmetic"), std::string::npos) << e;
  EXPECT_NE(e.find("tests/core/test_readers_core.cpp:"), std::string::npos) << e;
  EXPECT_EQ(e.find(PRT_SOURCE_DIR), std::string::npos) << e;
}

}  // namespace
}  // namespace prt
