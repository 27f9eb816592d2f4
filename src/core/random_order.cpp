#include "prt/core/random_order.hpp"

#include "prt/core/error.hpp"

namespace prt {

std::uint32_t RandomOrder::at(std::size_t p) const {
  const auto it = moved_.find(p);
  return it == moved_.end() ? static_cast<std::uint32_t>(p) : it->second;
}

std::uint32_t RandomOrder::next() {
  PRT_CHECK(i_ < n_, "RandomOrder: every element has been drawn");
  const std::size_t j = i_ + static_cast<std::size_t>(rng_.next() % (n_ - i_));
  const std::uint32_t drawn = at(j);
  // Position j takes what was at i; position i is never read again.
  if (j != i_) moved_[j] = at(i_);
  moved_.erase(i_);
  ++i_;
  return drawn;
}

}  // namespace prt
