#pragma once
// Reproducible random inputs for the relighting tests: a transfer field and an RGB SH light
// drawn from a Pcg32 stream of `seed` (values that exercise the arithmetic; no physics).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/sampling.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::testdata {

/// The shape of `rows` rows of `layout`, `bands`, `channels` over vertices 0..rows−1.
inline TransferShape shapeOf(TransferLayout layout, int bands, int channels, std::size_t rows) {
  TransferShape s;
  s.layout = layout;
  s.bands = bands;
  s.channels = channels;
  s.rows = {0, rows};
  return s;
}

/// Dense rows holding `values` (rows · stride of them).
inline Transfer denseTransfer(TransferLayout layout, int bands, int channels,
                              std::vector<float> values) {
  const std::size_t stride = shapeOf(layout, bands, channels, 1).stride();
  const std::size_t rows = values.size() / stride;
  return Transfer::dense(shapeOf(layout, bands, channels, rows), FloatArray(std::move(values)));
}

/// The dense values of a transfer as a vector (a copy, for tests that edit or compare them).
inline std::vector<float> valuesOf(const Transfer& t) {
  const Transfer d = t.toDense();
  return std::vector<float>(d.values().data(), d.values().data() + d.values().size());
}

/// Dense rows, every value uniform in [−0.3, 0.7).
inline Transfer randomField(TransferLayout layout, int bands, int channels, std::size_t rows,
                            std::uint64_t seed) {
  Transfer f = Transfer::zeros(shapeOf(layout, bands, channels, rows));
  Pcg32 rng(seed);
  float* x = f.mutableValues();
  for (std::size_t i = 0; i < f.values().size(); ++i) x[i] = rng.uniform() - 0.3f;
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
