#pragma once
// The cube's texels (cube_haar.hpp) as pieces of the sphere a transfer is integrated over.
//
// A texel's edges are arcs of great circles (the gnomonic projection maps the face's straight
// lines to them), so a texel is a convex spherical quadrilateral, and so is its part above any
// horizon n·ω = 0 (clipped by a great circle). Lambert's formula gives the cosine integral over
// such a polygon with vertices v_1 … v_m exactly (Arvo, "Applications of Irradiance Tensors to
// the Simulation of Non-Lambertian Phenomena", SIGGRAPH 1995, eq. 11):
//     ∫_P ω dω = ½ Σ_i Θ_i u_i,   Θ_i = ∠(v_i, v_{i+1}),  u_i = (v_i × v_{i+1}) / |v_i × v_{i+1}|
// (sign by the polygon's orientation). A texel wholly above the horizon therefore has
// ∫ max(n·ω, 0) dω = n · Φ_j with Φ_j = ∫_j ω dω stored once; one the horizon crosses is clipped
// and integrated on the spot.
//
// Sampling a texel: a point uniform on its square of the face plane (side 2/N at unit distance),
// d = cubeFaceDirection(face, s, t), has solid-angle density |d|³ / (2/N)² (dω = dA / |d|³), so
// f(d̂) · (2/N)² / |d|³ estimates ∫_texel f dω without bias.

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt::haar {

/// One texel's geometry: its corners (unit directions, in order around it) and its vector
/// integral Φ = ∫_texel ω dω (oriented toward the texel).
struct TexelGeometry {
  std::array<Vec3d, 4> corners;
  Vec3d moment;
};
TexelGeometry texelGeometry(std::uint32_t j, int resolution);
/// (1/π) ∫_texel max(n·ω, 0) dω, exactly (to rounding), for a unit normal n.
double clampedCosine(const TexelGeometry& texel, const Vec3d& normal);

class CubeTexels {
 public:
  explicit CubeTexels(int resolution);

  int resolution() const { return n_; }
  std::size_t count() const { return texels_.size(); }
  /// The unit directions of texel j's corners, in order around it.
  const std::array<Vec3d, 4>& corners(std::uint32_t j) const { return texels_[j].corners; }
  /// Its exact solid angle.
  double solidAngle(std::uint32_t j) const { return omega_[j]; }

  /// (1/π) ∫_texel max(n·ω, 0) dω, exactly (to rounding), for a unit normal n.
  double clampedCosine(std::uint32_t j, const Vec3d& normal) const {
    return haar::clampedCosine(texels_[j], normal);
  }
  /// True when some of texel j lies strictly above the horizon of n (its corners say: the
  /// texel is the convex hull of its corners).
  bool aboveHorizon(std::uint32_t j, const Vec3d& normal) const;

  /// A direction in texel j from (u, v) ∈ [0, 1)², uniform on the texel's square of the face
  /// plane, and the weight (2/N)²/|d|³ by which f(direction) estimates ∫_texel f dω. In float,
  /// from the face's plane (its centre and axes, stored once).
  Vec3f sample(std::uint32_t j, float u, float v, float& weight) const;
  /// The same for the texel (x, y) of `face` (no division: the bake's loop knows them).
  Vec3f sample(int face, int x, int y, float u, float v, float& weight) const {
    const float step = 2.0f / float(n_);
    const float s = -1.0f + step * (float(x) + u), t = -1.0f + step * (float(y) + v);
    const FacePlane& p = faces_[std::size_t(face)];
    const Vec3f d = p.centre + p.s * s + p.t * t;
    const float inv = 1.0f / std::sqrt(dot(d, d));
    weight = step * step * inv * inv * inv;
    return d * inv;
  }

  /// How face f lies against the horizon of a unit normal: wholly below (no texel above it),
  /// wholly above (every texel above it) or across it (a faces's quad is convex, so its corners
  /// say).
  enum class FaceSide { Below, Above, Across };
  FaceSide faceSide(int face, const Vec3f& normal) const;

 private:
  int n_ = 0;
  std::vector<TexelGeometry> texels_;
  std::vector<double> omega_;
  struct FacePlane {
    Vec3f centre, s, t;            ///< d(s, t) = centre + s·S + t·T at unit distance
    std::array<Vec3f, 4> corners;  ///< unit
  };
  std::array<FacePlane, 6> faces_;
};

}  // namespace prt::haar
