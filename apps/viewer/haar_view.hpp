#pragma once
// What prt view draws of a Haar bake (issue 33; docs/haar.md): each vertex relit on the CPU as
// prt render relights it — the environment's kHaarViewLightTerms largest area-weighted wavelet
// terms over the transfer's cube against the rows' sparse terms (relight::relightHaar) —
// uploaded as exit radiance (the CpuRadiance path: the shader interpolates it). A turned light
// is the environment resampled turned, not a rotation in the basis: HaarViewLight keeps the
// environment's cube four times finer than the transfer's (haar/turned_cube.hpp, as the browser
// viewers do) and splats it at each turn, 1.7–3.9× faster than projecting the environment again
// (bench BM_HaarTurnLight) and relit to 0.05% of it; a cube past haar::kMaxTurnedResolution
// projects the environment at each turn (haar::projectLight). Nothing is re-baked.

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

/// The exit radiance of each of `mesh`'s vertices: the Haar transfer relit under `light` with
/// the material's kd, else the mesh's albedo at its vertices (its texture folded in), as prt
/// render draws it.
std::vector<Rgb> haarViewRadiance(const Mesh& mesh, const Transfer& transfer,
                                  const Material& material, const haar::HaarLight& light);

}  // namespace prt::viewer
