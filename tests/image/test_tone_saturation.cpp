// Finite but absurd values (issue 16, item 5): every tone map saturates to white however bright
// the exposed value — an exposure at the ±64-stop limit, a light of 1e20, radiance near FLT_MAX,
// inf — where ACES's v² and v · 2^exposure used to overflow and render black; one exposure limit
// (image::kMaxExposureStops) for every tool.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/scratch.hpp"
#include "prt/core/error.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"

namespace prt::image {
namespace {

constexpr ToneMap kAll[] = {ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Aces};

TEST(ToneSaturation, EveryToneMapIsWhiteForAbsurdlyBrightValues) {
  const float inf = std::numeric_limits<float>::infinity();
  for (ToneMap op : kAll)
    for (float v : {1e8f, 1e19f, 1e20f, 2.7e36f, 3e38f, std::numeric_limits<float>::max(), inf})
      for (float stops : {0.0f, 1.0f, 62.0f, 63.0f, 64.0f}) {
        SCOPED_TRACE(::testing::Message() << "op " << int(op) << " v " << v << " stops " << stops);
        const Rgb t = toneMap(Rgb(v), op, stops);
        EXPECT_EQ(t.x, 1.0f);
        EXPECT_EQ(t.y, 1.0f);
        EXPECT_EQ(t.z, 1.0f);
      }
}

TEST(ToneSaturation, AcesClampedInputIsTheSameCurve) {
  // The input clamp at 16 changes nothing: the fit is monotone and reaches 1 at v ≈ 7.25.
  const auto fit = [](double v) {
    return std::min(1.0, v * (2.51 * v + 0.03) / (v * (2.43 * v + 0.59) + 0.14));
  };
  for (double v = 0; v < 40; v += 0.01)
    EXPECT_NEAR(toneMap(Rgb(float(v)), ToneMap::Aces).x, fit(v), 2e-6) << v;
  EXPECT_LT(fit(7.2), 1.0);
  EXPECT_EQ(fit(7.3), 1.0);
}

TEST(ToneSaturation, NanAndNegativeAreBlackDimValuesUnchanged) {
  for (ToneMap op : kAll) {
    EXPECT_EQ(toneMap(Rgb(std::nanf("")), op).x, 0.0f);
    EXPECT_EQ(toneMap(Rgb(-1e30f), op, 64).x, 0.0f);
  }
  EXPECT_FLOAT_EQ(toneMap(Rgb(0.25f), ToneMap::Clamp, 1.0f).x, 0.5f);
  EXPECT_FLOAT_EQ(toneMap(Rgb(3.0f), ToneMap::Reinhard).x, 0.75f);
  // 2^-64 of a dim value is black, not NaN.
  EXPECT_EQ(toneMap(Rgb(1e-30f), ToneMap::Aces, -64).x, 0.0f);
}

TEST(ToneSaturation, OneExposureLimit) {
  EXPECT_EQ(kMaxExposureStops, 64.0f);
  EXPECT_NO_THROW(checkExposure(64.0f));
  EXPECT_NO_THROW(checkExposure(-64.0f));
  for (float bad : {64.5f, -65.0f, 1e30f, std::numeric_limits<float>::infinity(), std::nanf("")}) {
    try {
      checkExposure(bad, "--exposure");
      ADD_FAILURE() << bad << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--exposure"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("[-64, 64]"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(clampExposure(1e30f), 64.0f);
  EXPECT_EQ(clampExposure(-std::numeric_limits<float>::infinity()), -64.0f);
  EXPECT_EQ(clampExposure(std::nanf("")), 0.0f);
  EXPECT_EQ(clampExposure(3.5f), 3.5f);
  // 2^64 is finite in float: the limit cannot overflow the exposure scale itself.
  EXPECT_TRUE(std::isfinite(std::exp2(kMaxExposureStops)));
  // The tone map applies the limit too (an exposure beyond it saturates, it does not go black).
  EXPECT_EQ(toneMap(Rgb(1.0f), ToneMap::Aces, 1e30f).x, 1.0f);
}

TEST(ToneSaturation, PngOfABrightImageAtTheExposureLimitIsWhite) {
  prt::testing::ScratchDir dir;
  Image img(4, 2);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = Rgb(i % 2 ? 1e20f : 2.7e36f);
  for (ToneMap op : kAll) {
    const std::string p = (dir.path() / "white.png").string();
    writeImage(p, img, {op, 63.0f});
    const Image back = readImage(p);
    for (const Rgb& c : back.pixels) EXPECT_EQ(c.x, 1.0f) << int(op);
  }
}

}  // namespace
}  // namespace prt::image
