#pragma once
// The one parallel primitive: a TBB parallel loop over an index range. Work must not depend on
// which thread or in which order chunks run: results are written per index, and reductions are
// done afterwards in a fixed order (see parallelReduce), so every result is independent of the
// thread count.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace prt {

/// Runs fn(begin, end) over disjoint chunks [begin, end) covering [0, n), in parallel.
void parallelFor(std::size_t n, std::size_t grain,
                 const std::function<void(std::size_t, std::size_t)>& fn);

/// Deterministic reduction: [0, n) is cut into fixed chunks of `chunk` items independent of the
/// thread count; fn(begin, end, partial) accumulates one chunk; the partials are then combined
/// in chunk order by combine(total, partial).
template <typename T, typename Fn, typename Combine>
T parallelReduce(std::size_t n, std::size_t chunk, const T& zero, Fn&& fn, Combine&& combine) {
  if (chunk == 0) chunk = 1;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::vector<T> partial(chunks, zero);
  parallelFor(chunks, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = b; c < e; ++c) {
      const std::size_t lo = c * chunk, hi = lo + chunk < n ? lo + chunk : n;
      fn(lo, hi, partial[c]);
    }
  });
  T total = zero;
  for (auto& p : partial) combine(total, p);
  return total;
}

/// Limits the worker threads while alive (0 = all hardware threads). Wraps tbb::global_control.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  std::unique_ptr<struct ThreadLimitImpl> impl_;
};

/// The number of threads parallelFor may use now.
int maxThreads();

}  // namespace prt
