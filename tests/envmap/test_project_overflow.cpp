// A valid but extremely bright environment overflows 32-bit sums: projection says so instead of
// returning inf coefficients (which `prt light` once wrote and `prt info` could not read).

#include <gtest/gtest.h>

#include <string>

#include "prt/core/error.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/envmap/project.hpp"
#include "prt/image/image_io.hpp"

namespace prt::envmap {
namespace {

TEST(ProjectOverflow, BrightestRadianceHdrGivesAClearErrorNotInf) {
  // 16 x 8 RGBE pixels (255, 255, 255, 255): 1.7e38 each, finite and valid.
  std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n";
  for (int i = 0; i < 16 * 8; ++i) hdr += std::string(4, '\xff');
  const image::Image img = image::readImageBytes(
      "bright.hdr", "hdr", {reinterpret_cast<const unsigned char*>(hdr.data()), hdr.size()});
  ASSERT_TRUE(std::isfinite(img.pixels[0].x));
  std::string e;
  try {
    projectEnvironment(Environment::latLong(img), 3);
  } catch (const Error& err) {
    e = err.what();
  }
  EXPECT_NE(e.find("projecting the environment onto SH overflowed"), std::string::npos) << e;
  // A bright but representable environment still projects.
  image::Image ok(16, 8);
  for (auto& p : ok.pixels) p = Rgb(1e30f);
  const sh::RgbSh c = projectEnvironment(Environment::latLong(ok), 3);
  EXPECT_TRUE(isFinite(c.c[0]));
  EXPECT_GT(c.c[0].x, 1e30f);
}

}  // namespace
}  // namespace prt::envmap
