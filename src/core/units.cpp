#include "prt/core/units.hpp"

#include <cstdio>

namespace prt {

std::string bytesText(std::size_t bytes) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB", "PB", "EB"};
  double x = static_cast<double>(bytes);
  int u = 0;
  while (x >= 1000.0 && u < 6) {
    x /= 1000.0;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", x, units[u]);
  return buf;
}

}  // namespace prt
