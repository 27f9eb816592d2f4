// prt unwrap's atlas on the Stanford bunny (69,451 triangles; skipped when glmark2-data is not
// installed) and the builtin sphere: time on one thread and on all, and the atlas's quality as
// counters (charts, wasted area of the square and of the texels, L2 stretch, texel density
// spread). Baselines in the same run: the mesh's topology pass alone (welding and edge
// adjacency, which any unwrapper must do) and the chart growing, so the cost of the conformal
// maps and the packing reads as a ratio.
//
//   bench_unwrap --benchmark_counters_tabular=true
//
// Figures and the machine: docs/performance.md, "Unwrap".

#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "prt/core/parallel.hpp"
#include "prt/geometry/load.hpp"
#include "prt/unwrap/charts.hpp"
#include "prt/unwrap/unwrap.hpp"

namespace {

using namespace prt;

constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

const Mesh* meshFor(const std::string& name, benchmark::State& state) {
  static const Mesh sphere = loadMesh("builtin:sphere");
  if (name == "sphere") return &sphere;
  if (!std::filesystem::exists(kBunny)) {
    state.SkipWithError("/usr/share/glmark2/models/bunny.obj absent (glmark2-data)");
    return nullptr;
  }
  static const Mesh bunny = loadMesh(kBunny);
  return &bunny;
}

void BM_Adjacency(benchmark::State& state, const std::string& name) {
  const Mesh* m = meshFor(name, state);
  if (!m) return;
  for (auto _ : state) benchmark::DoNotOptimize(buildAdjacency(*m));
  state.counters["triangles"] = double(m->triangleCount());
}

void BM_GrowCharts(benchmark::State& state, const std::string& name) {
  const Mesh* m = meshFor(name, state);
  if (!m) return;
  std::uint32_t charts = 0;
  for (auto _ : state) {
    const TriangleAdjacency adj = buildAdjacency(*m);
    charts = growCharts(adj, 60 * M_PI / 180).count;
    benchmark::DoNotOptimize(charts);
  }
  state.counters["charts"] = charts;
}

void BM_Unwrap(benchmark::State& state, const std::string& name) {
  const Mesh* m = meshFor(name, state);
  if (!m) return;
  ThreadLimit limit(int(state.range(0)));
  UnwrapSettings s;
  s.resolution = int(state.range(1));
  AtlasStats stats;
  for (auto _ : state) {
    const UnwrapResult r = unwrap(*m, s);
    stats = r.stats;
    benchmark::DoNotOptimize(r.mesh.lightmapUvs.data());
  }
  state.counters["threads"] = double(state.range(0));
  state.counters["charts"] = double(stats.charts);
  state.counters["wasted_area"] = stats.wastedArea;
  state.counters["wasted_texels"] = stats.wastedTexels;
  state.counters["stretch_L2"] = stats.stretchL2;
  state.counters["density_p05"] = stats.densityP05;
  state.counters["density_p95"] = stats.densityP95;
}

BENCHMARK_CAPTURE(BM_Adjacency, sphere, std::string("sphere"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GrowCharts, sphere, std::string("sphere"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Unwrap, sphere, std::string("sphere"))
    ->Args({1, 512})
    ->Args({0, 512})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Adjacency, bunny, std::string("bunny"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GrowCharts, bunny, std::string("bunny"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Unwrap, bunny, std::string("bunny"))
    ->Args({1, 1024})
    ->Args({0, 1024})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
