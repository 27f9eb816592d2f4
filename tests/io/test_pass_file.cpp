// Pass files (prt/io/pass_file.hpp): a round trip keeps every bit; merging pieces of one pass
// gives the pass; pieces of another bake or pass, gaps, overlaps and damaged bytes are refused
// with a line naming the problem.

#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "common/error_text.hpp"
#include "prt/core/error.hpp"
#include "prt/io/pass_file.hpp"

namespace prt {
namespace {

PassPiece piece(std::size_t first, std::size_t count, float base) {
  PassPiece p;
  p.identity = "a bake";
  p.pass = 1;
  p.passes = 3;
  p.name = "bounce 1";
  p.shape = TransferShape{TransferDomain::Vertices, TransferLayout::Vector, 2, 3, {first, count}};
  std::vector<float> v(count * p.shape.stride()), s(count * 4);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = base + 0.25f * float(i);
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = -base - float(i);
  p.values = FloatArray(std::move(v));
  p.sumChannels = 1;
  p.sum = FloatArray(std::move(s));
  p.variance.assign(count, 1e-3 * base);
  p.rays = {100, 10 * count};
  p.seconds = {1.0, 0.5};
  return p;
}

using testing::errorOf;

TEST(PassFile, RoundTripKeepsEveryBit) {
  const PassPiece p = piece(10, 5, 3.0f);
  const std::string bytes = encodePassPiece(p);
  const PassPiece q = decodePassPiece(
      {reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()}, "p.prtpass");
  EXPECT_EQ(q.identity, p.identity);
  EXPECT_EQ(q.shape, p.shape);
  EXPECT_EQ(0, std::memcmp(q.values.data(), p.values.data(), p.values.size() * 4));
  EXPECT_EQ(0, std::memcmp(q.sum.data(), p.sum.data(), p.sum.size() * 4));
  EXPECT_EQ(q.variance, p.variance);
  EXPECT_EQ(q.rays, p.rays);
  // Damaged: truncated, or a count the bytes cannot hold.
  const auto decode = [](const std::string& b) {
    decodePassPiece({reinterpret_cast<const unsigned char*>(b.data()), b.size()}, "p.prtpass");
  };
  EXPECT_NE(errorOf([&] { decode(bytes.substr(0, bytes.size() - 3)); }).find("truncated"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { decode("PRTPASS0" + bytes.substr(8)); }).find("not a pass file"),
            std::string::npos);
}

TEST(PassFile, EveryFlippedByteIsRefusedNeverUsed) {
  // The issue: a flipped byte in a .prtpass changed the bake (0.017) and exit 0. Now the
  // checksum covers the header and the rows: a flip of any bit of any byte is refused.
  const std::string bytes = encodePassPiece(piece(10, 5, 3.0f));
  const auto decode = [](const std::string& b) {
    decodePassPiece({reinterpret_cast<const unsigned char*>(b.data()), b.size()}, "p.prtpass");
  };
  int refused = 0, named = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i)
    for (int bit : {0, 5}) {
      std::string b = bytes;
      b[i] = static_cast<char>(b[i] ^ (1 << bit));
      const std::string e = errorOf([&] { decode(b); });
      refused += !e.empty();
      named += e.rfind("p.prtpass: ", 0) == 0;
    }
  EXPECT_EQ(refused, static_cast<int>(2 * bytes.size()));
  EXPECT_EQ(named, refused);
  std::string flipped = bytes;
  flipped[bytes.size() - 20] ^= 1;  // a row's float
  EXPECT_NE(errorOf([&] { decode(flipped); }).find("p.prtpass: is damaged: its checksum"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { decode("PRTPASS1" + bytes.substr(8)); })
                .find("is a pass file of an older prt, without a checksum"),
            std::string::npos);
}

TEST(PassFile, MergeJoinsPiecesOfOnePassAndRefusesTheRest) {
  const PassPiece a = piece(0, 4, 1.0f), b = piece(4, 6, 2.0f);
  const PassPiece m = mergePassPieces({b, a});
  EXPECT_EQ(m.shape.rows, (RowRange{0, 10}));
  EXPECT_EQ(0, std::memcmp(m.values.data(), a.values.data(), a.values.size() * 4));
  EXPECT_EQ(0,
            std::memcmp(m.values.data() + a.values.size(), b.values.data(), b.values.size() * 4));
  EXPECT_EQ(m.rays.back(), a.rays.back() + b.rays.back());
  EXPECT_EQ(m.rays.front(), 100u);
  EXPECT_NE(errorOf([&] {
              mergePassPieces({a, piece(5, 2, 0)});
            }).find("leaves a gap"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              mergePassPieces({a, piece(3, 2, 0)});
            }).find("overlaps"),
            std::string::npos);
  PassPiece other = b;
  other.identity = "another bake";
  EXPECT_NE(errorOf([&] { mergePassPieces({a, other}); }).find("another bake"), std::string::npos);
  PassPiece later = b;
  later.pass = 2;
  later.rays.push_back(1);
  later.seconds.push_back(1);
  EXPECT_NE(errorOf([&] { mergePassPieces({a, later}); }).find("is of pass 2"), std::string::npos);
}

}  // namespace
}  // namespace prt
