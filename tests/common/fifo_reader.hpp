#pragma once
// Reads a FIFO on a thread while a writer under test runs, without ever hanging: the FIFO is
// opened at once (non-blocking, so a writer that never opens it, or replaces it, cannot block
// the test), drained as bytes arrive, and finish() collects what came once the writer is done.

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <string>
#include <thread>

namespace prt::testing {

class FifoReader {
 public:
  explicit FifoReader(const std::string& path)
      : fd_(::open(path.c_str(), O_RDONLY | O_NONBLOCK)), thread_([this] { run(); }) {}
  ~FifoReader() {
    if (thread_.joinable()) finish();
  }
  FifoReader(const FifoReader&) = delete;
  FifoReader& operator=(const FifoReader&) = delete;

  bool opened() const { return fd_ >= 0; }
  /// Call once the writer has returned: the bytes it wrote.
  std::string finish() {
    done_ = true;
    thread_.join();
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    return bytes_;
  }

 private:
  void run() {
    if (fd_ < 0) return;
    char buf[65536];
    for (;;) {
      const bool last = done_;  // read after the writer finished: a final drain
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n > 0) {
        bytes_.append(buf, static_cast<std::size_t>(n));
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (last) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  int fd_;
  std::atomic<bool> done_{false};
  std::string bytes_;
  std::thread thread_;
};

}  // namespace prt::testing
