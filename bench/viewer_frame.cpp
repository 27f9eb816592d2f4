// The viewer's CPU work per frame (prt view): the light rotation R = Ry(spin) · R_user, the SH
// rotation of the light's first b bands (sh::Rotation::set + apply, RGB) and its packing into the
// std140 uniform block (LightPacker::pack), for b = 3, 6, 9, 16. Budget: under 0.1 ms at 9 bands.
// Baseline in the same run: the CPU relighting's light preparation for the same rotation
// (relight::prepareLight: builds a Rotation, allocates both layouts), which the viewer does not
// use per frame. The GL upload itself (glBufferSubData of the block) is timed by
// `prt view --headless --stats`; see docs/viewer.md.
// CPCA-compressed transfer adds, per frame, the light's projection onto every cluster's mean and
// basis (relight::projectClusters, K(N+1)·b²·3 multiply-adds) and its packing into the
// cluster table the shader reads (relight::packClusterTable): BM_ViewerClusterTable, K = 64 and
// 256, N = 8, vectors at 9 bands (the table the viewer uploads: 16·K(N+1) bytes).
// Run: build-viewer/bench/bench_viewer_frame --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include "prt/relight/cluster_projection.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/shader_transfer.hpp"

namespace {

prt::sh::RgbSh light(int bands) {
  prt::sh::RgbSh l(bands);
  for (int i = 0; i < bands * bands; ++i) l.c[i] = prt::Rgb(1.0f / (1 + i), 0.5f, 0.25f);
  return l;
}

void BM_ViewerLightFrame(benchmark::State& state) {
  const int bands = int(state.range(0));
  prt::relight::LightPacker packer;
  packer.setLight(light(bands));
  const prt::Mat3d user = prt::rotationEulerXYZ(20, 30, 40);
  double spin = 0;
  for (auto _ : state) {
    spin += 0.01;  // a new angle every frame, as auto-rotation gives
    const prt::Mat3d r = prt::rotationAxisAngle({0, 1, 0}, spin) * user;
    packer.pack(r, bands);
    benchmark::DoNotOptimize(packer.data());
    benchmark::ClobberMemory();
  }
  state.counters["bytes"] = double(packer.bytes());
}
BENCHMARK(BM_ViewerLightFrame)->Arg(3)->Arg(6)->Arg(9)->Arg(16)->Unit(benchmark::kMicrosecond);

void BM_PrepareLightBaseline(benchmark::State& state) {
  const int bands = int(state.range(0));
  const prt::sh::RgbSh l = light(bands);
  const prt::Mat3d user = prt::rotationEulerXYZ(20, 30, 40);
  double spin = 0;
  for (auto _ : state) {
    spin += 0.01;
    const prt::sh::Rotation rot(bands, prt::rotationAxisAngle({0, 1, 0}, spin) * user);
    prt::relight::PreparedLight p = prt::relight::prepareLight(l, bands, &rot);
    benchmark::DoNotOptimize(p.interleaved.data());
  }
}
BENCHMARK(BM_PrepareLightBaseline)->Arg(3)->Arg(9)->Unit(benchmark::kMicrosecond);

void BM_ViewerClusterTable(benchmark::State& state) {
  const int bands = 9, K = int(state.range(0)), N = 8;
  prt::TransferShape shape;
  shape.bands = bands;
  shape.rows.count = std::size_t(K);
  prt::CpcaRows c;
  c.clusters = K;
  c.basisCount = N;
  for (int v = 0; v < K; ++v) c.cluster.push_back(std::uint32_t(v));
  c.weights = prt::FloatArray(std::vector<float>(std::size_t(K) * N, 0.1f));
  std::vector<float> means(std::size_t(K) * shape.stride()), basis(means.size() * N);
  for (std::size_t i = 0; i < means.size(); ++i) means[i] = 1.0f / float(1 + i % 81);
  for (std::size_t i = 0; i < basis.size(); ++i) basis[i] = float(i % 7) * 0.01f;
  c.means = prt::FloatArray(std::move(means));
  c.basis = prt::FloatArray(std::move(basis));
  const prt::Transfer t = prt::Transfer::cpca(shape, std::move(c));
  prt::relight::LightPacker packer;
  packer.setLight(light(bands));
  const prt::Mat3d user = prt::rotationEulerXYZ(20, 30, 40);
  std::vector<float> table;
  double spin = 0;
  for (auto _ : state) {
    spin += 0.01;
    // What SceneView::prepare does for a compressed transfer on the GPU.
    packer.pack(prt::rotationAxisAngle({0, 1, 0}, spin) * user, bands);
    const prt::relight::PreparedLight l = prt::relight::prepareLight(packer.rotated(), bands);
    prt::relight::packClusterTable(prt::relight::projectClusters(t, l), table);
    benchmark::DoNotOptimize(table.data());
    benchmark::ClobberMemory();
  }
  state.counters["table_bytes"] = double(sizeof(float) * table.size());
}
BENCHMARK(BM_ViewerClusterTable)->Arg(64)->Arg(256)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
