// Benchmarks of transport::bake against raw Embree on the same scene, with the same rays, in the
// same run (figures and commands in docs/perf/bake.md).
//
//   bench_bake                       Google Benchmark cases:
//     BM_Shadowed/SCENE/BANDS        shadowed bake, 1024 samples; each iteration also traces the
//                                    bake's exact rays through a bare Embree scene (same build
//                                    flags) with rtcOccluded1 and with rtcOccluded1M streams of
//                                    64, timing only the Embree calls. Counters: bake and raw
//                                    rays/s, vs_raw = bake rate / the faster raw rate.
//     BM_Interreflected/SCENE        1 and 2 bounces, 256 samples: each bounce's cost / direct.
//     BM_Matrix/SCENE/BANDS          glossy transfer matrices, shadowed, 256 samples, against the
//                                    vector bake and raw Embree (the vector bake's rays) in the
//                                    same run: ns per sample of each; matrix/vector, matrix/raw.
//     BM_MatrixBounce/SCENE/BANDS    inter-reflected matrices, 1 bounce, 256 samples: diffuse
//                                    bounce surfaces (lambert; the vector pre-pass) and glossy
//                                    ones (phong; the shadowed matrices first) against the
//                                    shadowed matrix bake, same run: ns per sample and ratios.
//     BM_TexelShadowed/SCENE/RES     per-texel shadowed bake (3 bands, 256 samples) of a RES²
//                                    lightmap against raw Embree on the same rays (its texels'
//                                    sample points and seeds), and the per-vertex bake of the
//                                    same scene against its raw rays, same run: vs_raw of the
//                                    pass, and of the whole bake (sampling and the validity
//                                    probe included).
//     BM_TexelMatrix/SCENE/RES       per-texel shadowed glossy matrices (3 bands, 256 samples) of a
//                                    RES² lightmap against the per-vertex matrix bake of the same
//                                    scene and the per-texel vector bake, same run: ns per sample
//                                    of each, texel/vertex and matrix/vector.
//   bench_bake --equal-error         RMS error of T₀ against a 65536-sample bake at 64…4096
//                                    samples, cosine-Sobol' vs uniform random.
//
// Scenes: bunny = /usr/share/glmark2/models/bunny.obj (skipped with a message if absent; for
// BM_TexelShadowed, unwrapped by prt unwrap's atlas at 512², padding 2),
// sphere-plane = builtin:sphere-plane, cornell = builtin:cornell (its packed lightmap UVs).

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"
#include "prt/unwrap/unwrap.hpp"
#include "raw_embree.hpp"
#include "scenes.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using prt::bench::RawScene;
using prt::bench::kBunny;

using prt::bench::Scene;
using prt::bench::scene;

RawScene* rawScene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<RawScene>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second.get();
  return cache.emplace(name, std::make_unique<RawScene>(scene(name)->mesh)).first->second.get();
}

/// Where a row is integrated: a vertex, or a texel's sample point (its id seeds its rays).
struct RowPoint {
  prt::Vec3f p, n;
  std::size_t id = 0;
};

std::vector<RowPoint> vertexPoints(const prt::Mesh& m) {
  std::vector<RowPoint> out(m.vertexCount());
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = {m.positions[v], m.normals[v], v};
  return out;
}

/// The shadowed pass's rays for points [lo, hi), exactly as bake() and bakeTexels() cast them
/// (pass 0, cosine-Sobol'): same seeds, points, frames and origins.
void bakeRays(const Scene& s, const std::vector<RowPoint>& points, const prt::OwenSobol2D& sobol,
              std::uint64_t seed, std::size_t lo, std::size_t hi, std::vector<RTCRay>& out) {
  const std::size_t n = sobol.size();
  out.resize((hi - lo) * n);
  tbb::parallel_for(lo, hi, [&](std::size_t v) {
    const prt::Vec3f p = points[v].p, nrm = points[v].n;
    const prt::Vec3f o = p + nrm * s.occluder->rayOffset(p);
    const std::uint64_t key = prt::deriveSeed(prt::deriveSeed(seed, 0), points[v].id);
    prt::Vec3f t, b;
    prt::orthonormalBasis(nrm, t, b);
    for (std::uint32_t i = 0; i < n; ++i) {
      const prt::Point2 u = sobol.point(i, std::uint32_t(key), std::uint32_t(key >> 32));
      const prt::Vec3f l = prt::cosineHemisphere(u.x, u.y);
      const prt::Vec3f d = t * l.x + b * l.y + nrm * l.z;
      RTCRay& r = out[(v - lo) * n + i];
      r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
      r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
      r.tnear = 0.0f;
      r.tfar = std::numeric_limits<float>::infinity();
      r.time = 0, r.mask = ~0u, r.id = 0, r.flags = 0;
    }
  });
}

struct RawTimes {
  double single = 0, stream = 0;  // seconds in rtcOccluded1 / rtcOccluded1M
  std::uint64_t rays = 0, blocked = 0;
};

/// Traces the bake's rays through the bare scene, in blocks of vertices (ray generation is not
/// timed), in parallel over chunks of 64 rays like the bake.
RawTimes traceRaw(const std::string& name, int samples, std::uint64_t seed,
                  const std::vector<RowPoint>* given = nullptr) {
  const Scene& s = *scene(name);
  const RTCScene rs = rawScene(name)->scene();
  const prt::OwenSobol2D sobol(static_cast<std::uint32_t>(samples));
  const std::vector<RowPoint> vertices = given ? std::vector<RowPoint>() : vertexPoints(s.mesh);
  const std::vector<RowPoint>& points = given ? *given : vertices;
  RawTimes out;
  std::vector<RTCRay> rays, copy;
  const std::size_t block = std::max<std::size_t>(1, (1u << 20) / samples);
  for (std::size_t lo = 0; lo < points.size(); lo += block) {
    const std::size_t hi = std::min(lo + block, points.size());
    bakeRays(s, points, sobol, seed, lo, hi, rays);
    copy = rays;
    const std::size_t chunks = (rays.size() + 63) / 64;
    auto t0 = Clock::now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 16), [&](const auto& r) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      for (std::size_t c = r.begin(); c < r.end(); ++c)
        for (std::size_t k = c * 64; k < std::min(rays.size(), c * 64 + 64); ++k)
          rtcOccluded1(rs, &ctx, &rays[k]);
    });
    auto t1 = Clock::now();
    out.single += std::chrono::duration<double>(t1 - t0).count();
    out.stream += prt::bench::traceStreams(rs, copy);
    out.rays += rays.size();
    for (const RTCRay& r : rays) out.blocked += r.tfar < 0.0f;
  }
  return out;
}

void BM_Shadowed(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((std::string(kBunny) + " not found: bunny case skipped").c_str());
    return;
  }
  prt::BakeSettings settings;
  settings.mode = prt::TransferMode::Shadowed;
  settings.bands = static_cast<int>(state.range(0));
  settings.samples = 1024;
  settings.seed = 7;
  double bakeSeconds = 0, rawSingle = 0, rawStream = 0;
  std::uint64_t bakeRaysCount = 0, rawRays = 0;
  prt::BakeStats stats;
  for (auto _ : state) {
    const RawTimes raw = traceRaw(name, settings.samples, settings.seed);
    auto t = prt::bake(s->mesh, *s->occluder, settings, &stats);
    benchmark::DoNotOptimize(t.values().data());
    bakeSeconds += stats.secondsDirect;
    bakeRaysCount += stats.rays;
    rawSingle += raw.single;
    rawStream += raw.stream;
    rawRays += raw.rays;
    state.SetIterationTime(stats.secondsTotal);
  }
  const double bakeRate = bakeRaysCount / bakeSeconds;
  const double raw1 = rawRays / rawSingle, rawM = rawRays / rawStream;
  state.counters["vertices"] = double(s->mesh.vertexCount());
  state.counters["rays"] = double(stats.rays);
  state.counters["bake_Mrays/s"] = bakeRate * 1e-6;
  state.counters["raw1_Mrays/s"] = raw1 * 1e-6;
  state.counters["rawM_Mrays/s"] = rawM * 1e-6;
  state.counters["vs_raw"] = bakeRate / std::max(raw1, rawM);
  state.counters["threads"] = stats.threads;
}

void BM_TexelShadowed(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((std::string(kBunny) + " not found: bunny case skipped").c_str());
    return;
  }
  const int res = static_cast<int>(state.range(0));
  prt::BakeSettings settings;
  settings.mode = prt::TransferMode::Shadowed;
  settings.bands = 3;
  settings.samples = 256;
  settings.seed = 7;
  // The texels' sample points, as bakeTexels makes them.
  const prt::TexelSamples ts = prt::sampleTexels(s->mesh, s->mesh.lightmapUvs, res, res);
  std::vector<RowPoint> points;
  for (const prt::TexelSample& t : ts.samples)
    points.push_back({prt::samplePosition(s->mesh, t), prt::sampleNormal(s->mesh, t), t.texel});
  double pass = 0, total = 0, vertexPass = 0, raw = 0, rawVertex = 0;
  std::uint64_t rays = 0, rawRays = 0, vertexRays = 0, rawVertexRays = 0;
  for (auto _ : state) {
    const RawTimes r = traceRaw(name, settings.samples, settings.seed, &points);
    prt::BakeStats st;
    const prt::TexelBake b =
        prt::bakeTexels(s->mesh, *s->occluder, settings, s->mesh.lightmapUvs, res, res, 2, &st);
    benchmark::DoNotOptimize(b.transfer.values().data());
    const RawTimes rv = traceRaw(name, settings.samples, settings.seed);
    prt::BakeStats sv;
    const prt::Transfer v = prt::bake(s->mesh, *s->occluder, settings, &sv);
    benchmark::DoNotOptimize(v.values().data());
    pass += st.secondsDirect;
    total += st.secondsTotal;
    rays += st.rays;
    raw += std::min(r.single, r.stream);
    rawRays += r.rays;
    vertexPass += sv.secondsDirect;
    vertexRays += sv.rays;
    rawVertex += std::min(rv.single, rv.stream);
    rawVertexRays += rv.rays;
    state.SetIterationTime(st.secondsTotal);
  }
  const double rawRate = rawRays / raw;
  state.counters["texels"] = double(points.size());
  state.counters["texel_Mrays/s"] = rays / pass * 1e-6;
  state.counters["raw_Mrays/s"] = rawRate * 1e-6;
  state.counters["vs_raw"] = rays / pass / rawRate;
  state.counters["vs_raw_total"] = rays / total / rawRate;
  state.counters["vertex_vs_raw"] = (vertexRays / vertexPass) / (rawVertexRays / rawVertex);
}

void BM_TexelMatrix(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  const int res = static_cast<int>(state.range(0));
  prt::BakeSettings settings;
  settings.mode = prt::TransferMode::Shadowed;
  settings.layout = prt::TransferLayout::Matrix;
  settings.bands = 3;
  settings.samples = 256;
  settings.seed = 7;
  prt::BakeSettings vector = settings;
  vector.layout = prt::TransferLayout::Vector;
  double texel = 0, vertex = 0, texelVector = 0;
  double texelSamples = 0, vertexSamples = 0;
  for (auto _ : state) {
    prt::BakeStats st, sv, sx;
    const prt::TexelBake b =
        prt::bakeTexels(s->mesh, *s->occluder, settings, s->mesh.lightmapUvs, res, res, 2, &st);
    benchmark::DoNotOptimize(b.transfer.values().data());
    const prt::Transfer v = prt::bake(s->mesh, *s->occluder, settings, &sv);
    benchmark::DoNotOptimize(v.values().data());
    const prt::TexelBake x =
        prt::bakeTexels(s->mesh, *s->occluder, vector, s->mesh.lightmapUvs, res, res, 2, &sx);
    benchmark::DoNotOptimize(x.transfer.values().data());
    texel += st.secondsDirect;
    vertex += sv.secondsDirect;
    texelVector += sx.secondsDirect;
    texelSamples += double(st.vertices) * settings.samples;
    vertexSamples += double(sv.vertices) * settings.samples;
    state.SetIterationTime(st.secondsTotal);
  }
  const double nsTexel = texel / texelSamples * 1e9, nsVertex = vertex / vertexSamples * 1e9,
               nsVector = texelVector / texelSamples * 1e9;
  state.counters["texels"] = texelSamples / settings.samples / double(state.iterations());
  state.counters["ns/sample"] = nsTexel;
  state.counters["vertex_ns/sample"] = nsVertex;
  state.counters["texel_vs_vertex"] = nsTexel / nsVertex;
  state.counters["matrix_vs_vector"] = nsTexel / nsVector;
}

void BM_Interreflected(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((std::string(kBunny) + " not found: bunny case skipped").c_str());
    return;
  }
  prt::BakeSettings settings;
  settings.mode = prt::TransferMode::Interreflected;
  settings.bands = 3;
  settings.samples = 256;
  settings.bounces = static_cast<int>(state.range(0));
  settings.seed = 7;
  prt::BakeStats stats;
  for (auto _ : state) {
    auto t = prt::bake(s->mesh, *s->occluder, settings, &stats);
    benchmark::DoNotOptimize(t.values().data());
    state.SetIterationTime(stats.secondsTotal);
  }
  state.counters["direct_s"] = stats.secondsDirect;
  for (std::size_t k = 0; k < stats.secondsBounce.size(); ++k)
    state.counters["bounce" + std::to_string(k + 1) + "/direct"] =
        stats.secondsBounce[k] / stats.secondsDirect;
  state.counters["Mrays/s"] = stats.raysPerSecond * 1e-6;
}

void BM_Matrix(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((std::string(kBunny) + " not found: bunny case skipped").c_str());
    return;
  }
  prt::BakeSettings settings;
  settings.mode = prt::TransferMode::Shadowed;
  settings.bands = static_cast<int>(state.range(0));
  settings.samples = 256;
  settings.seed = 7;
  double matrixSeconds = 0, vectorSeconds = 0, rawSeconds = 0, samples = 0;
  for (auto _ : state) {
    const RawTimes raw = traceRaw(name, settings.samples, settings.seed);
    prt::BakeStats vs, ms;
    settings.layout = prt::TransferLayout::Vector;
    auto v = prt::bake(s->mesh, *s->occluder, settings, &vs);
    settings.layout = prt::TransferLayout::Matrix;
    auto m = prt::bake(s->mesh, *s->occluder, settings, &ms);
    benchmark::DoNotOptimize(v.values().data());
    benchmark::DoNotOptimize(m.values().data());
    matrixSeconds += ms.secondsTotal;
    vectorSeconds += vs.secondsTotal;
    rawSeconds += std::min(raw.single, raw.stream);
    samples += double(s->mesh.vertexCount()) * settings.samples;
    state.SetIterationTime(ms.secondsTotal);
  }
  // Per sample on all threads (wall time × threads / samples).
  const double threads = prt::maxThreads();
  state.counters["vertices"] = double(s->mesh.vertexCount());
  state.counters["matrix_ns"] = matrixSeconds * threads / samples * 1e9;
  state.counters["vector_ns"] = vectorSeconds * threads / samples * 1e9;
  state.counters["raw_ns"] = rawSeconds * threads / samples * 1e9;
  state.counters["matrix/vector"] = matrixSeconds / vectorSeconds;
  state.counters["matrix/raw"] = matrixSeconds / rawSeconds;
}

void BM_MatrixBounce(benchmark::State& state, const std::string& name) {
  Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((std::string(kBunny) + " not found: bunny case skipped").c_str());
    return;
  }
  prt::BakeSettings settings;
  settings.layout = prt::TransferLayout::Matrix;
  settings.bands = static_cast<int>(state.range(0));
  settings.samples = 256;
  settings.seed = 7;
  settings.bounces = 1;
  double direct = 0, diffuse = 0, glossy = 0, samples = 0;
  for (auto _ : state) {
    prt::BakeStats sd, sl, sg;
    settings.mode = prt::TransferMode::Shadowed;
    settings.material = prt::parseMaterial("lambert?kd=0.5");
    benchmark::DoNotOptimize(prt::bake(s->mesh, *s->occluder, settings, &sd).values().data());
    settings.mode = prt::TransferMode::Interreflected;
    benchmark::DoNotOptimize(prt::bake(s->mesh, *s->occluder, settings, &sl).values().data());
    settings.material = prt::parseMaterial("phong?exponent=8&ks=0.5&kd=0.5");
    benchmark::DoNotOptimize(prt::bake(s->mesh, *s->occluder, settings, &sg).values().data());
    direct += sd.secondsTotal;
    diffuse += sl.secondsTotal;
    glossy += sg.secondsTotal;
    samples += double(s->mesh.vertexCount()) * settings.samples;
    state.SetIterationTime(sg.secondsTotal);
  }
  const double threads = prt::maxThreads();
  state.counters["vertices"] = double(s->mesh.vertexCount());
  state.counters["shadowed_ns"] = direct * threads / samples * 1e9;
  state.counters["diffuse_bounce_ns"] = diffuse * threads / samples * 1e9;
  state.counters["glossy_bounce_ns"] = glossy * threads / samples * 1e9;
  state.counters["diffuse/shadowed"] = diffuse / direct;
  state.counters["glossy/shadowed"] = glossy / direct;
}

BENCHMARK_CAPTURE(BM_MatrixBounce, bunny, std::string("bunny"))
    ->Arg(5)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

BENCHMARK_CAPTURE(BM_Matrix, bunny, std::string("bunny"))
    ->Arg(5)
    ->Arg(9)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Matrix, sphere_plane, std::string("sphere-plane"))
    ->Arg(5)
    ->Arg(9)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Shadowed, bunny, std::string("bunny"))
    ->Arg(3)
    ->Arg(9)
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Shadowed, sphere_plane, std::string("sphere-plane"))
    ->Arg(3)
    ->Arg(9)
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_TexelShadowed, cornell, std::string("cornell"))
    ->Arg(256)
    ->Arg(512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_TexelShadowed, bunny, std::string("bunny-atlas"))
    ->Arg(512)
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TexelMatrix, cornell, std::string("cornell"))
    ->Arg(128)
    ->Arg(256)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_Interreflected, bunny, std::string("bunny"))
    ->Arg(2)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Interreflected, sphere_plane, std::string("sphere-plane"))
    ->Arg(2)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

// ---- Equal-error study -------------------------------------------------------------------

double rmsT0(const prt::Transfer& a, const prt::Transfer& ref) {
  // In radiance units under L = 1: √(4π) T₀.
  const double k = std::sqrt(4.0 * prt::kPi);
  double s = 0;
  for (std::size_t v = 0; v < a.rowCount(); ++v) {
    const double d = (a.row(v)[0] - ref.row(v)[0]) * k;
    s += d * d;
  }
  return std::sqrt(s / double(a.rowCount()));
}

int equalError() {
  struct Case {
    std::string label, mesh;
    std::size_t vertices;  // 0: all
  };
  std::vector<Case> cases = {{"sphere-plane", "builtin:sphere-plane?grid=32&subdiv=3", 0}};
  if (std::filesystem::exists(kBunny))
    cases.push_back({"bunny (first 1024 vertices)", kBunny, 1024});
  else
    std::printf("%s not found: bunny case skipped\n", kBunny);
  for (const Case& c : cases) {
    const prt::Mesh mesh =
        c.mesh.rfind("builtin:", 0) == 0 ? prt::builtinScene(c.mesh) : prt::loadMesh(c.mesh);
    const auto occ = prt::makeEmbreeOccluder(mesh);
    prt::BakeSettings s;
    s.mode = prt::TransferMode::Shadowed;
    s.bands = 1;
    s.rows.count = c.vertices;
    s.samples = 65536;
    s.seed = 1;  // the reference uses its own seed: its error is independent of the others
    const auto ref = prt::bake(mesh, *occ, s);
    std::printf(
        "\n%s: %zu vertices, RMS error of sqrt(4pi) T0 vs a 65536-sample cosine-Sobol bake\n",
        c.label.c_str(), ref.rowCount());
    std::printf("%8s %14s %14s %10s %22s\n", "samples", "cosine-Sobol", "uniform-random", "ratio",
                "uniform N for Sobol err");
    std::vector<std::pair<int, double>> uniformErr;
    std::vector<std::pair<int, double>> sobolErr;
    for (int n = 64; n <= 4096; n *= 2) {
      s.samples = n;
      s.seed = 2;
      s.sampling = prt::Sampling::CosineSobol;
      const double es = rmsT0(prt::bake(mesh, *occ, s), ref);
      s.sampling = prt::Sampling::UniformRandom;
      const double eu = rmsT0(prt::bake(mesh, *occ, s), ref);
      sobolErr.push_back({n, es});
      uniformErr.push_back({n, eu});
      // Uniform random error falls as N^-1/2: it matches es at N_u = n (eu/es)².
      std::printf("%8d %14.6f %14.6f %10.2f %22.0f\n", n, es, eu, eu / es,
                  n * (eu / es) * (eu / es));
    }
    // Fitted slopes log(err) vs log(N).
    auto slope = [](const std::vector<std::pair<int, double>>& e) {
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      for (auto [n, err] : e) {
        const double x = std::log(double(n)), y = std::log(err);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
      }
      const double m = double(e.size());
      return (m * sxy - sx * sy) / (m * sxx - sx * sx);
    };
    std::printf("fitted convergence: cosine-Sobol N^%.2f, uniform-random N^%.2f\n", slope(sobolErr),
                slope(uniformErr));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--equal-error") == 0) return equalError();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
