#pragma once
// Progress reporting and cancellation for long operations. The library calls the callback with
// the fraction done (0..1) from any thread (calls are serialised); returning false cancels, and
// the operation then throws prt::Cancelled.

#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>

namespace prt {

using ProgressFn = std::function<bool(double fraction)>;

/// Thread-safe counter over `total` work items that calls a ProgressFn at most every 1/256th.
class Progress {
 public:
  Progress(const ProgressFn& fn, std::size_t total);
  /// Adds `done` finished items; throws Cancelled if the callback asked to stop or
  /// cancellation was requested.
  void advance(std::size_t done);
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
  /// Throws Cancelled if cancelled.
  void check() const;

 private:
  ProgressFn fn_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::atomic<std::size_t> nextReport_{0};
  std::atomic<bool> cancelled_{false};
  std::mutex mutex_;
};

/// A process-wide cancel flag (set by the CLI's SIGINT handler); every Progress checks it.
void requestCancel();
bool cancelRequested();
void clearCancel();

}  // namespace prt
