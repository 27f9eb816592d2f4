#pragma once
// Baselines shared by the relighting benchmarks (bench_relight, bench_relight_glossy): the
// streaming read that bounds a relighting kernel, and a best-of-N timer for same-run ratios.

#include <algorithm>
#include <chrono>
#include <functional>
#include <span>
#include <vector>

#include "prt/core/parallel.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::bench {

// The streaming-read baseline: sum every float of `data` in chunks of `grain` floats, 16
// independent accumulators so the loop is vectorised without reassociation flags.
inline float streamSum(std::span<const float> data, std::size_t grain) {
  const std::size_t n = data.size();
  const std::size_t chunks = (n + grain - 1) / grain;
  std::vector<float> partial(chunks, 0.0f);
  prt::parallelFor(chunks, 1, [&](std::size_t cb, std::size_t ce) {
    for (std::size_t c = cb; c < ce; ++c) {
      const float* p = data.data();
      float acc[16] = {};
      std::size_t i = c * grain;
      const std::size_t hi = std::min(n, (c + 1) * grain);
      for (; i + 16 <= hi; i += 16)
        for (int k = 0; k < 16; ++k) acc[k] += p[i + k];
      for (; i < hi; ++i) acc[0] += p[i];
      float s = 0;
      for (float a : acc) s += a;
      partial[c] = s;
    }
  });
  float total = 0;
  for (float p : partial) total += p;
  return total;
}

/// The same over a transfer, in the vertex chunks vector relighting uses.
inline float streamSum(const prt::Transfer& t) {
  const std::size_t stride = t.stride();
  const std::size_t grain = std::max<std::size_t>(256, 65536 / (stride * sizeof(float)) * 4);
  return streamSum(t.values().span(), grain * stride);
}

inline double secondsOf(const std::function<void()>& fn, int reps) {
  double best = 1e30;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

}  // namespace prt::bench
