// Occlusion throughput (rays/s): raw Embree (rtcOccluded1 loop, rtcOccluded1M streams,
// rtcOccluded8/16 packets) against prt's Occluder (single and batched), on one thread and on
// all threads, for the builtin scenes and the Stanford bunny when installed. Rays are the ones a
// PRT bake casts: from vertices (offset by rayOffset along the normal), cosine-distributed about
// the normal, in vertex order (so coherent in origin, incoherent in direction).
//
//   bench_raytrace --benchmark_counters_tabular=true
//
// Figures and the machine: docs/perf/raytrace.md.

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>

#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "prt/raytrace/occluder.hpp"

namespace {

using namespace prt;

constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";
constexpr std::size_t kRays = 1 << 18;

struct SceneData {
  std::string name;
  Mesh mesh;
  std::unique_ptr<Occluder> occ;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<Ray> rays;
};

std::vector<std::unique_ptr<SceneData>>& scenes() {
  static std::vector<std::unique_ptr<SceneData>> s;
  return s;
}

void prepare(const std::string& name, const std::string& input) {
  auto d = std::make_unique<SceneData>();
  d->name = name;
  d->mesh = loadMesh(input);
  d->occ = makeEmbreeOccluder(d->mesh);
  // The raw Embree scene, built the same way as the occluder's.
  d->device = rtcNewDevice(nullptr);
  d->scene = rtcNewScene(d->device);
  rtcSetSceneFlags(d->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(d->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry g = rtcNewGeometry(d->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, d->mesh.vertexCount()));
  std::memcpy(v, d->mesh.positions.data(), 12 * d->mesh.vertexCount());
  auto* ix = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, d->mesh.triangleCount()));
  std::memcpy(ix, d->mesh.triangles.data(), 12 * d->mesh.triangleCount());
  rtcCommitGeometry(g);
  rtcAttachGeometry(d->scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(d->scene);
  // Cosine-distributed directions (Malley's method) from the vertices in order.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  d->rays.resize(kRays);
  const std::size_t perVertex = std::max<std::size_t>(1, kRays / d->mesh.vertexCount());
  for (std::size_t k = 0; k < kRays; ++k) {
    const std::size_t vi = (k / perVertex) % d->mesh.vertexCount();
    const Vec3f p = d->mesh.positions[vi], n = d->mesh.normals[vi];
    Vec3f t, b;
    orthonormalBasis(n, t, b);
    const float r = std::sqrt(u(rng)), phi = 2 * kPif * u(rng);
    const float z = std::sqrt(std::max(0.0f, 1 - r * r));
    d->rays[k] = Ray{p + n * d->occ->rayOffset(p),
                     normalize(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * z)};
  }
  scenes().push_back(std::move(d));
}

RTCRay toRtc(const Ray& r) {
  RTCRay x{};
  x.org_x = r.origin.x, x.org_y = r.origin.y, x.org_z = r.origin.z;
  x.dir_x = r.dir.x, x.dir_y = r.dir.y, x.dir_z = r.dir.z;
  x.tnear = r.tnear, x.tfar = r.tfar, x.mask = ~0u;
  return x;
}

enum Mode { kRaw1, kRaw1M, kRaw8, kRaw16, kPrtSingle, kPrtBatched };

/// Traces rays [b, e) of `d` with `mode`; returns the number occluded.
std::size_t trace(const SceneData& d, Mode mode, std::size_t b, std::size_t e) {
  std::size_t hits = 0;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  switch (mode) {
    case kRaw1:
      for (std::size_t k = b; k < e; ++k) {
        RTCRay r = toRtc(d.rays[k]);
        rtcOccluded1(d.scene, &ctx, &r);
        hits += r.tfar < 0;
      }
      break;
    case kRaw1M: {
      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
      RTCRay buf[64];
      for (std::size_t k = b; k < e; k += 64) {
        const std::size_t m = std::min<std::size_t>(64, e - k);
        for (std::size_t j = 0; j < m; ++j) buf[j] = toRtc(d.rays[k + j]);
        rtcOccluded1M(d.scene, &ctx, buf, unsigned(m), sizeof(RTCRay));
        for (std::size_t j = 0; j < m; ++j) hits += buf[j].tfar < 0;
      }
      break;
    }
    case kRaw8:
    case kRaw16: {
      const std::size_t w = mode == kRaw8 ? 8 : 16;
      alignas(64) RTCRay16 p;
      alignas(64) int valid[16];
      for (std::size_t k = b; k < e; k += w) {
        const std::size_t m = std::min(w, e - k);
        for (std::size_t j = 0; j < w; ++j) {
          valid[j] = j < m ? -1 : 0;
          const Ray& r = d.rays[k + std::min(j, m - 1)];
          // RTCRay8 and RTCRay16 share the SOA layout pattern; fill the 16-wide one and, for
          // packets of 8, pass it through a RTCRay8 view built the same way.
          p.org_x[j] = r.origin.x, p.org_y[j] = r.origin.y, p.org_z[j] = r.origin.z;
          p.dir_x[j] = r.dir.x, p.dir_y[j] = r.dir.y, p.dir_z[j] = r.dir.z;
          p.tnear[j] = r.tnear, p.tfar[j] = r.tfar, p.time[j] = 0, p.mask[j] = ~0u, p.id[j] = 0,
          p.flags[j] = 0;
        }
        if (w == 16) {
          rtcOccluded16(valid, d.scene, &ctx, &p);
          for (std::size_t j = 0; j < m; ++j) hits += p.tfar[j] < 0;
        } else {
          alignas(32) RTCRay8 q;
          for (std::size_t j = 0; j < 8; ++j) {
            q.org_x[j] = p.org_x[j], q.org_y[j] = p.org_y[j], q.org_z[j] = p.org_z[j];
            q.dir_x[j] = p.dir_x[j], q.dir_y[j] = p.dir_y[j], q.dir_z[j] = p.dir_z[j];
            q.tnear[j] = p.tnear[j], q.tfar[j] = p.tfar[j], q.time[j] = 0, q.mask[j] = ~0u;
            q.id[j] = 0, q.flags[j] = 0;
          }
          rtcOccluded8(valid, d.scene, &ctx, &q);
          for (std::size_t j = 0; j < m; ++j) hits += q.tfar[j] < 0;
        }
      }
      break;
    }
    case kPrtSingle:
      for (std::size_t k = b; k < e; ++k) hits += d.occ->occluded(d.rays[k]);
      break;
    case kPrtBatched: {
      std::uint8_t out[256];
      for (std::size_t k = b; k < e; k += 256) {
        const std::size_t m = std::min<std::size_t>(256, e - k);
        d.occ->occluded(std::span<const Ray>(d.rays).subspan(k, m),
                        std::span<std::uint8_t>(out, m));
        for (std::size_t j = 0; j < m; ++j) hits += out[j];
      }
      break;
    }
  }
  return hits;
}

void BM_Occlusion(benchmark::State& state) {
  const SceneData& d = *scenes().at(state.range(0));
  const Mode mode = Mode(state.range(1));
  const bool threaded = state.range(2) != 0;
  std::size_t hits = 0;
  for (auto _ : state) {
    if (threaded) {
      hits = parallelReduce<std::size_t>(
          d.rays.size(), 4096, 0,
          [&](std::size_t b, std::size_t e, std::size_t& acc) { acc += trace(d, mode, b, e); },
          [](std::size_t& a, std::size_t x) { a += x; });
    } else {
      hits = trace(d, mode, 0, d.rays.size());
    }
    benchmark::DoNotOptimize(hits);
  }
  static const char* names[] = {
      "rtcOccluded1",  "rtcOccluded1M",           "rtcOccluded8",
      "rtcOccluded16", "Occluder::occluded(ray)", "Occluder::occluded(span)"};
  state.SetLabel(d.name + " " + names[mode] + (threaded ? " all-threads" : " 1-thread"));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(d.rays.size()));
  state.counters["occluded"] = double(hits) / double(d.rays.size());
  state.counters["tris"] = double(d.mesh.triangleCount());
}

}  // namespace

int main(int argc, char** argv) {
  prepare("sphere-plane", "builtin:sphere-plane");
  prepare("cornell", "builtin:cornell");
  if (std::filesystem::exists(kBunny))
    prepare("bunny", kBunny);
  else
    std::fprintf(stderr,
                 "bench_raytrace: %s not found (apt install glmark2-data); skipping the bunny\n",
                 kBunny);
  for (int s = 0; s < int(scenes().size()); ++s)
    for (int mode = 0; mode <= kPrtBatched; ++mode)
      for (int threaded = 0; threaded <= 1; ++threaded)
        benchmark::RegisterBenchmark("occlusion", BM_Occlusion)
            ->Args({s, mode, threaded})
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->MinTime(0.3);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  for (auto& d : scenes()) {
    rtcReleaseScene(d->scene);
    rtcReleaseDevice(d->device);
  }
  return 0;
}
