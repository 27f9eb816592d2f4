// Environments that never show garbage (issue 16, items 9-10): an image whose every pixel is NaN
// or infinite is refused (it used to load as black and validate at 0 %), repaired pixels are
// reported in one line per file, and an SH projection that overflows names the input.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "common/scratch.hpp"
#include "prt/core/error.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/project.hpp"
#include "prt/image/image_io.hpp"
#include "support/hardening.hpp"

namespace prt::envmap {
namespace {

using test::errorOf;

TEST(EnvironmentReaders, AllNanIsRefusedSomeNanIsReported) {
  prt::testing::ScratchDir dir;
  image::Image img(8, 4);
  for (Rgb& p : img.pixels) p = Rgb(std::numeric_limits<float>::quiet_NaN());
  const std::string nan = dir / "nan.exr";
  image::writeImage(nan, img);
  EXPECT_EQ(errorOf([&] { loadEnvironment(nan); }),
            nan + ": every pixel (32) is NaN or infinite: the environment holds no light");
  img.pixels[5] = Rgb(1.0f);
  img.pixels[6] = Rgb(-2.0f);
  const std::string some = dir / "some.exr";
  image::writeImage(some, img);
  const LoadedEnvironment e = loadEnvironment(some);
  EXPECT_EQ(e.env.source(), some);
  const std::vector<std::string> w = repairWarnings(e);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], some + ": 30 non-finite and 1 negative pixels set to 0");
  // A black (but finite) image is light-less too, yet not garbage: it loads.
  image::Image black(8, 4);
  image::writeImage(dir / "black.exr", black);
  EXPECT_TRUE(repairWarnings(loadEnvironment(dir / "black.exr")).empty());
  // Builtins carry their name as the source.
  EXPECT_EQ(loadEnvironment("builtin:sky").env.source(), "builtin:sky");
}

TEST(EnvironmentReaders, ShOverflowNamesTheInput) {
  prt::testing::ScratchDir dir;
  // 16 x 8 RGBE pixels (255, 255, 255, 255): 1.7e38 each, finite and valid.
  std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n";
  for (int i = 0; i < 16 * 8; ++i) hdr += std::string(4, '\xff');
  const std::string p = dir.write("bright.hdr", hdr);
  const LoadedEnvironment e = loadEnvironment(p);
  const std::string msg = errorOf([&] { projectEnvironment(e.env, 3); });
  EXPECT_EQ(msg.rfind(p + ": projecting the environment onto SH overflowed", 0), 0u) << msg;
}

}  // namespace
}  // namespace prt::envmap
