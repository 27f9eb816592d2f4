#include "prt/core/base64.hpp"

namespace prt {

std::string base64(std::string_view bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  unsigned v = 0;
  int n = 0;
  for (unsigned char c : bytes) {
    v = (v << 8) | c;
    n += 8;
    while (n >= 6) out += k[(v >> (n -= 6)) & 63];
  }
  if (n > 0) out += k[(v << (6 - n)) & 63];
  while (out.size() % 4) out += '=';
  return out;
}

}  // namespace prt
