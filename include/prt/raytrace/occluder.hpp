#pragma once
// Ray queries against a scene: the one virtual interface of the library, since implementations
// really differ (Embree here; a GPU tracer or a test double elsewhere). Built once per scene,
// const and safe to share between threads.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/ray.hpp"

namespace prt {

class Occluder {
 public:
  virtual ~Occluder() = default;
  /// True if anything lies on the ray within (tnear, tfar).
  virtual bool occluded(const Ray& ray) const = 0;
  /// Batched occlusion: out[k] = occluded(rays[k]) (1 or 0). Implementations may use packets or
  /// streams; results equal the single-ray query.
  virtual void occluded(std::span<const Ray> rays, std::span<std::uint8_t> out) const;
  /// Closest hit.
  virtual Hit intersect(const Ray& ray) const = 0;
  /// Batched closest hits: out[k] = intersect(rays[k]). Implementations may use packets or
  /// streams; results equal the single-ray query.
  virtual void intersect(std::span<const Ray> rays, std::span<Hit> out) const;
  /// Offset along the normal that moves a ray origin off the surface at `p` robustly: scaled to
  /// the magnitude of p and the scene extent (floating-point error of the hit), not a constant.
  virtual float rayOffset(const Vec3f& p) const = 0;
  /// Bytes held by the acceleration structure and its copy of the geometry (0 if unknown).
  virtual std::size_t memoryBytes() const { return 0; }
};

/// An Embree 3 BVH over the mesh's triangles (the mesh need not outlive it: positions and
/// indices are copied into Embree's buffers, 12 bytes per vertex and per triangle). Triangle ids
/// in Hit are indices into mesh.triangles. Throws prt::Error (naming mesh.source) for an empty
/// mesh, out-of-range indices, non-finite positions and Embree failures.
std::unique_ptr<Occluder> makeEmbreeOccluder(const Mesh& mesh);

}  // namespace prt
