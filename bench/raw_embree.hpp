#pragma once
// A bare Embree scene with the occluder's build flags, the baseline the bake benchmarks trace
// their rays through in the same run (bench_bake, bench_haar).

#include <embree3/rtcore.h>

#include <cstdint>
#include <cstring>

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

}  // namespace prt::bench
