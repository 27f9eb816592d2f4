#pragma once
// Shared by the libFuzzer targets: tight resource limits, so the fuzzer explores parsers instead
// of spending its time (and memory) on large but legal allocations, and the rule that a loader
// may only fail with prt::Error. Anything else (a crash, a sanitizer report, std::bad_alloc or
// any other exception escaping) is a finding.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"

namespace prt::fuzz {

inline void init() {
  static const bool once = [] {
    Limits l;
    l.maxFileBytes = 1 << 24;
    l.maxDecompressedBytes = 1 << 24;
    l.maxImageSide = 4096;
    l.maxImagePixels = 1 << 20;
    l.maxVertices = 1 << 20;
    l.maxTriangles = 1 << 20;
    l.maxNesting = 64;
    setLimits(l);
    return true;
  }();
  (void)once;
}

/// Set when the last input was refused with prt::Error (the replay test checks regression
/// inputs named reject_* / accept_* against it; libFuzzer ignores it).
inline bool& rejected() {
  static bool r = false;
  return r;
}

inline std::span<const unsigned char> bytes(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const unsigned char*>(data), size};
}
inline std::string_view text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace prt::fuzz

/// Defines LLVMFuzzerTestOneInput running BODY (which sees `data`, `size`), treating prt::Error
/// as the expected way to fail.
#define PRT_FUZZ_TARGET(...)                                                          \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    ::prt::fuzz::init();                                                              \
    ::prt::fuzz::rejected() = false;                                                  \
    try {                                                                             \
      __VA_ARGS__;                                                                    \
    } catch (const ::prt::Error&) {                                                   \
      ::prt::fuzz::rejected() = true;                                                 \
    }                                                                                 \
    return 0;                                                                         \
  }
