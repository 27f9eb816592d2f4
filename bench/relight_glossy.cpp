// Glossy relighting (relight::relightPrepared of dense matrices) against the bounds of the machine,
// same run:
//   * vs_stream: a vectorised streaming read of the same matrix bytes (memory bandwidth) —
//     relighting reads each vertex's B⁴ floats once and does 2 FMAs per float, so bandwidth is
//     the ceiling on a CPU with two or more FMA units per core;
//   * vs_eigen: Eigen's matrix product L' = M_p [L_r L_g L_b] per vertex (a Map over the same
//     data, B² × B² times B² × 3), the plain formulation of Sloan et al. 2002 §6, parallel in the
//     same chunks (it computes less: no view, no lobe, no diffuse part).
//   BM_RelightGlossyLightOnly: the light turning under a still eye, from the view-collapsed vector
//     transfer (relight::viewTransfer), against relighting the matrices every frame.
// The mesh is the Stanford bunny (glmark2-data, 35k vertices) when installed, else a builtin
// sphere of 41k vertices; the transfer is synthetic (relighting cost does not depend on values).
//   bench_relight_glossy --benchmark_counters_tabular=true
// Results: docs/perf/relight.md.

#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <random>

#include "baselines.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/view_transfer.hpp"

namespace {

using prt::bench::secondsOf;
using prt::bench::streamSum;

const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

struct Data {
  prt::Mesh mesh;
  prt::Transfer transfer;
  prt::sh::RgbSh light;
  std::vector<prt::Rgb> out;
};

const prt::Mesh& mesh() {
  static const prt::Mesh m = std::filesystem::exists(kBunny)
                                 ? prt::loadScene({kBunny}, nullptr)
                                 : prt::builtinScene("builtin:sphere?subdiv=6");
  return m;
}

Data& data(int bands) {
  static std::map<int, std::unique_ptr<Data>> cache;
  auto& slot = cache[bands];
  if (!slot) {
    for (auto& [key, d] : cache)
      if (d && &d != &slot) d.reset();
    slot = std::make_unique<Data>();
    Data& d = *slot;
    d.mesh = mesh();
    prt::TransferShape shape;
    shape.layout = prt::TransferLayout::Matrix;
    shape.bands = bands;
    shape.rows.count = d.mesh.vertexCount();
    d.transfer = prt::Transfer::zeros(shape);
    float* values = d.transfer.mutableValues();
    prt::parallelFor(d.transfer.values().size(), 1 << 16, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i)
        values[i] = float((i * 2654435761u) % 1000) * 1e-3f - 0.5f;
    });
    d.light = prt::sh::RgbSh(bands);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (auto& c : d.light.c) c = prt::Rgb(u(rng), u(rng), u(rng));
    d.out.assign(d.mesh.vertexCount(), prt::Rgb(0.0f));
  }
  return *slot;
}

/// L' = M L for every vertex with Eigen (row-major B² × B² map times B² × 3).
void eigenProduct(const prt::Transfer& t, const Eigen::MatrixXf& light, std::vector<float>& out) {
  const int nc = t.coeffs();
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  prt::parallelFor(t.rowCount(), 64, [&](std::size_t b, std::size_t e) {
    for (std::size_t v = b; v < e; ++v) {
      Eigen::Map<const RowMajor> m(t.row(v), nc, nc);
      Eigen::Map<Eigen::MatrixXf> o(out.data() + v * nc * 3, nc, 3);
      o.noalias() = m * light;
    }
  });
}

// range(0): bands; range(1): 1 = glossy lobe + diffuse, 0 = diffuse only (kd, no lobe).
void BM_RelightGlossy(benchmark::State& state) {
  Data& d = data(int(state.range(0)));
  const prt::Material material =
      prt::parseMaterial(state.range(1) ? "phong?exponent=16&ks=0.5&kd=0.5" : "lambert");
  const auto light = prt::relight::prepareLight(d.light, d.transfer.bands());
  const auto mat = prt::prepareMaterial(material, d.transfer.bands());
  const prt::relight::Surface surface{d.mesh.positions, d.mesh.normals, {}};
  const prt::Vec3f eye(0, 1, 3);
  auto run = [&] { prt::relight::relightPrepared(d.transfer, light, mat, surface, eye, d.out); };
  const int nc = d.transfer.coeffs();
  Eigen::MatrixXf l(nc, 3);
  for (int i = 0; i < nc; ++i)
    for (int c = 0; c < 3; ++c) l(i, c) = d.light.c[i][c];
  std::vector<float> eigenOut(d.transfer.rowCount() * nc * 3);
  run();
  const double stream = secondsOf(
      [&] { benchmark::DoNotOptimize(streamSum(d.transfer.values().span(), 1 << 16)); }, 5);
  const double eigen = secondsOf([&] { eigenProduct(d.transfer, l, eigenOut); }, 5);
  const double relit = secondsOf(run, 5);
  for (auto _ : state) {
    run();
    benchmark::ClobberMemory();
  }
  const double bytes = double(d.transfer.values().size()) * 4;
  state.SetBytesProcessed(std::int64_t(state.iterations()) * std::int64_t(bytes));
  state.counters["vertices"] = double(d.transfer.rowCount());
  state.counters["frame_ms"] = relit * 1e3;
  state.counters["vs_stream"] = stream / relit;
  state.counters["vs_eigen"] = eigen / relit;
  state.counters["stream_GBps"] = bytes / stream * 1e-9;
}

// A light that turns under a still eye: the matrices collapsed once for the view
// (relight::viewTransfer, the cost of one full frame), then per frame a vector relighting of
// 3·B² floats per vertex. Counters: light_only_ms per frame, collapse_ms once, and the speed-up
// over relighting the matrices each frame (full_ms, same run).
void BM_RelightGlossyLightOnly(benchmark::State& state) {
  Data& d = data(int(state.range(0)));
  const prt::Material material = prt::parseMaterial("phong?exponent=16&ks=0.5&kd=0.5");
  const auto light = prt::relight::prepareLight(d.light, d.transfer.bands());
  const auto mat = prt::prepareMaterial(material, d.transfer.bands());
  const prt::relight::Surface surface{d.mesh.positions, d.mesh.normals, {}};
  const prt::Vec3f eye(0, 1, 3);
  prt::Transfer t;
  const double collapse =
      secondsOf([&] { t = prt::relight::viewTransfer(d.transfer, mat, surface, eye); }, 3);
  const double full = secondsOf(
      [&] { prt::relight::relightPrepared(d.transfer, light, mat, surface, eye, d.out); }, 20);
  auto run = [&] {
    prt::relight::relightPrepared(t, light, prt::PreparedMaterial{}, {}, eye, d.out);
  };
  const double lightOnly = secondsOf(run, 20);
  for (auto _ : state) {
    run();
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = double(d.transfer.rowCount());
  state.counters["light_only_ms"] = lightOnly * 1e3;
  state.counters["collapse_ms"] = collapse * 1e3;
  state.counters["full_ms"] = full * 1e3;
  state.counters["speedup"] = full / lightOnly;
}

BENCHMARK(BM_RelightGlossyLightOnly)->Arg(5)->Arg(9)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK(BM_RelightGlossy)
    ->Args({3, 1})
    ->Args({5, 0})
    ->Args({5, 1})
    ->Args({7, 1})
    ->Args({9, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
