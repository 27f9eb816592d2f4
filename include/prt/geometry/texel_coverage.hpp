#pragma once
// Which texels of a W × H lightmap a triangle covers (geometry/texel_sampling.hpp: coverTexels),
// one bit per texel — W·H/8 bytes, a 32nd of the sample placement's arrays — with the rank and
// select a draw among the covered texels needs: how many there are, and which is the k-th.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace prt {

class TexelCoverage {
 public:
  TexelCoverage() = default;
  /// No texel covered yet.
  TexelCoverage(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t texelCount() const { return std::size_t(width_) * std::size_t(height_); }
  bool covered(std::size_t texel) const { return (bits_[texel >> 6] >> (texel & 63)) & 1u; }
  void cover(std::size_t texel) { bits_[texel >> 6] |= std::uint64_t(1) << (texel & 63); }

  /// Makes count() and select() reflect the texels covered so far (call after the last cover).
  void index();
  /// Covered texels (as of index()).
  std::size_t count() const { return count_; }
  /// The k-th covered texel in texel order, k < count() (as of index()).
  std::uint32_t select(std::size_t k) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint64_t> bits_;
  std::vector<std::uint32_t> before_;  ///< covered texels in the words before word w
  std::size_t count_ = 0;
};

}  // namespace prt
