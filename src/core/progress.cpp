#include "prt/core/progress.hpp"

#include "prt/core/error.hpp"

namespace prt {

namespace {
std::atomic<bool> gCancel{false};
}

void requestCancel() {
  gCancel.store(true);
}
bool cancelRequested() {
  return gCancel.load(std::memory_order_relaxed);
}
void clearCancel() {
  gCancel.store(false);
}

Progress::Progress(const ProgressFn& fn, std::size_t total) : fn_(fn), total_(total ? total : 1) {}

void Progress::advance(std::size_t done) {
  const std::size_t now = done_.fetch_add(done, std::memory_order_relaxed) + done;
  if (cancelRequested()) cancelled_.store(true);
  if (fn_ && now >= nextReport_.load(std::memory_order_relaxed)) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (now >= nextReport_.load(std::memory_order_relaxed)) {
      nextReport_.store(now + total_ / 256 + 1, std::memory_order_relaxed);
      if (!fn_(static_cast<double>(now < total_ ? now : total_) / static_cast<double>(total_)))
        cancelled_.store(true);
    }
  }
  check();
}

void Progress::check() const {
  if (cancelled_.load(std::memory_order_relaxed) || cancelRequested()) throw Cancelled();
}

}  // namespace prt
