#pragma once
// Helpers for the hardening tests (malformed and hostile inputs, docs/robustness.md):
//   * finishesWithin: runs a call on a thread and aborts the whole test program if it does not
//     return in time, so a loader that loops forever fails the test instead of hanging ctest;
//   * PeakAllocation: the largest single operator-new request while it is alive, so a test can
//     prove that a file declaring a huge size is refused *before* the allocation. Include
//     PRT_DEFINE_ALLOCATION_PROBE in exactly one .cpp of a test program to install it;
//   * ScopedLimits: sets prt::limits() for one test and restores the previous ones.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <future>
#include <new>
#include <string>
#include <thread>

#include <zlib.h>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"

namespace prt::test {

inline std::atomic<std::size_t>& peakRequest() {
  static std::atomic<std::size_t> peak{0};
  return peak;
}
inline std::atomic<bool>& probeActive() {
  static std::atomic<bool> active{false};
  return active;
}

/// Records the largest single allocation request made while it is alive (any thread).
class PeakAllocation {
 public:
  PeakAllocation() {
    peakRequest() = 0;
    probeActive() = true;
  }
  ~PeakAllocation() { probeActive() = false; }
  std::size_t bytes() const { return peakRequest().load(); }
};

inline void noteAllocation(std::size_t n) {
  if (!probeActive().load(std::memory_order_relaxed)) return;
  std::size_t cur = peakRequest().load(std::memory_order_relaxed);
  while (n > cur && !peakRequest().compare_exchange_weak(cur, n)) {
  }
}

/// `data` gzip-compressed (zlib's deflate, level 1): the .gz inputs of the reader tests.
inline std::string gzipOf(const std::string& data) {
  z_stream zs{};
  deflateInit2(&zs, 1, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&zs, data.size()) + 32, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = uInt(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(out.size());
  deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

/// The error message of fn(), or "" if it did not throw prt::Error (anything else propagates).
inline std::string errorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const prt::Error& e) {
    return e.what();
  }
  return "";
}

/// Runs fn; if it has not returned after `seconds`, prints `what` and ends the test program
/// with a failure (a hang cannot be interrupted from inside).
inline std::string finishesWithin(double seconds, const std::string& what,
                                  const std::function<void()>& fn) {
  auto task = std::make_shared<std::packaged_task<std::string()>>([fn] { return errorOf(fn); });
  std::future<std::string> result = task->get_future();
  std::thread([task] { (*task)(); }).detach();
  if (result.wait_for(std::chrono::duration<double>(seconds)) != std::future_status::ready) {
    std::fprintf(stderr, "FAILED: %s did not finish within %.0f s (hang)\n", what.c_str(), seconds);
    std::fflush(stderr);
    std::_Exit(1);
  }
  return result.get();
}

/// Sets limits for the scope of a test.
class ScopedLimits {
 public:
  explicit ScopedLimits(const Limits& l) : saved_(limits()) { setLimits(l); }
  ~ScopedLimits() { setLimits(saved_); }

 private:
  Limits saved_;
};

}  // namespace prt::test

// GCC 12 cannot see that these new and delete are a matched malloc/free pair and warns
// (-Wmismatched-new-delete) at every inlined delete; the pair is correct by construction.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

#define PRT_DEFINE_ALLOCATION_PROBE                       \
  void* operator new(std::size_t n) {                     \
    ::prt::test::noteAllocation(n);                       \
    if (void* p = std::malloc(n ? n : 1)) return p;       \
    throw std::bad_alloc();                               \
  }                                                       \
  void* operator new[](std::size_t n) {                   \
    return ::operator new(n);                             \
  }                                                       \
  void operator delete(void* p) noexcept {                \
    std::free(p);                                         \
  }                                                       \
  void operator delete[](void* p) noexcept {              \
    std::free(p);                                         \
  }                                                       \
  void operator delete(void* p, std::size_t) noexcept {   \
    std::free(p);                                         \
  }                                                       \
  void operator delete[](void* p, std::size_t) noexcept { \
    std::free(p);                                         \
  }
