#pragma once
// A seeded random order of [0, n), drawn one element at a time: the Fisher–Yates shuffle
// (Durstenfeld 1964, "Algorithm 235: Random permutation") run lazily. Step i swaps position i
// with a uniform j in [i, n) and yields what lands at i, so the first k elements drawn are a
// uniformly random k-subset, and the whole a uniformly random permutation. Only the positions
// the swaps have touched are stored (a hash map), so drawing k of n costs O(k) time and memory,
// never an array of n — what lets a validation draw 100 texels of a 67-million-texel lightmap
// without touching the others. The draws are the same as the shuffle of an array 0..n−1 with
// the same generator, element for element.

#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include "prt/core/sampling.hpp"

namespace prt {

class RandomOrder {
 public:
  /// The order of [0, n) that a PCG32 stream seeded with `seed` gives.
  RandomOrder(std::size_t n, std::uint64_t seed) : n_(n), rng_(seed) {}
  /// Elements drawn so far.
  std::size_t drawn() const { return i_; }
  /// True once every element has been drawn.
  bool done() const { return i_ >= n_; }
  /// The next element (PRT_CHECK: not done()).
  std::uint32_t next();

 private:
  /// The element at position p of the array being shuffled.
  std::uint32_t at(std::size_t p) const;

  std::size_t n_, i_ = 0;
  Pcg32 rng_;
  std::unordered_map<std::size_t, std::uint32_t> moved_;  ///< positions ≥ i_ not holding p
};

}  // namespace prt
