// A Radiance HDR whose run-length scan line declares another width is corrupt (Radiance's
// freadcolrs rejects it): an error naming the file and the line, not flat pixels decoded as
// garbage with exit 0 (issue 16, item 9).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/scratch.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/image/image_io.hpp"

namespace prt::image {
namespace {

std::span<const unsigned char> span(const std::string& s) {
  return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

/// A 16x2 RLE HDR written by our writer, as bytes.
std::string rleHdr() {
  prt::testing::ScratchDir dir;
  Image img(16, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 16; ++x) img.at(x, y) = {0.1f * x, 0.5f, 0.25f * y};
  writeImage(dir / "g.hdr", img);
  const std::vector<unsigned char> b = readFileBytes(dir / "g.hdr");
  return std::string(b.begin(), b.end());
}

TEST(HdrScanLines, CorruptRunLengthWidthIsAnErrorNamingTheFile) {
  const std::string good = rleHdr();
  const std::size_t pixels = good.find("+X 16\n") + 6;
  ASSERT_EQ(good.substr(pixels, 4), std::string("\x02\x02\x00\x10", 4));  // RLE, width 16
  EXPECT_NO_THROW(readImageBytes("g.hdr", "hdr", span(good)));
  for (const std::string& width :
       {std::string("\x00\x11", 2), std::string("\x00\x08", 2), std::string("\x01\x10", 2)}) {
    std::string bad = good;
    bad.replace(pixels + 2, 2, width);
    try {
      readImageBytes("bad.hdr", "hdr", span(bad));
      ADD_FAILURE() << "decoded a scan line of the wrong width";
    } catch (const Error& e) {
      const std::string w = e.what();
      EXPECT_EQ(w.rfind("bad.hdr: corrupt Radiance HDR file: scan line 0 is run-length encoded "
                        "for width ",
                        0),
                0u)
          << w;
      EXPECT_NE(w.find("the image is 16 wide"), std::string::npos) << w;
    }
  }
  // The second scan line too.
  std::string bad = good;
  const std::size_t second = good.find(std::string("\x02\x02\x00\x10", 4), pixels + 4);
  ASSERT_NE(second, std::string::npos);
  bad[second + 3] = 0x0f;
  try {
    readImageBytes("bad.hdr", "hdr", span(bad));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scan line 1"), std::string::npos) << e.what();
  }
  // Flat (unencoded) pixels are still flat: a first pixel 2, 2, 200 (blue >= 128) is no RLE
  // header, as in Radiance.
  std::string flat = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n";
  for (int x = 0; x < 8; ++x) flat += std::string("\x02\x02\xc8\x80", 4);
  const Image img = readImageBytes("flat.hdr", "hdr", span(flat));
  EXPECT_NEAR(img.at(0, 0).z, (200 + 0.5f) / 256.0f, 1e-6f);
}

}  // namespace
}  // namespace prt::image
