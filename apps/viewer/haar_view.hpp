#pragma once
// What prt view draws of a Haar bake (issue 33; docs/haar.md): each row relit on the CPU as
// prt render relights it (render::haarRadiance, render/haar_shader.hpp) under the environment's
// kHaarViewLightTerms largest area-weighted wavelet terms over the transfer's cube. Per vertex
// the radiance is uploaded as exit radiance (the CpuRadiance path: the shader interpolates it);
// per texel as a one-band lightmap against the light's first coefficient, drawn per pixel as SH
// lightmaps are (relight::packRadianceLightmap: prt render's bilinear fetch, the albedo and the
// base-colour texture per pixel). A turned light is the environment resampled turned, not a
// rotation in the basis: HaarViewLight keeps the environment's cube four times finer than the
// transfer's (haar/turned_cube.hpp, as the browser viewers do) and splats it at each turn,
// 1.7–3.9× faster than projecting the environment again (bench BM_HaarTurnLight) and relit to
// 0.05% of it; a cube past haar::kMaxTurnedResolution projects the environment at each turn
// (haar::projectLight). Nothing is re-baked.

#include <cstddef>
#include <optional>
#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/haar/turned_cube.hpp"
#include "prt/io/bake_file.hpp"

namespace prt::viewer {

/// The light's terms a Haar bake is relit under: prt render's default (--terms).
inline constexpr std::size_t kHaarViewLightTerms = haar::kDefaultLightTerms;

/// `env` turned by `rotation` as prt render projects it (haar::projectLight), over an N² cube:
/// the first view's exposure is prt render's.
haar::HaarLight haarRenderLight(const envmap::Environment& env, int resolution,
                                const Mat3d& rotation);

/// An environment's light for a Haar bake over an N² cube, at any turn.
class HaarViewLight {
 public:
  /// Keeps `env` (which must outlive this) and, for N ≤ haar::kMaxTurnedResolution, makes its
  /// fine cube (once: a projection at 4N).
  HaarViewLight(const envmap::Environment& env, int resolution);
  /// The light turned by `rotation` (kHaarViewLightTerms terms, or the cube's all if fewer).
  haar::HaarLight at(const Mat3d& rotation) const;
  int resolution() const { return resolution_; }

 private:
  const envmap::Environment* env_;
  int resolution_;
  std::optional<haar::EnvironmentCube> cube_;
};

/// A per-texel Haar bake's texels, as prt render relights them (render::texelRelight): each
/// row's normal — a covered texel's own, a gutter texel its neighbour's, whose row it copies —
/// since an occluded-part row adds the unshadowed light at its normal. Traces the
/// inside-geometry probe that places the texels (once per bake).
std::vector<Vec3f> haarTexelNormals(const Mesh& mesh, const Transfer& transfer);

}  // namespace prt::viewer
