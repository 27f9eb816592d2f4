// Cube-map → SH projection at 9 bands (81 coefficients, RGB), faces of 128², 256², 512².
//   * Project:     envmap::projectEnvironment (unrolled polynomials, float chunks, parallel)
//   * NaiveEval:   baseline, one thread, per texel sh::eval + direction/solid angle from scratch
//   * MemoryRead:  baseline, one pass summing every pixel (the floor set by memory bandwidth)
// Run: build-light/bench/bench_envmap_project --benchmark_min_time=0.5

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/envmap/project.hpp"
#include "prt/sh/sh.hpp"

using namespace prt;

namespace {

constexpr int kBands = 9;

const envmap::Environment& cube(int n) {
  static std::array<envmap::Environment, 3> cache;
  const int slot = n == 128 ? 0 : n == 256 ? 1 : 2;
  if (cache[slot].texelCount() == 0) {
    std::array<image::Image, 6> faces;
    for (int f = 0; f < 6; ++f) {
      faces[f] = image::Image(n, n);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          faces[f].at(x, y) = Rgb(0.1f * f + 0.001f * x, 0.5f + 0.001f * y, 1.0f / (1 + x + y));
    }
    cache[slot] = envmap::Environment::cube(std::move(faces));
  }
  return cache[slot];
}

void Project(benchmark::State& state) {
  const auto& env = cube(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(envmap::projectEnvironment(env, kBands));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * env.texelCount()));
}

void NaiveEval(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto& env = cube(n);
  std::vector<float> y(kBands * kBands);
  for (auto _ : state) {
    std::vector<double> acc(3 * kBands * kBands, 0.0);
    for (int f = 0; f < 6; ++f)
      for (int py = 0; py < n; ++py)
        for (int px = 0; px < n; ++px) {
          const double s = 2.0 * (px + 0.5) / n - 1, t = 2.0 * (py + 0.5) / n - 1;
          const Vec3f d(normalize(envmap::cubeFaceDirection(f, s, t)));
          auto a = [](double u, double v) {
            return std::atan2(u * v, std::sqrt(u * u + v * v + 1));
          };
          const double s0 = s - 1.0 / n, s1 = s + 1.0 / n, t0 = t - 1.0 / n, t1 = t + 1.0 / n;
          const double w = a(s1, t1) - a(s0, t1) - a(s1, t0) + a(s0, t0);
          sh::eval(kBands, d, y.data());
          const Rgb& L = env.images()[f].at(px, py);
          for (int i = 0; i < kBands * kBands; ++i) {
            acc[3 * i] += w * L.x * y[i];
            acc[3 * i + 1] += w * L.y * y[i];
            acc[3 * i + 2] += w * L.z * y[i];
          }
        }
    benchmark::DoNotOptimize(acc.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * env.texelCount()));
}

void MemoryRead(benchmark::State& state) {
  const auto& env = cube(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    Rgb sum(0.0f);
    for (const auto& face : env.images())
      for (const Rgb& p : face.pixels) sum += p;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * env.texelCount()));
}

}  // namespace

BENCHMARK(Project)->Arg(128)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(NaiveEval)->Arg(128)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MemoryRead)->Arg(128)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
