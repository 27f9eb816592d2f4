#pragma once
// Transfer baking per vertex: unshadowed, shadowed and inter-reflected; diffuse vectors and
// glossy matrices (Sloan, Kautz & Snyder, "Precomputed Radiance Transfer for Real-Time Rendering
// in Dynamic, Low-Frequency Lighting Environments", SIGGRAPH 2002, §5–6). The maths, estimators
// and their error are derived in docs/transport.md.
//
// Vectors (TransferLayout::Vector):
//   T⁰_i(p) = (1/π) ∫ Y_i(ω) V(p,ω) max(n·ω,0) dω          (unshadowed: V = 1)
//   Tᵏ(p)   = (1/π) ∫ ρ(h(p,ω)) ⊙ Tᵏ⁻¹(h(p,ω)) [front face of h seen] max(n·ω,0) dω
//   T       = T⁰ + T¹ + … + Tᴷ
//
// Matrices (TransferLayout::Matrix), the light arriving at p as a linear map of the source light:
//   M⁰_ij(p) = ∫_{n·ω>0} Y_i(ω) V(p,ω) Y_j(ω) dω                  (unshadowed: V = 1)
//   M_ij(p)  = M⁰_ij(p) + ∫_{n·ω>0} Y_i(ω) z_j(h, −ω) [front face of h seen] dω
// for K bounces, with z the light the surface at h = h(p,ω) sends back toward p per unit of
// source light: for a diffuse material z = ρ(h) T^{K−1}(h), the diffuse vector transfer with
// K−1 bounces; for a glossy one (material lobe, ks > 0) z = M^{K−1}(h)ᵀ (ρ(h) d(n_h) +
// ks g(R_h(−ω))), the matrices with K−1 bounces seen through the material's diffuse and lobe
// kernels (prt/transfer/prepared_material.hpp) from p. Vector bakes treat every bounce surface
// as diffuse (kd only): a vector cannot carry the direction the light leaves in.
//
// Determinism: every vertex draws its own sample set from (seed, global vertex index, bounce),
// so the transfer of vertex v depends on the inputs and the seed only — never on the thread
// count, and never on the vertex range being baked: bakes of ranges merge bit-exactly.

#include <cstddef>

#include "prt/core/progress.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

/// What a bake will hold in memory, known before it starts (the transfer dominates: 4·B⁴ bytes
/// per row and channel for matrices; per texel, the whole lightmap's passes besides).
struct BakeFootprint {
  int channels = 1;               ///< of the transfer the bake will return
  std::size_t bytesPerRow = 0;    ///< of the transfer (per vertex, per texel)
  std::size_t transferBytes = 0;  ///< the returned transfer (the range's rows)
  std::size_t workingBytes = 0;   ///< whole-domain buffers (bounces; texels: the lightmaps)
};
/// Of a bake of settings.domain (per texel: settings.lightmap's texels).
BakeFootprint bakeFootprint(const Mesh& mesh, const BakeSettings& settings);
/// The rows of settings.domain on `mesh`: its vertices, or settings.lightmap's texels.
std::size_t domainRows(const Mesh& mesh, const BakeSettings& settings);

/// A mesh file's own glossy surface (Mesh::gloss: MTL Ks/Ns → phong, glTF metallic-roughness →
/// ggx with F0 as ks) as a material, clamped to the ranges a material spec accepts; kd left unset.
/// What a bake takes when it is given no material (prt bake, the Python module's bake).
Material materialFromGloss(const SurfaceGloss& gloss);

/// Bakes the transfer of mesh (whose triangles `occluder` was built from) under `settings`: a
/// dense Transfer over the rows settings.rows (count 0: to the last) of settings.domain — the
/// vertices, or the texels of settings.lightmap over mesh.lightmapUvs (bake_texels.hpp) — of
/// settings.layout and settings.bands, computed on this process's threads (passes.hpp runs the
/// same passes on MPI ranks or job-array shards). Channels: 1, unless the mode is
/// Interreflected and some bounce albedo (or, for glossy bounces, ks) is not grey, then 3 (the
/// hit albedos are folded into the bounces; the albedo at the row itself is not).
/// Throws prt::Error on bad settings or mesh, or when the footprint would not fit in this
/// machine's memory (the message states the figure); prt::Cancelled if `progress` returns false.
Transfer bake(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
              BakeStats* stats = nullptr, const ProgressFn& progress = {});

}  // namespace prt
