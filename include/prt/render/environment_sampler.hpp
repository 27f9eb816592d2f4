#pragma once
// The environment as the reference sees it (render/reference.hpp): a piecewise-constant
// function over its texels' exact footprints, with a luminance-proportional sampling
// distribution (an alias table) over them.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/envmap/environment.hpp"

namespace prt::render {

/// The environment as a piecewise-constant function over its texels, with a
/// luminance-proportional sampling distribution over them.
class EnvironmentSampler {
 public:
  explicit EnvironmentSampler(const envmap::Environment& env);

  /// Radiance of the texel containing unit direction `dir` (environment frame).
  Rgb radiance(const Vec3f& dir) const;
  /// Density (per steradian) with which sample() produces `dir`.
  double pdf(const Vec3f& dir) const;
  /// Both at once (one texel search): returns the radiance, writes the density to `pdf`.
  Rgb lookup(const Vec3f& dir, double& pdf) const;
  /// Draws a direction: u0 picks the texel, (u1, u2) the point within it. Returns false for a
  /// null sample (a probe texel point outside the disc, or an all-black environment).
  bool sample(double u0, float u1, float u2, Vec3f& dir, double& pdf, Rgb& radiance) const;
  /// False when the environment carries no positive luminance (nothing to sample).
  bool canSample() const { return total_ > 0; }
  /// Σ_k L_k ΔΩ_k max(n·ω_k, 0) over texel centres ω_k (rotated by `rotation`): the clamped
  /// cosine integral of the piecewise-constant environment by texel quadrature, i.e. the exact
  /// irradiance up to the curvature of the cosine within a texel.
  Rgb irradianceQuadrature(const Vec3f& n, const Mat3d& rotation = Mat3d::identity()) const;

  const envmap::Environment& environment() const { return env_; }

 private:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  std::size_t texelOf(const Vec3f& dir) const;
  double densityWithin(std::size_t k, const Vec3f& dir) const;

  envmap::Environment env_;
  /// Per texel what a lookup needs, side by side: one cache line fetch per random lookup.
  struct TexelEntry {
    Rgb radiance;
    float prob = 0;  ///< P_k = lum_k ΔΩ_k / Σ, Σ P_k = 1
  };
  /// Walker's alias table (Vose's construction, "A Linear Algorithm for Generating Random
  /// Numbers with a Given Distribution", IEEE TSE 1991): texel j = ⌊u n⌋ is kept when the
  /// fraction of u n is below `accept`, else `alias` is taken — O(1) per sample, one random
  /// memory access instead of a binary search over a CDF of n doubles.
  struct AliasEntry {
    float accept = 1;
    std::uint32_t alias = 0;
  };
  std::vector<TexelEntry> texels_;
  std::vector<AliasEntry> alias_;
  std::vector<Vec3f> direction_;
  std::vector<float> solidAngle_;
  double total_ = 0;  ///< Σ lum_k ΔΩ_k
};

}  // namespace prt::render
