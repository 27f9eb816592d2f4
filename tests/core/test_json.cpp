// The one JSON writer (core/json.hpp): shortest round-trip floats, null for non-finite numbers,
// numeric arrays on one line, and output that nlohmann reads back to the same value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "prt/core/json.hpp"

namespace prt {
namespace {

TEST(Json, FloatsAreShortestAndReadBackExactly) {
  EXPECT_EQ(jsonFloat(0.1f).dump(), "0.1");
  EXPECT_EQ(jsonFloat(1.0f / 3.0f).dump(), "0.33333334");  // not 0.3333333432674408
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1e6f, 1e6f);
  for (int i = 0; i < 10000; ++i) {
    const float f = i % 2 ? u(rng) : std::ldexp(u(rng), -100);
    const Json back = Json::parse(jsonFloat(f).dump());
    EXPECT_EQ(static_cast<float>(back.get<double>()), f) << f;
  }
  EXPECT_TRUE(jsonFloat(std::numeric_limits<float>::quiet_NaN()).is_null());
  EXPECT_TRUE(jsonFloat(std::numeric_limits<float>::infinity()).is_null());
}

TEST(Json, LayoutKeepsNumberArraysOnOneLineAndReadsBack) {
  Json j;
  j["name"] = "a \"quoted\" </script> name";
  j["rgb"] = Json::array({1.5, 2, 3});
  j["rows"] = Json::array({Json::array({1, 2}), Json::array({3, 4})});
  j["nan"] = std::numeric_limits<double>::quiet_NaN();
  j["empty"] = Json::object();
  const std::string text = formatJson(j);
  EXPECT_NE(text.find("\"rgb\": [1.5, 2, 3]"), std::string::npos) << text;
  EXPECT_NE(text.find("    [1, 2],\n    [3, 4]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\"nan\": null"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');
  // The order the writer set is kept.
  EXPECT_LT(text.find("\"name\""), text.find("\"rgb\""));
  const Json back = Json::parse(text);
  EXPECT_EQ(back["name"], j["name"]);
  EXPECT_EQ(back["rows"], j["rows"]);
  EXPECT_TRUE(back["nan"].is_null());
  EXPECT_EQ(formatJson(j, 0).find('\n'), std::string::npos);
}

}  // namespace
}  // namespace prt
