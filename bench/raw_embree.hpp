#pragma once
// A bare Embree scene with the occluder's build flags, the baseline the bake benchmarks trace
// their rays through in the same run (bench_bake, bench_haar).

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <vector>

#include "prt/geometry/mesh.hpp"

namespace prt::bench {

/// A bare Embree scene with the occluder's build flags (robust, high quality).
class RawScene {
 public:
  explicit RawScene(const Mesh& mesh) {
    device_ = rtcNewDevice("threads=0,verbose=0");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, mesh.positions.size()));
    std::memcpy(v, mesh.positions.data(), mesh.positions.size() * 12);
    auto* idx = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, mesh.triangles.size()));
    std::memcpy(idx, mesh.triangles.data(), mesh.triangles.size() * 12);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene_);
  }
  ~RawScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  RTCScene scene() const { return scene_; }

 private:
  RTCDevice device_;
  RTCScene scene_;
};

/// Traces `rays` through `scene` as incoherent rtcOccluded1M streams of 64, in parallel over
/// chunks as the bakes cast theirs (each ray's tfar set to −∞ where blocked); returns the seconds
/// the Embree calls took.
inline double traceStreams(RTCScene scene, std::vector<RTCRay>& rays) {
  const std::size_t chunks = (rays.size() + 63) / 64;
  const auto t0 = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 16), [&](const auto& r) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      const std::size_t m = std::min<std::size_t>(64, rays.size() - c * 64);
      rtcOccluded1M(scene, &ctx, &rays[c * 64], static_cast<unsigned>(m), sizeof(RTCRay));
    }
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace prt::bench
