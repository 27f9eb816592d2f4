#pragma once
// Private to src/distributed: waiting on MPI requests without spinning.

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <thread>

namespace prt::distributed::detail {

/// Waits for `req` by polling MPI_Test: a few times at once, then sleeping between polls, from
/// 20 µs up to 500 µs, so a waiting rank (or rank 0's coordinator thread) leaves the cores to
/// the ranks and threads that work (a spinning wait costs a core; rank 0's coordinator, which
/// waits most of the time, used 0.75% of one in a 2-rank bake). A chunk takes tens of
/// milliseconds, so the ≤ 0.5 ms a request may wait is about 1%. `idle` runs about every 50 ms
/// while waiting (the root's watch over the other ranks).
inline void politeWait(MPI_Request* req, MPI_Status* status,
                       const std::function<void()>& idle = {}) {
  using Clock = std::chrono::steady_clock;
  int flag = 0;
  auto next = Clock::now() + std::chrono::milliseconds(50);
  int sleepUs = 20;
  for (int spin = 0;; ++spin) {
    MPI_Test(req, &flag, status ? status : MPI_STATUS_IGNORE);
    if (flag) return;
    if (spin < 64) continue;
    std::this_thread::sleep_for(std::chrono::microseconds(sleepUs));
    sleepUs = std::min(500, sleepUs * 2);
    if (idle && Clock::now() >= next) {
      idle();
      next = Clock::now() + std::chrono::milliseconds(50);
    }
  }
}

/// politeWait over several requests.
inline void politeWaitAll(int count, MPI_Request* reqs, const std::function<void()>& idle = {}) {
  for (int i = 0; i < count; ++i) politeWait(&reqs[i], nullptr, idle);
}

}  // namespace prt::distributed::detail
