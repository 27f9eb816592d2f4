// The resource policy (prt/core/limits.hpp): environment overrides and the JSON depth scan.

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"

namespace prt {
namespace {

std::string errorOf(void (*fn)()) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Limits, EnvironmentOverridesEachCapAndRejectsNonsense) {
  ::setenv("PRT_MAX_IMAGE_SIDE", "123", 1);
  ::setenv("PRT_MAX_COORDINATE", "1e6", 1);
  const Limits l = limitsFromEnvironment();
  EXPECT_EQ(l.maxImageSide, 123u);
  EXPECT_EQ(l.maxCoordinate, 1e6);
  EXPECT_EQ(l.maxVertices, Limits{}.maxVertices);
  for (const char* bad : {"-5", "0", "12abc", "99999999999999999999999"}) {
    ::setenv("PRT_MAX_IMAGE_SIDE", bad, 1);
    EXPECT_EQ(errorOf([] { limitsFromEnvironment(); }),
              std::string("PRT_MAX_IMAGE_SIDE: '") + bad + "' is not a positive whole number");
  }
  ::unsetenv("PRT_MAX_IMAGE_SIDE");
  ::setenv("PRT_MAX_COORDINATE", "inf", 1);
  EXPECT_NE(errorOf([] { limitsFromEnvironment(); }).find("PRT_MAX_COORDINATE"), std::string::npos);
  ::unsetenv("PRT_MAX_IMAGE_SIDE");
  ::unsetenv("PRT_MAX_COORDINATE");
}

TEST(Limits, CheckImageSizeNamesTheLimitThatIsExceeded) {
  const Limits saved = limits();
  Limits l;
  l.maxImageSide = 100;
  l.maxImagePixels = 1000;
  setLimits(l);
  EXPECT_NO_THROW(checkImageSize("a.png", 100, 10));
  EXPECT_EQ(errorOf([] { checkImageSize("a.png", 101, 1); }),
            "a.png: image size 101x1 exceeds the limit of 100 pixels a side (PRT_MAX_IMAGE_SIDE)");
  EXPECT_EQ(errorOf([] { checkImageSize("a.png", 100, 11); }),
            "a.png: image size 100x11 exceeds the limit of 1000 pixels (PRT_MAX_IMAGE_PIXELS)");
  setLimits(saved);
}

TEST(Limits, JsonDepthScanIgnoresStringsAndStopsEarly) {
  EXPECT_EQ(jsonNestingDepth(R"({"a": [1, {"b": "[[[[\"]]"}]})", 100), 3u);
  EXPECT_EQ(jsonNestingDepth("", 100), 0u);
  EXPECT_EQ(jsonNestingDepth(std::string(1000000, '['), 10), 11u);  // stops at stopAt + 1
  EXPECT_EQ(jsonNestingDepth("]]]][[", 10), 2u);  // stray closers do not underflow
  EXPECT_EQ(errorOf([] { checkJsonNesting("x.json", std::string(300, '{')); }),
            "x.json: JSON nested deeper than 256 levels (PRT_MAX_NESTING); refusing to parse it");
}

}  // namespace
}  // namespace prt
