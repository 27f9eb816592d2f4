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
  EXPECT_EQ(w[0], some +
                      ": 30 pixels with NaN/Inf set to 0, 1 pixels with negative values clamped "
                      "to 0 (66.7% of its light)");
  // Negatives as small as lossy compression leaves (here 1e-5 of the light) are clamped
  // silently; past kNegativeLightWarning they are said.
  image::Image grey(8, 4, Rgb(1.0f));
  grey.pixels[3] = Rgb(-3.2e-4f / 3, 0.0f, 0.0f);  // 1.1e-4 / 96 ≈ 1.1e-6 of the light
  image::writeImage(dir / "residue.exr", grey);
  const LoadedEnvironment residue = loadEnvironment(dir / "residue.exr");
  EXPECT_TRUE(repairWarnings(residue).empty());
  EXPECT_TRUE(anyPixelRepaired(residue));
  grey.pixels[3] = Rgb(-0.1f, 0.0f, 0.0f);  // 0.1 / 93.1 ≈ 1.1e-3 of the light
  image::writeImage(dir / "negative.exr", grey);
  const std::vector<std::string> said = repairWarnings(loadEnvironment(dir / "negative.exr"));
  ASSERT_EQ(said.size(), 1u);
  EXPECT_NE(said[0].find("1 pixels with negative values clamped to 0 (0.107% of its light)"),
            std::string::npos)
      << said[0];
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
