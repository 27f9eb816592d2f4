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
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/field.hpp"
#include "prt/transfer/material.hpp"

namespace prt {

enum class Sampling {
  /// Cosine-weighted hemisphere over Owen-scrambled Sobol' points (the default: unbiased and
  /// far less noisy than random sampling for the same ray count).
  CosineSobol,
  /// The GAMES202 course's scheme: independent uniform directions over the whole sphere,
  /// weight 4π/N · max(n·ω,0)/π; half of them fall below the horizon. For comparison.
  UniformRandom,
};
const char* toString(Sampling sampling);
/// Parses "sobol" | "cosine-sobol" | "uniform" | "uniform-random"; throws prt::Error otherwise.
Sampling parseSampling(const std::string& s);

/// Limits on the settings (checked by bake(); each violation is a one-line prt::Error).
inline constexpr int kMaxBakeSamples = 1 << 24;
inline constexpr int kMaxBounces = 16;

struct BakeSettings {
  TransferMode mode = TransferMode::Shadowed;
  /// Vector: diffuse transfer (B² per vertex). Matrix: glossy transfer (B² × B² per vertex,
  /// see prt/transfer/field.hpp), sampled uniformly over each vertex's hemisphere.
  TransferLayout layout = TransferLayout::Vector;
  int bands = 3;
  int samples = 1024;  ///< directions per vertex per pass (powers of two suit Sobol' best)
  int bounces = 0;     ///< inter-reflection bounces (Interreflected only), 0..16
  std::uint64_t seed = 0;
  Sampling sampling = Sampling::CosineSobol;
  /// The surface. Its diffuse colour (material.diffuse, else mesh.albedo, else 1) is the albedo
  /// of the bounces. Its lobe and ks shape the bounces of an inter-reflected matrix bake (the
  /// light glossy surfaces send toward each other); otherwise the lobe is applied at relighting
  /// only. Either way it is stored with the bake as the default for relighting.
  Material material;
  /// The vertex range to bake: [firstVertex, firstVertex + vertexCount); vertexCount 0 means
  /// "to the last vertex". The result holds the range's vertices only (row 0 = firstVertex).
  std::size_t firstVertex = 0, vertexCount = 0;
};

struct BakeStats {
  std::uint64_t rays = 0;    ///< rays cast, all passes
  double raysPerSecond = 0;  ///< over the ray-casting passes
  double secondsTotal = 0;
  double secondsDirect = 0;           ///< the T⁰ pass (for Interreflected: over the whole mesh)
  std::vector<double> secondsBounce;  ///< one entry per bounce
  std::vector<std::uint64_t> raysBounce;
  int threads = 0;
  std::size_t vertices = 0;  ///< vertices in the baked range
  /// Monte Carlo error estimates over the baked range, as i.i.d. standard errors
  /// sqrt(sample variance / N) of the per-vertex estimators. For the scrambled-Sobol' estimator
  /// these are conservative (its error falls faster than N^-1/2).
  double stdErrT0Mean = 0, stdErrT0Max = 0;
  /// Of T·L for the constant environment L = 1 (L00 = √(4π)), i.e. of √(4π)·T₀, summed over the
  /// bounces (independent estimators; first channel for RGB transfer).
  double stdErrConstMean = 0, stdErrConstMax = 0;
};

/// True when the bake's bounces follow the material's lobe: an inter-reflected matrix bake (with
/// bounces) of a glossy material. Its transfer then holds that lobe and ks in the light the
/// surfaces send each other, so relighting with another material changes the surface at each
/// vertex but not that light (a new bake changes both). A vector bake's bounces are diffuse: it
/// cannot hold the direction light leaves in.
bool glossyBounces(const BakeSettings& settings);

/// What a bake will hold in memory, known before it starts (the transfer dominates: 4·B⁴ bytes
/// per vertex and channel for matrices).
struct BakeFootprint {
  int channels = 1;                ///< of the transfer the bake will return
  std::size_t bytesPerVertex = 0;  ///< of the transfer
  std::size_t transferBytes = 0;   ///< the returned transfer (the range's vertices)
  std::size_t workingBytes = 0;    ///< full-mesh buffers for inter-reflection
};
BakeFootprint bakeFootprint(const Mesh& mesh, const BakeSettings& settings);
/// The largest transfer a bake file can hold (a GLB chunk length is 32 bits).
inline constexpr std::size_t kMaxTransferFileBytes =
    (std::size_t(1) << 32) - (std::size_t(1) << 26);

/// Bakes the transfer of mesh (whose triangles `occluder` was built from) under `settings`.
/// Channels: 1, unless the mode is Interreflected and some bounce albedo (or, for glossy
/// bounces, ks) is not grey, then 3 (the hit albedos are folded into the bounces; the albedo at
/// the vertex itself is not).
/// Throws prt::Error on bad settings or mesh, or when the footprint would not fit in this
/// machine's memory or a bake file (the message states the figure); prt::Cancelled if
/// `progress` returns false.
TransferField bake(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                   BakeStats* stats = nullptr, const ProgressFn& progress = {});

}  // namespace prt
