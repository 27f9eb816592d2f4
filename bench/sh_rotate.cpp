// SH rotation: build (Ivanic–Ruedenberg recurrence, Rotation::set) + apply, for B = 3, 6, 9, and
// rotateZ; baseline in the same run: apply alone, and a rotation done the slow way (project the
// rotated function by quadrature would be far slower; we use the matrix apply as the reference
// for the cost of the unavoidable B-band matrix-vector work).
// Run: build-sh/bench/bench_sh_rotate --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "prt/sh/rotate.hpp"

namespace {

prt::Mat3d rotation(int k) {
  return prt::rotationAxisAngle(prt::normalize(prt::Vec3d(1, 2, 3 + k % 7)), 0.1 * k);
}

void BM_BuildApply(benchmark::State& state) {
  const int bands = int(state.range(0));
  prt::sh::Rotation rot(bands);
  std::vector<prt::Rgb> in(bands * bands, prt::Rgb(0.5f)), out(bands * bands);
  std::vector<prt::Mat3d> rs;
  for (int k = 0; k < 64; ++k) rs.push_back(rotation(k));
  std::size_t k = 0;
  for (auto _ : state) {
    rot.set(rs[k++ & 63]);
    rot.apply(in.data(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
}

void BM_Build(benchmark::State& state) {
  const int bands = int(state.range(0));
  prt::sh::Rotation rot(bands);
  std::vector<prt::Mat3d> rs;
  for (int k = 0; k < 64; ++k) rs.push_back(rotation(k));
  std::size_t k = 0;
  for (auto _ : state) {
    rot.set(rs[k++ & 63]);
    benchmark::ClobberMemory();
  }
}

void BM_ApplyRgb(benchmark::State& state) {
  const int bands = int(state.range(0));
  const prt::sh::Rotation rot(bands, rotation(3));
  std::vector<prt::Rgb> in(bands * bands, prt::Rgb(0.5f)), out(bands * bands);
  for (auto _ : state) {
    rot.apply(in.data(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
}

void BM_RotateZRgb(benchmark::State& state) {
  const int bands = int(state.range(0));
  std::vector<prt::Rgb> in(bands * bands, prt::Rgb(0.5f)), out(bands * bands);
  double a = 0.1;
  for (auto _ : state) {
    prt::sh::rotateZ(bands, a, in.data(), out.data());
    a += 1e-3;
    benchmark::DoNotOptimize(out.data());
  }
}

}  // namespace

BENCHMARK(BM_BuildApply)->Arg(3)->Arg(6)->Arg(9);
BENCHMARK(BM_Build)->Arg(3)->Arg(6)->Arg(9);
BENCHMARK(BM_ApplyRgb)->Arg(3)->Arg(6)->Arg(9);
BENCHMARK(BM_RotateZRgb)->Arg(3)->Arg(6)->Arg(9);
BENCHMARK_MAIN();
