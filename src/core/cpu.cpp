#include "prt/core/cpu.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace prt {

namespace {

Simd initialPolicy() {
  const char* v = std::getenv("PRT_SIMD");
  return v && std::strcmp(v, "portable") == 0 ? Simd::Portable : Simd::Auto;
}

std::atomic<Simd>& policy() {
  static std::atomic<Simd> p{initialPolicy()};
  return p;
}

}  // namespace

bool cpuHasAvx2Fma() {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool yes = [] {
    __builtin_cpu_init();  // safe even before libgcc's own constructor ran
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return yes;
#else
  return false;
#endif
}

bool simdAvx2Fma() {
  return cpuHasAvx2Fma() && policy().load(std::memory_order_relaxed) == Simd::Auto;
}

void setSimd(Simd p) {
  policy().store(p, std::memory_order_relaxed);
}

Simd simdPolicy() {
  return policy().load(std::memory_order_relaxed);
}

}  // namespace prt
