// prt view with finite but absurd values (issue 16, item 5): at the exposure limit and under a
// light of 1e20 the relit surface shows white, as prt render's PNG does, where the shared tone
// map (shaders/prt_display.glsl) used to overflow to black.

#include <fstream>

#include "viewer_test_util.hpp"

namespace prt::viewer::test {
namespace {

TEST(ViewSaturation, AbsurdExposureAndLightShowWhite) {
  PRT_REQUIRE_HEADLESS_GL();
  std::string light = "{\"bands\": 3, \"coefficients\": [[1e20, 1e20, 1e20]";
  for (int i = 1; i < 9; ++i) light += ", [0, 0, 0]";
  std::ofstream(path("l20.json")) << light << "]}\n";
  for (const char* tm : {"aces", "reinhard", "clamp"})
    for (const std::string& args : {std::string("--exposure 63"), std::string("--exposure 64"),
                                    std::string("--light l20.json --exposure 64")}) {
      SCOPED_TRACE(std::string(tm) + " " + args);
      const Result v = prt("-q view '" + spherePlaneBake() +
                           "' --headless --size 64x48 --background none --tonemap " + tm + " " +
                           args + " --screenshot sat.png");
      ASSERT_EQ(v.rc, 0) << v.err;
      const image::Image img = image::readImage(path("sat.png"));  // 255 decodes to exactly 1
      const Rgb c = img.at(img.width / 2, img.height / 2);
      EXPECT_EQ(c.x, 1.0f);
      EXPECT_EQ(c.y, 1.0f);
      EXPECT_EQ(c.z, 1.0f);
    }
}

}  // namespace
}  // namespace prt::viewer::test
