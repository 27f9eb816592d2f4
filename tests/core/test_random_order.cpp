// RandomOrder (core/random_order.hpp): the lazy Fisher–Yates shuffle draws exactly what the
// shuffle of a whole array 0..n−1 with the same generator draws, element for element, so a
// subset drawn from it is the one an array would have given, at O(drawn) memory; drawn to the
// end it is a permutation; its first elements are uniformly distributed (χ² over many seeds).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "prt/core/random_order.hpp"

namespace prt {
namespace {

/// The first `count` elements of the Fisher–Yates shuffle of an array 0..n−1, done on the array.
std::vector<std::uint32_t> arrayShuffle(std::size_t n, std::size_t count, std::uint64_t seed) {
  std::vector<std::uint32_t> all(n);
  std::iota(all.begin(), all.end(), 0u);
  Pcg32 rng(seed);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(rng.next() % (n - i));
    std::swap(all[i], all[j]);
  }
  all.resize(count);
  return all;
}

TEST(RandomOrder, DrawsWhatTheShuffleOfAnArrayDraws) {
  for (std::size_t n : {1u, 2u, 7u, 100u, 1000u, 65537u})
    for (std::uint64_t seed : {0ull, 1ull, 0x5eb5e7ull, 123456789ull}) {
      const std::size_t count = std::min<std::size_t>(n, 300);
      RandomOrder order(n, seed);
      std::vector<std::uint32_t> lazy;
      for (std::size_t i = 0; i < count; ++i) lazy.push_back(order.next());
      EXPECT_EQ(lazy, arrayShuffle(n, count, seed)) << "n " << n << " seed " << seed;
      EXPECT_EQ(order.drawn(), count);
    }
}

TEST(RandomOrder, DrawnToTheEndIsAPermutation) {
  RandomOrder order(5000, 9);
  std::vector<std::uint32_t> all;
  while (!order.done()) all.push_back(order.next());
  EXPECT_EQ(all, arrayShuffle(5000, 5000, 9));
  std::sort(all.begin(), all.end());
  for (std::uint32_t i = 0; i < all.size(); ++i) ASSERT_EQ(all[i], i);
}

// The first 3 of 10 over 20 000 seeds: each element is among them with probability 3/10, so
// its count h is Binomial(20 000, 0.3) and Σ (h − e)² / var has mean 10; it stays below 29.6,
// the χ² bound of 10 degrees of freedom at p = 0.001 (the counts' fixed sum only lowers it).
TEST(RandomOrder, ItsFirstElementsAreUniform) {
  constexpr int kSeeds = 20000, kN = 10, kK = 3;
  std::vector<double> hits(kN, 0.0);
  for (int s = 0; s < kSeeds; ++s) {
    RandomOrder order(kN, std::uint64_t(s) * 0x9e3779b97f4a7c15ull);
    for (int i = 0; i < kK; ++i) hits[order.next()] += 1;
  }
  const double expected = double(kSeeds) * kK / kN, var = expected * (1.0 - double(kK) / kN);
  double chi2 = 0;
  for (double h : hits) chi2 += (h - expected) * (h - expected) / var;
  EXPECT_LT(chi2, 29.6);
}

}  // namespace
}  // namespace prt
