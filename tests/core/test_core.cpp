#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/scratch.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/progress.hpp"
#include "prt/core/vec.hpp"

using namespace prt;

TEST(Vec, RotationIsOrthonormalAndRightHanded) {
  const Mat3d r = rotationAxisAngle({0, 0, 1}, kPi / 2);
  const Vec3d x = r * Vec3d(1, 0, 0);
  EXPECT_NEAR(x.x, 0, 1e-15);
  EXPECT_NEAR(x.y, 1, 1e-15);  // +X turns to +Y about +Z
  const Mat3d e = rotationEulerXYZ(10, 20, 30);
  const Mat3d i = e * e.transposed();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(i.m[a][b], a == b ? 1 : 0, 1e-14);
}

TEST(Vec, OrthonormalBasis) {
  for (Vec3f n : {Vec3f(0, 0, 1), Vec3f(0, 0, -1), normalize(Vec3f(1, 2, -3)), Vec3f(1, 0, 0)}) {
    Vec3f t, b;
    orthonormalBasis(n, t, b);
    EXPECT_NEAR(dot(t, n), 0, 1e-6);
    EXPECT_NEAR(dot(b, n), 0, 1e-6);
    EXPECT_NEAR(dot(t, b), 0, 1e-6);
    EXPECT_NEAR(length(t), 1, 1e-6);
    const Vec3f c = cross(t, b);
    EXPECT_NEAR(dot(c, n), 1, 1e-5);
  }
}

TEST(Parallel, ReduceIsIndependentOfThreadCount) {
  auto run = [](int threads) {
    ThreadLimit limit(threads);
    return parallelReduce<double>(
        100000, 1000, 0.0,
        [](std::size_t b, std::size_t e, double& acc) {
          for (std::size_t i = b; i < e; ++i) acc += 1.0 / (1.0 + double(i) * 0.37);
        },
        [](double& t, double p) { t += p; });
  };
  const double a = run(1), b = run(2);
  EXPECT_EQ(a, b);  // bit-identical
}

TEST(Progress, CancelThrows) {
  int calls = 0;
  Progress p([&](double) { return ++calls < 2; }, 1000);
  EXPECT_NO_THROW(p.advance(1));
  EXPECT_THROW(p.advance(500), Cancelled);
}

TEST(File, AtomicWriteLeavesNothingOnFailure) {
  const prt::testing::ScratchDir scratch;
  const std::filesystem::path& dir = scratch.path();
  const std::string path = (dir / "out.txt").string();
  std::filesystem::remove(path);
  EXPECT_THROW(writeFileAtomically(path,
                                   [](std::ostream& o) {
                                     o << "partial";
                                     throw Error("boom");
                                   }),
               Error);
  EXPECT_FALSE(std::filesystem::exists(path));
  for (auto& e : std::filesystem::directory_iterator(dir))
    ADD_FAILURE() << "left behind " << e.path();
  writeFileAtomically(path, std::string_view("hello"));
  EXPECT_EQ(readFileBytes(path).size(), 5u);
  EXPECT_THROW(writeFileAtomically((dir / "no/such/dir/x").string(), std::string_view("x")), Error);
  EXPECT_THROW(readFileBytes((dir / "missing").string()), Error);
  EXPECT_EQ(fileExtension("a/b/C.HDR"), "hdr");
}
