#pragma once
// Which SIMD paths the kernels may take — the one run-time CPU check for the kernels whose AVX2
// and portable forms differ in rounding (FMA): relighting and the cluster projections. Each has
// a portable form beside its AVX2+FMA one; setSimd(Simd::Portable) forces the portable forms,
// so tests compare both on every machine and benchmarks measure either. Results agree up to
// float rounding (documented per kernel). Loops compiled several times by GCC's target_clones
// (the bake's Sobol' direction batch, CPCA's chunk products) give identical bits in every
// version (no FMA contraction, same operation order), so they need no switch here.

namespace prt {

enum class Simd {
  Auto,      ///< the fastest path this CPU runs (AVX2+FMA where present)
  Portable,  ///< the portable kernels only
};

/// True when kernels may use AVX2 and FMA: the CPU has both and setSimd has not forced the
/// portable paths. Cheap (a cached CPU test and a relaxed atomic load).
bool simdAvx2Fma();
/// Whether this CPU has AVX2 and FMA at all (whatever setSimd says).
bool cpuHasAvx2Fma();
/// Sets the process-wide policy (tests, benchmarks, PRT_SIMD=portable in the environment).
void setSimd(Simd policy);
Simd simdPolicy();

/// Sets a policy for one scope and restores the previous one (tests).
class ScopedSimd {
 public:
  explicit ScopedSimd(Simd policy) : previous_(simdPolicy()) { setSimd(policy); }
  ~ScopedSimd() { setSimd(previous_); }
  ScopedSimd(const ScopedSimd&) = delete;
  ScopedSimd& operator=(const ScopedSimd&) = delete;

 private:
  Simd previous_;
};

}  // namespace prt
