// CPCA (prt/compress/cpca.hpp) cost and pay-off, figures in docs/performance.md.
//
//   BM_Compress: compression time of a ~200k-vertex shadowed 9-band bake (builtin sphere-plane,
//     grid 440: 196,563 vertices, 81 floats each) with K = 256, N = 8. Goal: < 60 s on 2 cores.
//   BM_RelightDense / BM_RelightCompressed: one frame of diffuse relighting of 2^20 vertices at
//     9 bands, from the dense transfer and from its CPCA form (the per-frame cluster projections
//     included). The 1M rows are the real bake's rows tiled, so the compression error is the
//     bake's. BM_RelightCompressed reports in the same run
//       vs_dense      = dense 9-band frame time / compressed frame time,
//       vs_equal_err  = frame time of the dense transfer truncated to the fewest bands whose
//                       truncation error is at least the compression error / compressed time,
//     the second being "uncompressed relighting at equal error".

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "prt/compress/cpca.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/compressed.hpp"
#include "prt/relight/relight.hpp"
#include "prt/transport/bake.hpp"

namespace {

constexpr std::size_t kVertices = 1 << 20;

struct Fixture {
  prt::TransferField bake;  // ~200k rows, 9 bands, scalar
  prt::CompressedTransfer compressed;
  prt::CpcaStats stats;
  prt::TransferField dense1M;
  prt::CompressedTransfer compressed1M;
  prt::sh::RgbSh light{9};
  std::vector<prt::Rgb> albedo, out;
};

Fixture& fixture() {
  static std::unique_ptr<Fixture> f;
  if (f) return *f;
  f = std::make_unique<Fixture>();
  const prt::Mesh mesh = prt::builtinScene("builtin:sphere-plane?grid=440");
  const auto occ = prt::makeEmbreeOccluder(mesh);
  prt::BakeSettings s;
  s.mode = prt::TransferMode::Shadowed;
  s.bands = 9;
  s.samples = 128;
  s.vertexCount = mesh.vertexCount();
  f->bake = prt::bake(mesh, *occ, s);
  // Tile the rows to 2^20 vertices (dense and compressed alike).
  const std::size_t n = f->bake.vertexCount, D = f->bake.stride();
  f->dense1M = prt::TransferField::zeros(prt::TransferLayout::Vector, 9, 1, kVertices);
  for (std::size_t v = 0; v < kVertices; ++v)
    std::copy_n(f->bake.vertex(v % n), D, f->dense1M.vertex(v));
  for (int i = 0; i < 81; ++i)
    f->light.c[i] = prt::Rgb(1.0f / (1 + i), 0.8f / (1 + i), 0.6f / (1 + i));
  f->albedo.assign(kVertices, prt::Rgb(0.7f));
  f->out.assign(kVertices, prt::Rgb(0.0f));
  return *f;
}

void compressOnce(Fixture& f) {
  if (!f.compressed.cluster.empty()) return;
  f.compressed = prt::compressCpca(f.bake, {256, 8, 1, 30}, &f.stats);
  const std::size_t n = f.bake.vertexCount, N = 8;
  prt::CompressedTransfer& c = f.compressed1M;
  c = f.compressed;
  c.vertexCount = kVertices;
  c.cluster.resize(kVertices);
  c.weights.resize(kVertices * N);
  for (std::size_t v = n; v < kVertices; ++v) {
    c.cluster[v] = f.compressed.cluster[v % n];
    std::copy_n(f.compressed.weights.data() + (v % n) * N, N, c.weights.data() + v * N);
  }
}

void BM_Compress(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) {
    f.compressed.cluster.clear();
    compressOnce(f);
  }
  state.counters["rows"] = static_cast<double>(f.bake.vertexCount);
  state.counters["seconds"] = f.stats.seconds;
  state.counters["iterations"] = f.stats.iterations;
  state.counters["rel_rms"] = f.stats.relativeRms;
  state.counters["snr_db"] = f.stats.snrDb;
  state.counters["ratio"] = f.stats.compressionRatio;
  state.counters["threads"] = prt::maxThreads();
}
BENCHMARK(BM_Compress)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

double frameSeconds(const std::function<void()>& fn, int reps = 10) {
  fn();  // warm
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < reps; ++i) fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / reps;
}

void BM_RelightDense(benchmark::State& state) {
  Fixture& f = fixture();
  const prt::relight::PreparedLight p = prt::relight::prepareLight(f.light, 9);
  for (auto _ : state) {
    prt::relight::relight(f.dense1M, p, f.albedo, f.out);
    benchmark::DoNotOptimize(f.out.data());
  }
  state.SetBytesProcessed(state.iterations() * f.dense1M.data.size() * 4);
}
BENCHMARK(BM_RelightDense)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RelightCompressed(benchmark::State& state) {
  Fixture& f = fixture();
  compressOnce(f);
  const prt::relight::PreparedLight p = prt::relight::prepareLight(f.light, 9);
  auto compressedFrame = [&] {
    prt::relight::relightCompressed(f.compressed1M, p, f.albedo, f.out);  // projections included
    benchmark::DoNotOptimize(f.out.data());
  };
  for (auto _ : state) compressedFrame();
  // Same-run ratios, measured back to back.
  const double tc = frameSeconds(compressedFrame);
  const double td = frameSeconds([&] {
    prt::relight::relight(f.dense1M, p, f.albedo, f.out);
    benchmark::DoNotOptimize(f.out.data());
  });
  // Equal error: the fewest bands b whose truncation error sqrt(Σ_{i ≥ b²} T_i² / Σ T_i²) over
  // the bake is at most the compression's relative RMS error.
  std::vector<double> energy(81, 0.0);
  for (std::size_t v = 0; v < f.bake.vertexCount; ++v)
    for (int i = 0; i < 81; ++i) energy[i] += double(f.bake.vertex(v)[i]) * f.bake.vertex(v)[i];
  double total = 0;
  for (double e : energy) total += e;
  int b = 9;
  for (int k = 1; k <= 9; ++k) {
    double tail = 0;
    for (int i = k * k; i < 81; ++i) tail += energy[i];
    if (std::sqrt(tail / total) <= f.stats.relativeRms) {
      b = k;
      break;
    }
  }
  const prt::TransferField cut = f.dense1M.truncated(b);
  const prt::relight::PreparedLight pb = prt::relight::prepareLight(f.light, b);
  const double te = frameSeconds([&] {
    prt::relight::relight(cut, pb, f.albedo, f.out);
    benchmark::DoNotOptimize(f.out.data());
  });
  state.counters["vs_dense"] = td / tc;
  state.counters["equal_err_bands"] = b;
  state.counters["vs_equal_err"] = te / tc;
  state.counters["rel_rms"] = f.stats.relativeRms;
  state.counters["bytes_per_vertex"] =
      static_cast<double>(f.compressed1M.bytes()) / static_cast<double>(kVertices);
}
BENCHMARK(BM_RelightCompressed)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
