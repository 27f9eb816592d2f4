// Image I/O, colour and the pixel policy: round trips through every writable format, the
// decode rules for 8-bit files, and one-line errors for broken files.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "common/scratch.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"
#include "support/hardening.hpp"

namespace fs = std::filesystem;
using namespace prt;
using namespace prt::image;

namespace {

using TempDir = prt::testing::ScratchDir;

Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = {0.01f + 3.0f * x / w, 0.5f * y / h, 0.25f + 0.001f * (x * y)};
  return img;
}

void truncateFile(const std::string& path, double keep) {
  const auto bytes = readFileBytes(path);
  std::ofstream os(path, std::ios::binary | std::ios::trunc);
  os.write(reinterpret_cast<const char*>(bytes.data()),
           static_cast<std::streamsize>(bytes.size() * keep));
}

using test::errorOf;

}  // namespace

TEST(Color, SrgbMatchesTheStandard) {
  // IEC 61966-2-1 reference points: the knee, mid grey, white.
  EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-5);
  EXPECT_NEAR(srgbToLinear(1.0f), 1.0f, 1e-6);
  for (int i = 0; i <= 255; ++i) {
    const float v = i / 255.0f;
    EXPECT_NEAR(linearToSrgb(srgbToLinear(v)), v, 2e-6) << i;
    EXPECT_FLOAT_EQ(srgb8ToLinear(static_cast<std::uint8_t>(i)), srgbToLinear(v));
    EXPECT_FLOAT_EQ(
        gamma22ToLinear(static_cast<std::uint8_t>(i)),
        static_cast<float>(std::pow(static_cast<double>(i / 255.0f), 2.2000000476837158)));
  }
  EXPECT_NEAR(luminance(Rgb(1, 1, 1)), 1.0f, 1e-6);
}

TEST(Color, ToneMappers) {
  EXPECT_FLOAT_EQ(toneMap(Rgb(0.25f), ToneMap::Clamp).x, 0.25f);
  EXPECT_FLOAT_EQ(toneMap(Rgb(4.0f), ToneMap::Clamp).x, 1.0f);
  EXPECT_FLOAT_EQ(toneMap(Rgb(0.25f), ToneMap::Clamp, 1.0f).x, 0.5f);  // one stop doubles
  EXPECT_FLOAT_EQ(toneMap(Rgb(3.0f), ToneMap::Reinhard).x, 0.75f);
  EXPECT_FLOAT_EQ(toneMap(Rgb(0.0f), ToneMap::Aces).x, 0.0f);
  EXPECT_NEAR(toneMap(Rgb(1e4f), ToneMap::Aces).x, 1.0f, 1e-3);
  float prev = -1;
  for (float v = 0; v < 20; v += 0.05f) {  // monotonic and bounded
    const float t = toneMap(Rgb(v), ToneMap::Aces).x;
    EXPECT_GE(t, prev);
    EXPECT_LE(t, 1.0f);
    prev = t;
  }
  EXPECT_THROW(parseToneMap("filmic"), Error);
}

TEST(ImageIo, ExrRoundTripIsExact) {
  TempDir dir;
  const Image img = gradient(17, 9);
  writeImage(dir / "a.exr", img);
  const Image back = readImage(dir / "a.exr");
  ASSERT_EQ(back.width, 17);
  ASSERT_EQ(back.height, 9);
  for (std::size_t i = 0; i < img.size(); ++i) EXPECT_EQ(back.pixels[i], img.pixels[i]) << i;
}

TEST(ImageIo, HdrRoundTripWithinRgbePrecision) {
  TempDir dir;
  const Image img = gradient(16, 8);
  writeImage(dir / "a.hdr", img);
  const Image back = readImage(dir / "a.hdr");
  ASSERT_EQ(back.width, 16);
  for (std::size_t i = 0; i < img.size(); ++i) {
    const float m = std::max({img.pixels[i].x, img.pixels[i].y, img.pixels[i].z});
    // RGBE keeps 8 mantissa bits relative to the largest channel.
    EXPECT_NEAR(back.pixels[i].x, img.pixels[i].x, m / 128);
    EXPECT_NEAR(back.pixels[i].y, img.pixels[i].y, m / 128);
    EXPECT_NEAR(back.pixels[i].z, img.pixels[i].z, m / 128);
  }
}

TEST(ImageIo, PngEncodesSrgbAndDecodesBothWays) {
  TempDir dir;
  Image img(256, 1);
  for (int x = 0; x < 256; ++x) img.at(x, 0) = Rgb(srgb8ToLinear(static_cast<std::uint8_t>(x)));
  writeImage(dir / "ramp.png", img, {ToneMap::Clamp, 0.0f});
  ReadStats stats;
  const Image srgb = readImage(dir / "ramp.png", {}, &stats);
  EXPECT_TRUE(stats.ldr);
  const Image g22 = readImage(dir / "ramp.png", {LdrDecode::Gamma22});
  for (int x = 0; x < 256; ++x) {
    // Code x must come back as code x: linear → sRGB → 8 bits → linear is the identity on codes.
    EXPECT_FLOAT_EQ(srgb.at(x, 0).y, srgb8ToLinear(static_cast<std::uint8_t>(x))) << x;
    EXPECT_FLOAT_EQ(g22.at(x, 0).y, static_cast<float>(std::pow(x / 255.0, 2.2))) << x;
  }
}

TEST(ImageIo, NonFiniteAndNegativePixelsAreZeroedAndCounted) {
  TempDir dir;
  Image img = gradient(8, 4);
  img.at(0, 0).x = std::numeric_limits<float>::quiet_NaN();
  img.at(1, 0).y = std::numeric_limits<float>::infinity();
  img.at(2, 0).z = -std::numeric_limits<float>::infinity();
  img.at(3, 0).x = -0.5f;
  img.at(4, 0) = Rgb(-1.0f);
  writeImage(dir / "bad.exr", img);
  ReadStats stats;
  const Image back = readImage(dir / "bad.exr", {}, &stats);
  EXPECT_EQ(stats.nonFinitePixels, 3u);
  EXPECT_EQ(stats.negativePixels, 2u);
  for (const Rgb& p : back.pixels) {
    EXPECT_TRUE(isFinite(p));
    EXPECT_GE(std::min({p.x, p.y, p.z}), 0.0f);
  }
  EXPECT_EQ(back.at(0, 0).x, 0.0f);
  EXPECT_EQ(back.at(0, 0).y, img.at(0, 0).y);  // other channels untouched
  EXPECT_EQ(back.at(3, 0).x, 0.0f);
}

TEST(ImageIo, BrokenFilesGiveOneLineErrorsNamingTheFile) {
  TempDir dir;
  const Image img = gradient(64, 32);
  for (const std::string ext : {"png", "hdr", "exr"}) {
    const std::string p = dir / ("t." + ext);
    writeImage(p, img);
    truncateFile(p, 0.6);
    const std::string e = errorOf([&] { readImage(p); });
    EXPECT_NE(e.find(p), std::string::npos) << ext << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  {
    const std::string p = dir / "garbage.jpg";
    std::ofstream(p) << "this is not a jpeg";
    EXPECT_NE(errorOf([&] { readImage(p); }).find(p), std::string::npos);
  }
  {
    const std::string p = dir / "empty.png";
    std::ofstream{p};
    EXPECT_NE(errorOf([&] { readImage(p); }).find("empty"), std::string::npos);
  }
  EXPECT_NE(errorOf([&] { readImage(dir / "image.tga"); }).find("unknown image extension"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { readImage(dir / "missing.exr"); }).find("missing.exr"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { writeImage(dir / "out.bmp", img); }).find("out.bmp"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "out.bmp"));
}
