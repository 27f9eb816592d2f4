// The Embree 3 occluder: one device and one scene per mesh, built once with the high-quality
// (SAH, spatial splits) builder and shared read-only by all threads.
//
// References: Wald et al., "Embree: A Kernel Framework for Efficient CPU Ray Tracing", SIGGRAPH
// 2014; Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2013 (used by Embree in
// robust mode, so rays cannot slip through the shared edges of a closed mesh); Wächter & Binder,
// "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6, 2019, and
// Pharr, Jakob, Humphreys, "Physically Based Rendering" 3rd ed. §3.9 (error bounds) for the
// ray-origin offset.
//
// Memory: Embree keeps its own copy of the vertices (12 bytes each, plus 4 bytes of padding at
// the end) and triangle indices (12 bytes each), so the Mesh may be destroyed after
// construction; on top of that the BVH. memoryBytes() reports what Embree holds after the build
// (measured through its memory monitor; see docs/perf/raytrace.md for bytes per triangle).

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "prt/core/error.hpp"
#include "prt/geometry/load.hpp"
#include "prt/raytrace/occluder.hpp"

namespace prt {

namespace {

const char* embreeErrorName(RTCError e) {
  switch (e) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "error";
}

/// The offset scale: 2^-16 of the magnitude (about 128 float ulps, i.e. 256 units of the unit
/// roundoff 2^-24), the constant of Wächter & Binder, applied to max(|p|_inf, scene radius).
/// Why the larger of the two: the error of a hit point computed by barycentric interpolation is
/// bounded by gamma_n * sum |b_i p_i| <= gamma_n * max|p_i| (pbrt §3.9.4), where the p_i are the
/// triangle's vertices — near the origin |p| is small but the vertices need not be, and the
/// ray/triangle test works in coordinates relative to the origin, whose rounding grows with the
/// coordinates of the triangles around p; the scene radius bounds those. The factor 2^-16 leaves
/// a margin of ~30x over the few-ulp bounds (n ~ 7 operations plus Embree's own intersection
/// rounding), so rays from barycentrically interpolated points on a tessellated surface never
/// re-hit their own surface (tests/raytrace checks this with 10^5 rays, and that a zero offset does
/// self-intersect).
constexpr float kOffsetScale = 1.0f / 65536.0f;

class EmbreeOccluder final : public Occluder {
 public:
  explicit EmbreeOccluder(const Mesh& mesh) : source_(mesh.source) {
    const std::string label = mesh.source.empty() ? std::string("mesh") : mesh.source;
    if (mesh.triangles.empty())
      throw Error(label, "cannot build a ray-tracing scene: no triangles");
    if (mesh.positions.size() > std::numeric_limits<std::uint32_t>::max() ||
        mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max())
      throw Error(label, "too many vertices or triangles for 32-bit indices");
    checkMeshExtent(mesh, label);
    const std::size_t nv = mesh.positions.size();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (std::uint32_t i : mesh.triangles[t])
        if (i >= nv)
          throw Error(label, "triangle " + std::to_string(t) + " references vertex " +
                                 std::to_string(i) + " (mesh has " + std::to_string(nv) + ")");

    device_ = rtcNewDevice("threads=0,verbose=0");
    if (!device_)
      throw Error(label, std::string("Embree: cannot create device: ") +
                             embreeErrorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(device_, &EmbreeOccluder::onError, this);
    rtcSetDeviceMemoryMonitorFunction(device_, &EmbreeOccluder::onMemory, this);
    try {
      build(mesh, label);
    } catch (...) {
      release();
      throw;
    }
    // Scene radius for rayOffset: the largest |coordinate| of the bounding box, so the offset
    // also covers points near the origin of a scene whose triangles lie far from it.
    const Bounds b = computeBounds(mesh);
    float r = 0;
    for (int k = 0; k < 3; ++k) r = std::max({r, std::fabs(b.lo[k]), std::fabs(b.hi[k])});
    sceneScale_ = std::max(r, std::numeric_limits<float>::min());
  }

  ~EmbreeOccluder() override { release(); }

  bool occluded(const Ray& ray) const override {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r = toRtc(ray);
    rtcOccluded1(scene_, &ctx, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf when occluded
  }

  void occluded(std::span<const Ray> rays, std::span<std::uint8_t> out) const override;
  void intersect(std::span<const Ray> rays, std::span<Hit> out) const override;
  using Occluder::intersect;

  Hit intersect(const Ray& ray) const override {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray = toRtc(ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    Hit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.hit = true;
    h.triangle = rh.hit.primID;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    h.t = rh.ray.tfar;
    return h;
  }

  float rayOffset(const Vec3f& p) const override {
    const float m = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z), sceneScale_});
    return kOffsetScale * m;
  }

  std::size_t memoryBytes() const override {
    const std::int64_t b = bytes_.load();
    return b > 0 ? std::size_t(b) : 0;
  }
  /// The peak during the build (temporary build memory included).
  std::size_t peakBytes() const { return peakBytes_.load(); }

 private:
  static RTCRay toRtc(const Ray& ray) {
    RTCRay r;
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.dir_x = ray.dir.x;
    r.dir_y = ray.dir.y;
    r.dir_z = ray.dir.z;
    r.tnear = ray.tnear;
    r.tfar = ray.tfar;
    r.time = 0.0f;
    r.mask = std::numeric_limits<unsigned>::max();
    r.id = 0;
    r.flags = 0;
    return r;
  }

  void build(const Mesh& mesh, const std::string& label) {
    scene_ = rtcNewScene(device_);
    check(label, "creating the scene");
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    check(label, "creating the triangle geometry");
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
    // rtcSetNewGeometryBuffer pads the buffer so Embree's 16-byte vector loads of the last vertex
    // stay in bounds.
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          mesh.positions.size()));
    auto* idx = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(std::uint32_t), mesh.triangles.size()));
    if (!v || !idx) {
      rtcReleaseGeometry(geom);
      check(label, "allocating geometry buffers");
      throw Error(label, "Embree: cannot allocate geometry buffers");
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3f& p = mesh.positions[i];
      if (!isFinite(p)) {
        rtcReleaseGeometry(geom);
        throw Error(label, "vertex " + std::to_string(i) + " has a non-finite coordinate");
      }
      v[3 * i] = p.x;
      v[3 * i + 1] = p.y;
      v[3 * i + 2] = p.z;
    }
    std::memcpy(idx, mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    check(label, "committing the geometry");
    rtcCommitScene(scene_);
    check(label, "building the BVH");
  }

  void check(const std::string& label, const char* what) {
    const RTCError e = rtcGetDeviceError(device_);
    if (e != RTC_ERROR_NONE || !lastError_.empty())
      throw Error(label, std::string("Embree error while ") + what + ": " +
                             (lastError_.empty() ? embreeErrorName(e) : lastError_));
  }

  void release() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
    scene_ = nullptr;
    device_ = nullptr;
  }

  static void onError(void* self, RTCError code, const char* str) {
    auto* o = static_cast<EmbreeOccluder*>(self);
    o->lastError_ =
        std::string(embreeErrorName(code)) + (str && *str ? std::string(" (") + str + ")" : "");
  }

  static bool onMemory(void* self, ssize_t bytes, bool /*post*/) {
    auto* o = static_cast<EmbreeOccluder*>(self);
    const std::int64_t now = o->bytes_.fetch_add(bytes) + bytes;
    std::size_t peak = o->peakBytes_.load();
    while (now > 0 && std::size_t(now) > peak && !o->peakBytes_.compare_exchange_weak(peak, now)) {
    }
    return true;
  }

  std::string source_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  float sceneScale_ = 1.0f;
  std::string lastError_;
  std::atomic<std::int64_t> bytes_{0};
  std::atomic<std::size_t> peakBytes_{0};
};

void EmbreeOccluder::occluded(std::span<const Ray> rays, std::span<std::uint8_t> out) const {
  PRT_CHECK(out.size() >= rays.size(), "occluded: output span shorter than the rays");
  // Streams of up to 64 rays through rtcOccluded1M (Embree regroups them into packets
  // internally when that pays); see docs/perf/raytrace.md for the comparison with single rays
  // and with rtcOccluded8 packets.
  constexpr std::size_t kChunk = 64;
  RTCRay buf[kChunk];
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  for (std::size_t base = 0; base < rays.size(); base += kChunk) {
    const std::size_t m = std::min(kChunk, rays.size() - base);
    for (std::size_t k = 0; k < m; ++k) buf[k] = toRtc(rays[base + k]);
    rtcOccluded1M(scene_, &ctx, buf, static_cast<unsigned>(m), sizeof(RTCRay));
    for (std::size_t k = 0; k < m; ++k) out[base + k] = buf[k].tfar < 0.0f ? 1 : 0;
  }
}

void EmbreeOccluder::intersect(std::span<const Ray> rays, std::span<Hit> out) const {
  PRT_CHECK(out.size() >= rays.size(), "intersect: output span shorter than the rays");
  // Streams of up to 64 rays through rtcIntersect1M, as occluded's.
  constexpr std::size_t kChunk = 64;
  RTCRayHit buf[kChunk];
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  for (std::size_t base = 0; base < rays.size(); base += kChunk) {
    const std::size_t m = std::min(kChunk, rays.size() - base);
    for (std::size_t k = 0; k < m; ++k) {
      buf[k].ray = toRtc(rays[base + k]);
      buf[k].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      buf[k].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(scene_, &ctx, buf, static_cast<unsigned>(m), sizeof(RTCRayHit));
    for (std::size_t k = 0; k < m; ++k) {
      Hit h;
      if (buf[k].hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        h.hit = true;
        h.triangle = buf[k].hit.primID;
        h.u = buf[k].hit.u;
        h.v = buf[k].hit.v;
        h.t = buf[k].ray.tfar;
      }
      out[base + k] = h;
    }
  }
}

}  // namespace

std::unique_ptr<Occluder> makeEmbreeOccluder(const Mesh& mesh) {
  return std::make_unique<EmbreeOccluder>(mesh);
}

}  // namespace prt
