// The C++ side of the Python binding's overhead (docs/performance.md, "Python"): prt::bake of a
// mesh file with a BVH built once, exactly the work prtkit.bake does on a prtkit.Mesh whose
// BVH is already built. bench/python_overhead.py runs this program and prtkit.bake in turns
// on the same mesh and settings and reports the ratio.
//
//   bench_python_overhead [MESH] [--samples N] [--bands B] [--mode M] [benchmark flags]
//
// MESH defaults to the Stanford dragon (100k vertices) of /work/shared/data, else the bunny of
// glmark2-data; the case is skipped with a message when neither exists.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "prt/geometry/load.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transport/bake.hpp"

namespace {

std::string gMesh;
prt::BakeSettings gSettings;

void BM_Bake(benchmark::State& state) {
  if (gMesh.empty()) {
    state.SkipWithError("no mesh: give a path (the dragon or glmark2-data's bunny are absent)");
    return;
  }
  const prt::Mesh mesh = prt::loadMesh(gMesh);
  const auto occluder = prt::makeEmbreeOccluder(mesh);
  prt::BakeStats stats;
  for (auto _ : state) {
    prt::Transfer t = prt::bake(mesh, *occluder, gSettings, &stats);
    benchmark::DoNotOptimize(t.values().data());
  }
  state.counters["vertices"] = static_cast<double>(mesh.vertexCount());
  state.counters["Mrays_per_s"] = stats.raysPerSecond / 1e6;
  state.SetLabel(gMesh);
}
BENCHMARK(BM_Bake)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

int main(int argc, char** argv) {
  for (const char* p : {"/work/shared/data/meshes/stanford_dragon/dragon_vrip_res2.ply.gz",
                        "/usr/share/glmark2/models/bunny.obj"})
    if (std::filesystem::exists(p)) {
      gMesh = p;
      break;
    }
  gSettings.mode = prt::TransferMode::Shadowed;
  gSettings.bands = 3;
  gSettings.samples = 256;
  // Our options first, the rest for Google Benchmark.
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    const auto value = [&] { return i + 1 < argc ? argv[++i] : argv[i]; };
    if (std::strcmp(argv[i], "--samples") == 0)
      gSettings.samples = std::atoi(value());
    else if (std::strcmp(argv[i], "--bands") == 0)
      gSettings.bands = std::atoi(value());
    else if (std::strcmp(argv[i], "--mode") == 0)
      gSettings.mode = prt::parseTransferMode(value());
    else if (argv[i][0] != '-')
      gMesh = argv[i];
    else
      rest.push_back(argv[i]);
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
