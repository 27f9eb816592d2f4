#pragma once
// What prt view draws of a Haar bake (issue 33; docs/haar.md): each vertex relit on the CPU as
// prt render relights it — the environment's kHaarViewLightTerms largest area-weighted wavelet
// terms over the transfer's cube (haar::projectLight; a turned light is the environment
// resampled turned, not a rotation in the basis) against the rows' sparse terms
// (relight::relightHaar) — uploaded as exit radiance (the CpuRadiance path: the shader
// interpolates it). A turning light costs one projection (the cube's texel means, the wavelet
// transform, the term selection) and one sparse relighting; nothing is re-baked.

#include <cstddef>
#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/io/bake_file.hpp"

namespace prt::viewer {

/// The light's terms a Haar bake is relit under: prt render's default (--terms).
inline constexpr std::size_t kHaarViewLightTerms = haar::kDefaultLightTerms;

/// `env` turned by `rotation`, as the Haar light over an N² cube (N = the transfer's).
haar::HaarLight haarViewLight(const envmap::Environment& env, int resolution,
                              const Mat3d& rotation);

/// The exit radiance of each of `mesh`'s vertices: the Haar transfer relit under `light` with
/// the material's kd, else the mesh's albedo at its vertices (its texture folded in), as prt
/// render draws it.
std::vector<Rgb> haarViewRadiance(const Mesh& mesh, const Transfer& transfer,
                                  const Material& material, const haar::HaarLight& light);

}  // namespace prt::viewer
