#include "prt/geometry/texel_coverage.hpp"

#include <algorithm>
#include <bit>

#include "prt/core/error.hpp"

namespace prt {

TexelCoverage::TexelCoverage(int width, int height)
    : width_(width), height_(height), bits_((texelCount() + 63) / 64, 0) {}

void TexelCoverage::index() {
  before_.resize(bits_.size());
  std::size_t n = 0;
  for (std::size_t w = 0; w < bits_.size(); ++w) {
    before_[w] = static_cast<std::uint32_t>(n);
    n += static_cast<std::size_t>(std::popcount(bits_[w]));
  }
  count_ = n;
}

std::uint32_t TexelCoverage::select(std::size_t k) const {
  PRT_CHECK(k < count_, "TexelCoverage::select past the covered texels");
  // The last word with fewer than k + 1 covered texels before it holds the k-th, at the
  // (k − before)-th set bit of that word.
  const auto it = std::upper_bound(before_.begin(), before_.end(), static_cast<std::uint32_t>(k));
  const std::size_t w = static_cast<std::size_t>(it - before_.begin()) - 1;
  std::uint64_t word = bits_[w];
  for (std::size_t skip = k - before_[w]; skip > 0; --skip) word &= word - 1;
  return static_cast<std::uint32_t>(w * 64 + static_cast<std::size_t>(std::countr_zero(word)));
}

}  // namespace prt
