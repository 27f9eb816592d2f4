#pragma once
// FNV-1a, 64 bits (Fowler, Noll & Vo): the one hash for identities that must not change between
// runs or machines — a bake's checkpoint identity, a reference file's fingerprints, the host of
// an MPI rank. Not for hash tables of untrusted keys.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace prt {

class Fnv1a {
 public:
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  /// The bytes of the elements (no length): trivially copyable element types only.
  template <class T>
  void addAll(const std::vector<T>& v) {
    if (!v.empty()) add(v.data(), v.size() * sizeof(T));
  }
  std::uint64_t value() const { return h_; }
  /// 16 lower-case hex digits.
  std::string hex() const {
    char s[20];
    std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(h_));
    return s;
  }

 private:
  std::uint64_t h_ = 1469598103934665603ull;
};

}  // namespace prt
