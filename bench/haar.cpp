// Benchmarks of the Haar basis (issue 33; docs/haar.md), each against a baseline in the same
// run:
//
//   bench_haar
//     BM_HaarRelight/SCENE/TERMS   relight every vertex of a Haar bake (32² cube, TERMS per
//                                  vertex) under a 200-term light: ms per relight, against the
//                                  streaming read of the same rows (vs_stream: how far from
//                                  memory bound) and the 5-band SH relighting of the same mesh
//                                  (vs_sh5).
//     BM_HaarProductOrder/SCENE/TERMS
//                                  the sparse product Σ_t D̃_t L̃[k_t] alone, on one thread,
//                                  organised two ways over the same rows and 200-term light:
//                                  by row (gather from the light laid out densely, as
//                                  relightHaar does) and by light coefficient (Ng et al. 2003
//                                  §6: each light term scatters into the rows that keep its
//                                  coefficient, a column of the transfer built untimed):
//                                  by_light_vs_by_row, the two's time ratio.
//     BM_HaarTurnLight/ENV         a turned light over a 32² cube (200 terms), as a viewer makes
//                                  it at each turn: splatted from the environment's 128² cube,
//                                  made once (haar::turnedLight; the desktop and browser
//                                  viewers), against projecting the environment itself at each
//                                  turn (haar::projectLight; prt render): vs_project.
//     BM_HaarBake/SCENE            the shadowed Haar bake (the default 32² cube, one ray per
//                                  texel, 64 terms) against raw Embree (rtcOccluded1M, 64-ray
//                                  streams) on the same rays, ray generation untimed: vs_raw.
//
// Scenes: bunny = /usr/share/glmark2/models/bunny.obj (skipped with a message if absent),
// sphere-plane = builtin:sphere-plane. Environments: builtin:sky, and Poly Haven's courtyard
// (blender-data; skipped with a message if absent).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>

#include "baselines.hpp"
#include "prt/core/sampling.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "prt/haar/cube_texels.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/haar/turned_cube.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/transport/bake.hpp"
#include "raw_embree.hpp"
#include "scenes.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using prt::bench::kBunny;
using prt::bench::Scene;
using prt::bench::scene;

prt::BakeSettings haarSettings(int resolution, int terms) {
  prt::BakeSettings s;
  s.mode = prt::TransferMode::Shadowed;
  s.basis = prt::TransferBasis::Haar;
  s.haar = {resolution, terms};
  s.samples = 1;
  s.seed = 7;
  return s;
}

void BM_HaarRelight(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((std::string(kBunny) + " not found: bunny case skipped").c_str());
    return;
  }
  const int terms = static_cast<int>(state.range(0));
  const prt::Transfer haarT = prt::bake(s->mesh, *s->occluder, haarSettings(32, terms));
  prt::BakeSettings ss;
  ss.mode = prt::TransferMode::Shadowed;
  ss.bands = 5;
  ss.samples = 64;
  const prt::Transfer shT = prt::bake(s->mesh, *s->occluder, ss);
  const prt::envmap::Environment sky = prt::envmap::builtinEnvironment("builtin:sky");
  const prt::haar::HaarLight light = prt::haar::projectLight(sky, 32, 200);
  const prt::sh::RgbSh sh5 = prt::envmap::projectEnvironment(sky, 5);
  std::vector<prt::Rgb> out(s->mesh.vertexCount());
  const prt::relight::Surface surface{s->mesh.positions, s->mesh.normals, {}};
  double haarSeconds = 0, streamSeconds = 0, shSeconds = 0;
  int n = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    prt::relight::relightHaar(haarT, light, s->mesh.normals, {}, out);
    const double t = std::chrono::duration<double>(Clock::now() - t0).count();
    benchmark::DoNotOptimize(out.data());
    state.SetIterationTime(t);
    haarSeconds += t;
    streamSeconds += prt::bench::secondsOf(
        [&] { benchmark::DoNotOptimize(prt::bench::streamSum(haarT)); }, 1);
    shSeconds += prt::bench::secondsOf(
        [&] {
          prt::relight::relight(shT, sh5, prt::Material{}, surface, prt::Vec3f(0.0f), out);
          benchmark::DoNotOptimize(out.data());
        },
        1);
    ++n;
  }
  state.counters["vertices"] = double(s->mesh.vertexCount());
  state.counters["ms"] = 1e3 * haarSeconds / n;
  state.counters["stream_ms"] = 1e3 * streamSeconds / n;
  state.counters["sh5_ms"] = 1e3 * shSeconds / n;
  state.counters["vs_stream"] = streamSeconds / haarSeconds;
  state.counters["vs_sh5"] = shSeconds / haarSeconds;
  state.counters["threads"] = prt::maxThreads();
}

void BM_HaarProductOrder(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((std::string(kBunny) + " not found: bunny case skipped").c_str());
    return;
  }
  const int terms = static_cast<int>(state.range(0));
  const int resolution = 32;
  const prt::Transfer t = prt::bake(s->mesh, *s->occluder, haarSettings(resolution, terms));
  const prt::haar::HaarLight light =
      prt::haar::projectLight(prt::envmap::builtinEnvironment("builtin:sky"), resolution, 200);
  const std::size_t cube = 6u * resolution * resolution, rows = t.rowCount();
  auto indexAt = [](const float* row, int k) { return static_cast<std::uint32_t>(row[1 + 2 * k]); };
  // By row: the light dense, zeros where no term is kept.
  std::vector<prt::Rgb> dense(cube, prt::Rgb(0.0f));
  for (std::size_t i = 0; i < light.index.size(); ++i) dense[light.index[i]] = light.value[i];
  // By light coefficient: the transfer's columns (compressed sparse columns over the cube).
  std::vector<std::uint32_t> start(cube + 1, 0), colRow;
  std::vector<float> colValue;
  for (std::size_t r = 0; r < rows; ++r)
    for (int k = 0; k < terms; ++k)
      if (t.row(r)[2 + 2 * k] != 0.0f) ++start[indexAt(t.row(r), k) + 1];
  for (std::size_t j = 0; j < cube; ++j) start[j + 1] += start[j];
  colRow.resize(start[cube]);
  colValue.resize(start[cube]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t r = 0; r < rows; ++r)
    for (int k = 0; k < terms; ++k)
      if (const float v = t.row(r)[2 + 2 * k]; v != 0.0f) {
        const std::uint32_t e = fill[indexAt(t.row(r), k)]++;
        colRow[e] = static_cast<std::uint32_t>(r);
        colValue[e] = v;
      }
  std::vector<prt::Rgb> byRow(rows), byLight(rows);
  double rowSeconds = 0, lightSeconds = 0;
  int n = 0;
  for (auto _ : state) {
    rowSeconds += prt::bench::secondsOf(
        [&] {
          for (std::size_t r = 0; r < rows; ++r) {
            const float* row = t.row(r);
            prt::Rgb acc(0.0f);
            for (int k = 0; k < terms; ++k) acc += dense[indexAt(row, k)] * row[2 + 2 * k];
            byRow[r] = acc;
          }
          benchmark::DoNotOptimize(byRow.data());
        },
        1);
    lightSeconds += prt::bench::secondsOf(
        [&] {
          std::fill(byLight.begin(), byLight.end(), prt::Rgb(0.0f));
          for (std::size_t i = 0; i < light.index.size(); ++i) {
            const prt::Rgb l = light.value[i];
            const std::uint32_t j = light.index[i];
            for (std::uint32_t e = start[j]; e < start[j + 1]; ++e)
              byLight[colRow[e]] += l * colValue[e];
          }
          benchmark::DoNotOptimize(byLight.data());
        },
        1);
    state.SetIterationTime(rowSeconds / (n + 1));
    ++n;
  }
  // Both orders sum the same products (in another order): they agree to rounding.
  double diff = 0, scale = 0;
  for (std::size_t r = 0; r < rows; ++r)
    for (int c = 0; c < 3; ++c) {
      diff = std::max(diff, double(std::abs(byRow[r][c] - byLight[r][c])));
      scale = std::max(scale, double(std::abs(byRow[r][c])));
    }
  if (!(diff <= 1e-4 * scale)) state.SkipWithError("the two orders disagree");
  state.counters["vertices"] = double(rows);
  state.counters["by_row_ms"] = 1e3 * rowSeconds / n;
  state.counters["by_light_ms"] = 1e3 * lightSeconds / n;
  state.counters["by_light_vs_by_row"] = lightSeconds / rowSeconds;
  // The share of the stored transfer terms the light's K terms meet: the by-light loop's work.
  std::size_t met = 0;
  for (const std::uint32_t j : light.index) met += start[j + 1] - start[j];
  state.counters["terms_met"] = double(met) / double(std::max<std::size_t>(1, start[cube]));
}

void BM_HaarTurnLight(benchmark::State& state, const std::string& source) {
  if (source.rfind("builtin:", 0) != 0 && !std::filesystem::exists(source)) {
    state.SkipWithError((source + " not found: case skipped").c_str());
    return;
  }
  const prt::envmap::Environment env = prt::envmap::loadEnvironment(source).env;
  const int n = 32;
  const std::size_t terms = 200;
  const prt::haar::EnvironmentCube cube = prt::haar::environmentCube(env, n);
  double turnedSeconds = 0, projectSeconds = 0;
  int turn = 0;
  for (auto _ : state) {
    const prt::Mat3d r = prt::rotationEulerXYZ(10.0 * turn, 37.0 * turn, 0.0);
    const double t = prt::bench::secondsOf(
        [&] { benchmark::DoNotOptimize(prt::haar::turnedLight(cube, n, terms, r).index.data()); },
        1);
    state.SetIterationTime(t);
    turnedSeconds += t;
    projectSeconds += prt::bench::secondsOf(
        [&] { benchmark::DoNotOptimize(prt::haar::projectLight(env, n, terms, r).index.data()); },
        1);
    ++turn;
  }
  state.counters["turned_ms"] = 1e3 * turnedSeconds / turn;
  state.counters["project_ms"] = 1e3 * projectSeconds / turn;
  state.counters["vs_project"] = projectSeconds / turnedSeconds;
  state.counters["threads"] = prt::maxThreads();
}

void BM_HaarBake(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((std::string(kBunny) + " not found: bunny case skipped").c_str());
    return;
  }
  const prt::BakeSettings settings = haarSettings(32, 64);
  const prt::haar::CubeTexels cube(32);
  prt::bench::RawScene raw(s->mesh);
  double bakeSeconds = 0, rawSeconds = 0;
  std::uint64_t bakeRays = 0, rawRays = 0;
  for (auto _ : state) {
    prt::BakeStats stats;
    auto t = prt::bake(s->mesh, *s->occluder, settings, &stats);
    benchmark::DoNotOptimize(t.values().data());
    bakeSeconds += stats.secondsDirect;
    bakeRays += stats.rays;
    state.SetIterationTime(stats.secondsTotal);
    // The bake's rays (bake_haar.cpp: per vertex its seeded jitter, one ray per texel above
    // the horizon), generated in blocks of vertices and traced untimed-generation.
    const std::size_t block = 512;
    std::vector<RTCRay> rays;
    for (std::size_t lo = 0; lo < s->mesh.vertexCount(); lo += block) {
      const std::size_t hi = std::min(lo + block, s->mesh.vertexCount());
      rays.clear();
      for (std::size_t v = lo; v < hi; ++v) {
        const prt::Vec3f p = s->mesh.positions[v], nrm = s->mesh.normals[v];
        const prt::Vec3f o = p + nrm * s->occluder->rayOffset(p);
        prt::Pcg32 rng(prt::deriveSeed(settings.seed, v));
        for (std::uint32_t j = 0; j < cube.count(); ++j) {
          if (!cube.aboveHorizon(j, prt::Vec3d(nrm))) continue;
          float w = 0;
          const float a = rng.uniform(), b = rng.uniform();
          const prt::Vec3f d = cube.sample(j, a, b, w);
          if (prt::dot(nrm, d) <= 0.0f) continue;
          RTCRay r{};
          r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
          r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
          r.tfar = std::numeric_limits<float>::infinity();
          r.mask = ~0u;
          rays.push_back(r);
        }
      }
      rawSeconds += prt::bench::traceStreams(raw.scene(), rays);
      rawRays += rays.size();
    }
  }
  state.counters["vertices"] = double(s->mesh.vertexCount());
  state.counters["bake_Mrays/s"] = bakeRays / bakeSeconds * 1e-6;
  state.counters["raw_Mrays/s"] = rawRays / rawSeconds * 1e-6;
  state.counters["vs_raw"] = (bakeRays / bakeSeconds) / (rawRays / rawSeconds);
  state.counters["threads"] = prt::maxThreads();
}

}  // namespace

BENCHMARK_CAPTURE(BM_HaarRelight, bunny, std::string("bunny"))
    ->Arg(64)
    ->Arg(16)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HaarRelight, sphere_plane, std::string("sphere-plane"))
    ->Arg(64)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HaarProductOrder, bunny, std::string("bunny"))
    ->Arg(64)
    ->Arg(16)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HaarTurnLight, sky, std::string("builtin:sky"))
    ->Iterations(12)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HaarTurnLight, courtyard,
                  std::string("/usr/share/blender/datafiles/studiolights/world/courtyard.exr"))
    ->Iterations(12)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HaarBake, bunny, std::string("bunny"))
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HaarBake, sphere_plane, std::string("sphere-plane"))
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
