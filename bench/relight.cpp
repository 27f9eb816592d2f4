// Relighting throughput against the memory system. Relighting reads each vertex's transfer once
// and does a few flops per float, so its ceiling is a streaming read of the same bytes; the
// baseline here is exactly that (a vectorised sum of the transfer array, split over the same
// threads and chunks) measured in the same run. Each relight benchmark reports
//   vs_stream = (stream time) / (relight time)  for the same transfer bytes,
// i.e. the fraction of streaming bandwidth relighting achieves (target ≥ 0.7).
// Results: docs/perf/relight.md.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <random>

#include "baselines.hpp"
#include "prt/core/parallel.hpp"
#include "prt/relight/relight.hpp"

namespace {

using prt::bench::secondsOf;
using prt::bench::streamSum;

constexpr std::size_t kVertices = 1 << 20;

struct Data {
  prt::Transfer transfer;
  prt::sh::RgbSh light;
  std::vector<prt::Rgb> out;
  std::vector<prt::Rgb> albedo;
};

// One data set per (bands, channels), built on first use and kept (up to ~1 GB for 9-band RGB).
Data& data(int bands, int channels) {
  static std::map<std::pair<int, int>, std::unique_ptr<Data>> cache;
  auto& slot = cache[{bands, channels}];
  if (!slot) {
    // Release the previous data set first: the 9-band RGB one is large.
    for (auto& [key, d] : cache)
      if (d && &d != &slot) d.reset();
    slot = std::make_unique<Data>();
    Data& d = *slot;
    prt::TransferShape shape;
    shape.bands = bands;
    shape.channels = channels;
    shape.rows.count = kVertices;
    d.transfer = prt::Transfer::zeros(shape);
    float* values = d.transfer.mutableValues();
    prt::parallelFor(d.transfer.values().size(), 1 << 16, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) values[i] = float((i * 2654435761u) % 1000) * 1e-3f;
    });
    d.light = prt::sh::RgbSh(bands);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (auto& c : d.light.c) c = prt::Rgb(u(rng), u(rng), u(rng));
    d.out.assign(kVertices, prt::Rgb(0.0f));
    d.albedo.assign(kVertices, prt::Rgb(0.5f));
  }
  return *slot;
}

void BM_StreamSum(benchmark::State& state) {
  Data& d = data(int(state.range(0)), int(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(streamSum(d.transfer));
  state.SetBytesProcessed(std::int64_t(state.iterations()) *
                          std::int64_t(d.transfer.values().size() * 4));
}

// range(2): 0 = no albedo (white), 1 = per-vertex albedo (12 more bytes read per vertex).
void BM_Relight(benchmark::State& state) {
  Data& d = data(int(state.range(0)), int(state.range(1)));
  const auto light = prt::relight::prepareLight(d.light, d.transfer.bands());
  std::span<const prt::Rgb> albedo;
  if (state.range(2)) albedo = d.albedo;
  // The one entry point, the light prepared once (what a frame loop does).
  auto run = [&] {
    prt::relight::relightPrepared(d.transfer, light, prt::PreparedMaterial{}, {{}, {}, albedo},
                                  prt::Vec3f(0.0f), d.out);
  };
  run();  // warm
  // Best-of-5 of each, interleaved in the same run, for the ratio.
  const double stream = secondsOf([&] { benchmark::DoNotOptimize(streamSum(d.transfer)); }, 5);
  const double relit = secondsOf(run, 5);
  for (auto _ : state) {
    run();
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(std::int64_t(state.iterations()) *
                          std::int64_t(d.transfer.values().size() * 4));
  state.counters["vs_stream"] = stream / relit;
  state.counters["stream_GBps"] = double(d.transfer.values().size() * 4) / stream * 1e-9;
}

void args(benchmark::internal::Benchmark* b, bool albedo) {
  for (int channels : {1, 3})
    for (int bands : {3, 5, 9}) {
      if (albedo)
        b->Args({bands, channels, 0})->Args({bands, channels, 1});
      else
        b->Args({bands, channels});
    }
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_StreamSum)->Apply([](auto* b) { args(b, false); });
BENCHMARK(BM_Relight)->Apply([](auto* b) { args(b, true); });

}  // namespace

BENCHMARK_MAIN();
