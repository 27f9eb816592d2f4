// Hostile image headers (issue 11, docs/robustness.md): a declared size is checked against the
// image limits and against the bytes present before any pixel buffer is allocated.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "prt/core/limits.hpp"
#include "prt/image/image_io.hpp"
#include "support/hardening.hpp"

PRT_DEFINE_ALLOCATION_PROBE

namespace prt::image {
namespace {

using test::errorOf;
using test::PeakAllocation;
using test::ScopedLimits;

std::span<const unsigned char> span(const std::string& s) {
  return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

void expectOneLine(const std::string& e, const std::string& file, const std::string& part) {
  EXPECT_EQ(e.rfind(file + ": ", 0), 0u) << e;
  EXPECT_NE(e.find(part), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(ImageHardening, HdrHeaderSizesAreCheckedAgainstTheBytesAndTheLimits) {
  // The 53-byte header of issue 11: 20000 x 10000 allocated 2.2 GiB before "truncated".
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 10000 +X 20000\n";
  ASSERT_EQ(header.size(), 53u);
  {
    PeakAllocation peak;
    expectOneLine(errorOf([&] { readImageBytes("big.hdr", "hdr", span(header)); }), "big.hdr",
                  "truncated Radiance HDR file (20000x10000 needs at least");
    EXPECT_LT(peak.bytes(), 1u << 20);
  }
  // 65536 x 65536 ended in std::bad_alloc; now the side limit names itself.
  const std::string huge = "#?RADIANCE\n\n-Y 65536 +X 65536\n" + std::string(64, '\0');
  expectOneLine(errorOf([&] { readImageBytes("huge.hdr", "hdr", span(huge)); }), "huge.hdr",
                "image size 65536x65536 exceeds the limit of 32768 pixels a side "
                "(PRT_MAX_IMAGE_SIDE)");
  // A complete file still reads, and the pixel limit applies to it.
  std::string ok = "#?RADIANCE\n\n-Y 2 +X 3\n";
  for (int i = 0; i < 6; ++i) ok += std::string("\x80\x80\x80\x81", 4);
  EXPECT_EQ(readImageBytes("ok.hdr", "hdr", span(ok)).size(), 6u);
  Limits small = limits();
  small.maxImagePixels = 5;
  ScopedLimits scoped(small);
  expectOneLine(errorOf([&] { readImageBytes("ok.hdr", "hdr", span(ok)); }), "ok.hdr",
                "image size 3x2 exceeds the limit of 5 pixels (PRT_MAX_IMAGE_PIXELS)");
}

void putBe32(std::string& s, std::uint32_t v) {
  for (int k = 3; k >= 0; --k) s.push_back(char((v >> (8 * k)) & 0xff));
}

TEST(ImageHardening, PngHeaderSizeIsCheckedBeforeDecoding) {
  // A PNG signature and IHDR declaring 40000 x 20 (stb's own checks pass; ours do not).
  std::string png = "\x89PNG\r\n\x1a\n";
  putBe32(png, 13);
  png += "IHDR";
  putBe32(png, 40000);
  putBe32(png, 20);
  png += std::string("\x08\x02\x00\x00\x00", 5);
  putBe32(png, 0);  // CRC (stb does not check it)
  PeakAllocation peak;
  expectOneLine(errorOf([&] { readImageBytes("wide.png", "png", span(png)); }), "wide.png",
                "image size 40000x20 exceeds the limit of 32768 pixels a side");
  EXPECT_LT(peak.bytes(), 1u << 20);
}

std::string writtenBytes(const std::string& ext, const Image& img) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("prt_img_" + std::to_string(std::rand()) + "_" + std::to_string(std::rand()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / ("small." + ext)).string();
  writeImage(path, img);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::filesystem::remove_all(dir);
  return bytes;
}

TEST(ImageHardening, ChunkAndAttributeLengthsAreCheckedBeforeTheDecoderAllocates) {
  // fuzz_ldr: a PNG whose IDAT declared 1.7 GB made stb_image allocate it before reading.
  std::string png = writtenBytes("png", Image(8, 4));
  const std::size_t idat = png.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  png[idat - 4] = 0x68;
  {
    PeakAllocation peak;
    expectOneLine(errorOf([&] { readImageBytes("idat.png", "png", span(png)); }), "idat.png",
                  "truncated or corrupt PNG: a chunk declares 1744830");
    EXPECT_LT(peak.bytes(), 1u << 20);
  }
  // Other formats stb_image knows are not taken for PNG or JPEG.
  expectOneLine(
      errorOf([&] { readImageBytes("gif.png", "png", span(std::string("GIF89a....."))); }),
      "gif.png", "not a PNG file (bad signature)");
  // fuzz_exr: an attribute declaring 1.8 GB made OpenEXR allocate it before reading.
  std::string exr = writtenBytes("exr", Image(8, 4));
  const std::string key = std::string("compression\0compression\0", 24);
  const std::size_t at = exr.find(key);
  ASSERT_NE(at, std::string::npos);
  const std::int32_t huge = 1836016384;
  std::memcpy(&exr[at + key.size()], &huge, 4);
  PeakAllocation peak;
  expectOneLine(errorOf([&] { readImageBytes("attr.exr", "exr", span(exr)); }), "attr.exr",
                "OpenEXR header: attribute 'compression' declares 1836016384 bytes");
  EXPECT_LT(peak.bytes(), 1u << 20);
}

TEST(ImageHardening, ExrDataWindowIsCheckedBeforeAllocating) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("prt_exr_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                    "_" + std::to_string(std::rand()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "small.exr").string();
  writeImage(path, Image(8, 4));
  std::ifstream in(path, std::ios::binary);
  std::string exr((std::istreambuf_iterator<char>(in)), {});
  std::filesystem::remove_all(dir);
  const std::string key = std::string("dataWindow\0box2i\0", 17);
  const std::size_t at = exr.find(key);
  ASSERT_NE(at, std::string::npos);
  for (const std::int32_t side : {100000, 20000}) {
    std::string bad = exr;
    std::int32_t box[4] = {0, 0, side - 1, side - 1};
    std::memcpy(&bad[at + key.size() + 4], box, sizeof box);
    PeakAllocation peak;
    const std::string e = errorOf([&] { readImageBytes("big.exr", "exr", span(bad)); });
    expectOneLine(e, "big.exr", "");
    EXPECT_LT(peak.bytes(), 8u << 20) << e;
  }
}

}  // namespace
}  // namespace prt::image
