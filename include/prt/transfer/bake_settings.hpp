#pragma once
// How a transfer is baked: the recipe stored with it in a bake file (mode, samples, bounces,
// seed, sampling, material), the settings a bake takes (the recipe plus the shape asked for),
// and the statistics it reports. Types only: the baking itself is transport/bake.hpp, so that
// anything that reads a bake file links no ray tracer.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/transfer/material.hpp"
#include "prt/transfer/shape.hpp"

namespace prt {

/// Which integral the transfer holds (the transport, independent of layout and material).
enum class TransferMode { Unshadowed, Shadowed, Interreflected };
const char* toString(TransferMode mode);
/// Parses "unshadowed" | "shadowed" | "interreflected"; throws prt::Error otherwise.
TransferMode parseTransferMode(const std::string& s);
/// The modes from the richest to the plainest: the order in which a verb picks its default.
inline constexpr TransferMode kModesRichestFirst[] = {
    TransferMode::Interreflected, TransferMode::Shadowed, TransferMode::Unshadowed};

enum class Sampling {
  /// Cosine-weighted hemisphere over Owen-scrambled Sobol' points (the default: unbiased and
  /// far less noisy than random sampling for the same ray count).
  CosineSobol,
  /// The GAMES202 course's scheme: independent uniform directions over the whole sphere,
  /// weight 4π/N · max(n·ω,0)/π; half of them fall below the horizon. For comparison.
  UniformRandom,
};
const char* toString(Sampling sampling);
/// Parses "cosine" | "sobol" | "cosine-sobol" | "uniform" | "uniform-random" (the front ends'
/// spellings, one list); throws prt::Error otherwise.
Sampling parseSampling(const std::string& s);

/// Limits on the settings (checked by bake(); each violation is a one-line prt::Error).
inline constexpr int kMaxBakeSamples = 1 << 24;
inline constexpr int kMaxBounces = 16;
/// Rays per cube texel of a Haar bake (its `samples`): at most 64, and 1 when not given.
inline constexpr int kMaxHaarRaysPerTexel = 64;
inline constexpr int kDefaultHaarRaysPerTexel = 1;
/// An inter-reflected Haar bake's bounce is SH (transfer/shape.hpp): its SH passes cast this many
/// directions per row for each ray per cube texel — the SH bake's default at one ray a texel.
inline constexpr int kHaarBounceSamplesPerTexelRay = 1024;
/// Adaptive sampling (BakeRecipe::targetError): the pilot every row casts before it decides how
/// many more it needs — the first 64 points of its Owen-scrambled Sobol' sequence, a (0,6,2)-net,
/// so each of 64 equal-measure cells of the cosine-weighted hemisphere holds one of them.
inline constexpr int kAdaptivePilotSamples = 64;
/// The largest target error: the radiance under the constant unit sky lies in [0, 1].
inline constexpr double kMaxTargetError = 1.0;

/// The bounces a mode bakes (and its reference follows): `bounces` for Interreflected, else 0 —
/// the one rule.
constexpr int effectiveBounces(TransferMode mode, int bounces) {
  return mode == TransferMode::Interreflected ? bounces : 0;
}

/// How a transfer was (or is to be) baked, apart from its shape.
struct BakeRecipe {
  TransferMode mode = TransferMode::Shadowed;
  int samples = 1024;  ///< directions per row per pass (powers of two suit Sobol' best)
  int bounces = 0;     ///< inter-reflection bounces, 0..16 (only Interreflected bounces)
  std::uint64_t seed = 0;
  Sampling sampling = Sampling::CosineSobol;
  /// Adaptive sampling (issue 35; docs/transport.md, "Adaptive sampling"): 0 casts `samples`
  /// directions per row and pass. E > 0 makes `samples` the most a row may cast: each row first
  /// casts kAdaptivePilotSamples, estimates its variance from them, and casts the power of two
  /// of directions (at most `samples`, at least 1/E) at which the i.i.d. standard error of its
  /// radiance under the constant unit sky (√(4π)·T₀, BakeStats::stdErrConst) reaches E/√P over
  /// its P passes — a two-stage rule (Stein 1945) decided by the row's own pilot, so the bake
  /// stays deterministic and independent of threads, ranks and ranges. Vector SH bakes with
  /// cosine-Sobol' sampling only.
  double targetError = 0;
  bool adaptive() const { return targetError > 0; }
  /// The surface. Its diffuse colour (material.diffuse, else mesh.albedo, else 1) is the albedo
  /// of the bounces. Its lobe and ks shape the bounces of an inter-reflected matrix bake (the
  /// light glossy surfaces send toward each other); otherwise the lobe is applied at relighting
  /// only. Either way it is stored with the bake as the default for relighting.
  Material material;

  /// The bounces the mode bakes (prt::effectiveBounces).
  int effectiveBounces() const { return prt::effectiveBounces(mode, bounces); }
  /// True when a bake of this recipe in `layout` bounces light through the material's lobe: an
  /// inter-reflected matrix bake (with bounces) of a glossy material. Its transfer then holds
  /// that lobe and ks in the light the surfaces send each other, so relighting with another
  /// material changes the surface at each vertex but not that light. A vector bake's bounces
  /// are diffuse: it cannot hold the direction light leaves in.
  bool glossyBounces(TransferLayout layout) const {
    return layout == TransferLayout::Matrix && effectiveBounces() > 0 && material.glossy();
  }
  bool operator==(const BakeRecipe&) const = default;
};

/// The one check of a recipe, for bake() and for the bake file's writer and reader alike (a file
/// holds only what a bake could have made): samples in 1..kMaxBakeSamples, bounces in
/// 0..kMaxBounces, the target error finite in [0, kMaxTargetError], the material by
/// checkMaterial. Throws prt::Error naming the value.
void checkRecipe(const BakeRecipe& recipe);

/// What bake() takes: the recipe, and the shape of the transfer to make.
struct BakeSettings : BakeRecipe {
  /// Vector: diffuse transfer (B² per row). Matrix: glossy transfer (B² × B² per row, see
  /// prt/transfer/shape.hpp), sampled uniformly over each vertex's hemisphere.
  TransferLayout layout = TransferLayout::Vector;
  int bands = 3;
  /// The basis: SH of `bands` bands, or Haar wavelets over a cube map (`haar`: its resolution
  /// and the terms kept per row; bands unused), whose `samples` are the rays per cube texel
  /// (transport/bake_haar: one jittered ray or more per texel above the horizon).
  TransferBasis basis = TransferBasis::SphericalHarmonics;
  TransferShape::HaarSize haar{};
  /// `shape` in this basis: its bands, or no bands and the Haar size.
  TransferShape inBasis(TransferShape shape) const;
  /// Where the rows lie: the mesh's vertices, or the texels of a lightmap (`lightmap`: its
  /// width, height and gutter padding) over the mesh's lightmap UVs (transport/passes.hpp).
  TransferDomain domain = TransferDomain::Vertices;
  TransferShape::LightmapSize lightmap{};
  /// Or the probes of a grid in space (probe_grid.hpp): matrix transfer over the whole sphere,
  /// its bounces off the scene's surfaces diffuse.
  ProbeGrid probes{};
  /// The rows to bake: [rows.first, rows.first + rows.count) of the domain; count 0 means "to
  /// the last row". The result holds those rows only (its row 0 is rows.first).
  RowRange rows;
};

struct BakeStats {
  std::uint64_t rays = 0;    ///< rays cast, all passes
  double raysPerSecond = 0;  ///< over the ray-casting passes (raysPerSecondOf)
  double secondsTotal = 0;
  double secondsDirect = 0;           ///< the T⁰ pass (for Interreflected: over the whole mesh)
  std::vector<double> secondsBounce;  ///< one entry per bounce
  std::vector<std::uint64_t> raysBounce;
  int threads = 0;
  std::size_t vertices = 0;  ///< rows in the baked range
  /// Monte Carlo error estimates over the baked range, as i.i.d. standard errors
  /// sqrt(sample variance / N) of the per-vertex estimators. For the scrambled-Sobol' estimator
  /// these are conservative (its error falls faster than N^-1/2).
  double stdErrT0Mean = 0, stdErrT0Max = 0;
  /// Of T·L for the constant environment L = 1 (L00 = √(4π)), i.e. of √(4π)·T₀, summed over the
  /// bounces (independent estimators; first channel for RGB transfer).
  double stdErrConstMean = 0, stdErrConstMax = 0;
  /// Rays per sampled row and pass, on average: what adaptive sampling spent (0 without rows).
  double raysPerRowAndPass() const {
    const double passes = 1.0 + static_cast<double>(secondsBounce.size());
    return vertices > 0 ? static_cast<double>(rays) / (static_cast<double>(vertices) * passes)
                        : 0.0;
  }
};

/// Rays per second: rays / seconds, 0 when no time was measured — the one formula.
inline double raysPerSecondOf(std::uint64_t rays, double seconds) {
  return seconds > 0 ? static_cast<double>(rays) / seconds : 0.0;
}

/// The statistics of a bake of the union of two disjoint row ranges baked apart (a rows, b
/// rows): rays and times add, the ray rate over the summed ray time, mean errors average
/// weighted by rows, maxima take the maximum.
BakeStats combineBakeStats(const BakeStats& a, std::size_t rowsA, const BakeStats& b,
                           std::size_t rowsB);

}  // namespace prt
