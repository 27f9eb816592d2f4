// SH evaluation cost per direction, B = 1..16: the fast float and double paths (Sloan 2013
// polynomial recurrence, compile-time specialised) against the naive trigonometric reference.
// Run: build-sh/bench/bench_sh_eval --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "prt/sh/sh.hpp"

namespace {

constexpr int kDirs = 1024;

template <typename T>
std::vector<prt::Vec3<T>> directions() {
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  std::vector<prt::Vec3<T>> d;
  for (int i = 0; i < kDirs; ++i)
    d.emplace_back(prt::normalize(prt::Vec3d(g(rng), g(rng), g(rng))));
  return d;
}

template <typename T>
void BM_Eval(benchmark::State& state) {
  const int bands = int(state.range(0));
  const auto dirs = directions<T>();
  std::vector<T> out(bands * bands);
  for (auto _ : state) {
    for (const auto& d : dirs) {
      prt::sh::eval(bands, d, out.data());
      benchmark::DoNotOptimize(out.data());
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kDirs);
}

void BM_EvalBatchFloat(benchmark::State& state) {
  const int bands = int(state.range(0));
  const auto dirs = directions<float>();
  std::vector<float> out(std::size_t(kDirs) * bands * bands);
  for (auto _ : state) {
    prt::sh::evalBatch(bands, dirs, out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kDirs);
}

void BM_EvalNaive(benchmark::State& state) {
  const int bands = int(state.range(0));
  const auto dirs = directions<double>();
  std::vector<double> out(bands * bands);
  for (auto _ : state) {
    for (const auto& d : dirs) {
      prt::sh::evalReference(bands, d, out.data());
      benchmark::DoNotOptimize(out.data());
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kDirs);
}

}  // namespace

BENCHMARK(BM_Eval<float>)->DenseRange(1, 16);
BENCHMARK(BM_Eval<double>)->DenseRange(1, 16);
BENCHMARK(BM_EvalBatchFloat)->DenseRange(1, 16);
BENCHMARK(BM_EvalNaive)->DenseRange(1, 16);
BENCHMARK_MAIN();
