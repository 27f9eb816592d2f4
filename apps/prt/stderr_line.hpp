#pragma once
// One line to standard error in one write(2).
//
// std::cerr is unbuffered: `std::cerr << verb << ": error: " << what` is three writes, and
// under mpirun the runtime's own banner ("Primary job terminated normally, but ...") can land
// between them, splitting our one line in two ("prt bake" ... banner ... ": error: rank 2 ...").
// Writing the whole line at once keeps it whole: a pipe takes writes of up to PIPE_BUF bytes
// atomically, and every line we print is cut well short of that (oneLine).

#include <cerrno>
#include <string>

#include <unistd.h>

namespace prt::cli {

/// Writes `line` and a newline to standard error as one write (repeated only for what a
/// partial write left).
inline void printLine(std::string line) {
  line += '\n';
  const char* at = line.data();
  std::size_t left = line.size();
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, at, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // standard error is gone: nothing else to tell
    at += n;
    left -= static_cast<std::size_t>(n);
  }
}

}  // namespace prt::cli
