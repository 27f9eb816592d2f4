#pragma once
// Diffuse transfer baking per vertex: unshadowed, shadowed and inter-reflected
// (Sloan, Kautz & Snyder, "Precomputed Radiance Transfer for Real-Time Rendering in Dynamic,
// Low-Frequency Lighting Environments", SIGGRAPH 2002, §5). The maths, estimators and their
// error are derived in docs/transport.md.
//
//   T⁰_i(p) = (1/π) ∫ Y_i(ω) V(p,ω) max(n·ω,0) dω          (unshadowed: V = 1)
//   Tᵏ(p)   = (1/π) ∫ ρ(h(p,ω)) ⊙ Tᵏ⁻¹(h(p,ω)) [front face of h seen] max(n·ω,0) dω
//   T       = T⁰ + T¹ + … + Tᴷ
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
#include "prt/transport/transfer.hpp"

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
  int bands = 3;
  int samples = 1024;  ///< directions per vertex per pass (powers of two suit Sobol' best)
  int bounces = 0;     ///< inter-reflection bounces (Interreflected only), 0..16
  std::uint64_t seed = 0;
  Sampling sampling = Sampling::CosineSobol;
  /// Uniform albedo used for the bounces, overriding mesh.albedo. Without either, albedo 1.
  std::optional<Rgb> albedo;
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

/// Bakes the transfer of mesh (whose triangles `occluder` was built from) under `settings`.
/// Channels: 1, unless the mode is Interreflected and some bounce albedo is not grey, then 3
/// (the hit albedos are folded into the bounces; the albedo at the vertex itself is not).
/// Throws prt::Error on bad settings or mesh, prt::Cancelled if `progress` returns false.
TransferField bake(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                   BakeStats* stats = nullptr, const ProgressFn& progress = {});

}  // namespace prt
