// SH rotation: build (Rotation::set, zyz angles) + apply (zxzxz, RGB), for B = 3, 6, 9, and
// rotateZ. Baseline in the same run: the previous method, dense per-band matrices built by the
// Ivanic–Ruedenberg recurrence (detail::rotationBlocksReference) then a dense RGB matrix-vector
// product (BM_DenseBuildApply).
// Run: build-rot/bench/bench_sh_rotate --benchmark_min_time=0.2
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

// The previous method: dense double blocks by the recurrence, a float copy, dense RGB apply.
void BM_DenseBuildApply(benchmark::State& state) {
  const int bands = int(state.range(0));
  const int size = prt::sh::detail::rotationBlockOffset(bands);
  std::vector<double> blocks(size);
  std::vector<float> blocksF(size);
  std::vector<prt::Rgb> in(bands * bands, prt::Rgb(0.5f)), out(bands * bands);
  std::vector<prt::Mat3d> rs;
  for (int k = 0; k < 64; ++k) rs.push_back(rotation(k));
  std::size_t k = 0;
  for (auto _ : state) {
    prt::sh::detail::rotationBlocksReference(bands, rs[k++ & 63], blocks.data());
    for (int i = 0; i < size; ++i) blocksF[i] = float(blocks[i]);
    for (int l = 0; l < bands; ++l) {
      const float* b = blocksF.data() + prt::sh::detail::rotationBlockOffset(l);
      const int w = 2 * l + 1, o = l * l;
      for (int i = 0; i < w; ++i) {
        prt::Rgb acc(0.0f);
        for (int j = 0; j < w; ++j) acc += in[o + j] * b[i * w + j];
        out[o + i] = acc;
      }
    }
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

template <typename T>
void BM_ApplyScalar(benchmark::State& state) {
  const int bands = int(state.range(0));
  const prt::sh::Rotation rot(bands, rotation(3));
  std::vector<T> in(bands * bands, T(0.5)), out(bands * bands);
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

BENCHMARK(BM_BuildApply)->Arg(3)->Arg(6)->Arg(9)->Arg(16);
BENCHMARK(BM_DenseBuildApply)->Arg(3)->Arg(6)->Arg(9)->Arg(16);
BENCHMARK(BM_Build)->Arg(3)->Arg(6)->Arg(9);
BENCHMARK(BM_ApplyRgb)->Arg(3)->Arg(6)->Arg(9)->Arg(16);
BENCHMARK(BM_ApplyScalar<float>)->Arg(6)->Arg(9)->Arg(16);
BENCHMARK(BM_ApplyScalar<double>)->Arg(6)->Arg(9)->Arg(16);
BENCHMARK(BM_RotateZRgb)->Arg(3)->Arg(6)->Arg(9);
BENCHMARK_MAIN();
