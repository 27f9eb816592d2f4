#pragma once
// Reproducible random inputs for the relighting tests: a transfer field and an RGB SH light
// drawn from a Pcg32 stream of `seed` (values that exercise the arithmetic; no physics).

#include <cstddef>
#include <cstdint>

#include "prt/core/sampling.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/field.hpp"

namespace prt::testdata {

/// Every value uniform in [−0.3, 0.7).
inline TransferField randomField(TransferLayout layout, int bands, int channels, std::size_t rows,
                                 std::uint64_t seed) {
  TransferField f = TransferField::zeros(layout, bands, channels, rows);
  Pcg32 rng(seed);
  for (float& x : f.data) x = rng.uniform() - 0.3f;
  return f;
}

/// Every coefficient's channels uniform in [0, 1).
inline sh::RgbSh randomLight(int bands, std::uint64_t seed) {
  sh::RgbSh l(bands);
  Pcg32 rng(seed);
  for (Rgb& c : l.c) c = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
  return l;
}

}  // namespace prt::testdata
