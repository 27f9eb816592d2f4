// Benchmarks of probe grids (issue 32, docs/probes.md) against baselines measured in the same run:
//
//   BM_ProbeRelight/NX/NY/NZ/BANDS   relighting every probe of the builtin Cornell box's grid
//                                    after a light change (relight::relightProbes: B² × B² per
//                                    probe and channel, RGB probes), against re-baking the grid:
//                                    its rays (probes × 1024 samples, shadowed) at raw Embree's
//                                    rate (rtcOccluded1M streams of 64 from the probes, uniform
//                                    over the sphere) measured here. Counters: relight_ms,
//                                    rebake_ms (at raw rate: a lower bound of any re-bake),
//                                    rebake_vs_relight, GMAC/s.
//   BM_ProbeBake/BANDS               the probe bake (shadowed, 256 samples, 32 × 16 × 16), all
//                                    of it (its inside-geometry test and refill too), against raw
//                                    Embree on as many rays as its samples from the same probes:
//                                    vs_raw; its pass alone (the rays and their sums, without
//                                    the inside-geometry test): vs_raw_pass.
//
// Run: build/bench/bench_probes --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/passes.hpp"
#include "raw_embree.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Box {
  prt::Mesh mesh = prt::builtinScene("builtin:cornell");
  std::unique_ptr<prt::Occluder> occluder = prt::makeEmbreeOccluder(mesh);
};

Box& box() {
  static Box b;
  return b;
}

prt::ProbeGrid gridOf(const prt::Mesh& m, std::array<int, 3> n) {
  const prt::Bounds b = prt::computeBounds(m);
  return prt::makeProbeGrid(b.lo, b.hi, n, "cornell");
}

/// Seconds raw Embree takes for `samples` occlusion rays from every probe of `grid`, uniform over
/// the sphere (Owen-scrambled Sobol', a seed per probe), in streams of 64 (ray generation untimed).
double rawSeconds(const prt::Mesh& mesh, const prt::ProbeGrid& grid, int samples) {
  RTCDevice device = rtcNewDevice("threads=0,verbose=0");
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                        RTC_FORMAT_FLOAT3, 12, mesh.vertexCount()));
  std::memcpy(v, mesh.positions.data(), mesh.vertexCount() * 12);
  auto* idx = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, mesh.triangleCount()));
  std::memcpy(idx, mesh.triangles.data(), mesh.triangleCount() * 12);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene);
  const prt::OwenSobol2D sobol(static_cast<std::uint32_t>(samples));
  const std::size_t probes = grid.probes(), block = std::max<std::size_t>(1, (1u << 20) / samples);
  std::vector<RTCRay> rays;
  double seconds = 0;
  for (std::size_t lo = 0; lo < probes; lo += block) {
    const std::size_t hi = std::min(probes, lo + block);
    rays.resize((hi - lo) * std::size_t(samples));
    tbb::parallel_for(lo, hi, [&](std::size_t p) {
      const prt::Vec3f o = grid.position(p);
      const std::uint64_t key = prt::deriveSeed(3, p);
      for (int i = 0; i < samples; ++i) {
        const prt::Point2 u = sobol.point(std::uint32_t(i), std::uint32_t(key),
                                          std::uint32_t(key >> 32));
        const float z = 1 - 2 * u.x, r = std::sqrt(std::max(0.0f, 1 - z * z));
        const float phi = 2 * float(prt::kPi) * u.y;
        RTCRay& ray = rays[(p - lo) * std::size_t(samples) + std::size_t(i)];
        ray.org_x = o.x, ray.org_y = o.y, ray.org_z = o.z;
        ray.dir_x = r * std::cos(phi), ray.dir_y = r * std::sin(phi), ray.dir_z = z;
        ray.tnear = 0, ray.tfar = std::numeric_limits<float>::infinity();
        ray.time = 0, ray.mask = ~0u, ray.id = 0, ray.flags = 0;
      }
    });
    seconds += prt::bench::traceStreams(scene, rays);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return seconds;
}

prt::BakeSettings probeSettings(const prt::ProbeGrid& grid, int bands, int samples,
                                prt::TransferMode mode) {
  prt::BakeSettings s;
  s.mode = mode;
  s.layout = prt::TransferLayout::Matrix;
  s.domain = prt::TransferDomain::Probes;
  s.probes = grid;
  s.bands = bands;
  s.samples = samples;
  s.bounces = mode == prt::TransferMode::Interreflected ? 1 : 0;
  return s;
}

void BM_ProbeRelight(benchmark::State& state) {
  Box& b = box();
  const std::array<int, 3> n{int(state.range(0)), int(state.range(1)), int(state.range(2))};
  const int bands = int(state.range(3));
  const prt::ProbeGrid grid = gridOf(b.mesh, n);
  // The probes themselves: an inter-reflected bake at a few samples (the relighting's cost does
  // not depend on how well they were baked); RGB, as the box's coloured walls make them.
  prt::ThreadExecutor threads;
  const prt::Transfer t = prt::bake(b.mesh, *b.occluder,
                                    probeSettings(grid, bands, 16, prt::TransferMode::Interreflected),
                                    threads);
  prt::sh::RgbSh light(bands);
  for (int i = 0; i < bands * bands; ++i) light.c[std::size_t(i)] = prt::Rgb(1.0f / (1 + i));
  double relight = 0;
  std::size_t count = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    const prt::relight::ProbeLighting l = prt::relight::relightProbes(t, light);
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    benchmark::DoNotOptimize(l.coefficients.data());
    relight += s;
    ++count;
    state.SetIterationTime(s);
  }
  const double raw = rawSeconds(b.mesh, grid, 1024);
  const double relightS = relight / double(count);
  const double macs = double(grid.probes()) * bands * bands * bands * bands * 3;
  state.counters["probes"] = double(grid.probes());
  state.counters["channels"] = t.channels();
  state.counters["relight_ms"] = relightS * 1e3;
  state.counters["rebake_ms"] = raw * 1e3;
  state.counters["rebake_vs_relight"] = raw / relightS;
  state.counters["GMAC/s"] = macs / relightS * 1e-9;
  state.counters["threads"] = prt::maxThreads();
}

void BM_ProbeBake(benchmark::State& state) {
  Box& b = box();
  const int bands = int(state.range(0));
  const prt::ProbeGrid grid = gridOf(b.mesh, {32, 16, 16});
  const prt::BakeSettings s = probeSettings(grid, bands, 256, prt::TransferMode::Shadowed);
  double bake = 0, pass = 0, raw = 0;
  std::uint64_t rays = 0;
  for (auto _ : state) {
    prt::ThreadExecutor threads;
    prt::BakeStats st;
    const prt::Transfer t = prt::bake(b.mesh, *b.occluder, s, threads, &st);
    benchmark::DoNotOptimize(t.values().data());
    bake += st.secondsTotal;  // all the bake does: the inside-geometry test and refill too
    pass += st.secondsDirect;  // its one pass alone (shadowed: the rays and their sums)
    rays += st.rays;
    raw += rawSeconds(b.mesh, grid, s.samples);
    state.SetIterationTime(st.secondsTotal);
  }
  state.counters["probes"] = double(grid.probes());
  state.counters["bake_Mrays/s"] = double(rays) / bake * 1e-6;
  state.counters["raw_Mrays/s"] = double(rays) / raw * 1e-6;
  state.counters["vs_raw"] = raw / bake;
  state.counters["vs_raw_pass"] = raw / pass;
}

}  // namespace

BENCHMARK(BM_ProbeRelight)
    ->Args({32, 16, 16, 3})
    ->Args({32, 16, 16, 2})
    ->Args({16, 16, 16, 4})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProbeBake)->Arg(3)->Iterations(3)->UseManualTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
