#pragma once
// Lighting in the Haar basis (cube_haar.hpp): the non-linear approximation of an environment by
// its K largest wavelet coefficients (Ng, Ramamoorthi & Hanrahan 2003, §4.2), as sparse RGB
// terms, and the unshadowed part of the transfer's light (a Haar row holds the occluded part
// D = U − T alone; transfer/shape.hpp), in two pieces:
//     R(p) = kd(p) ⊙ ( Σ_b L_b U_b(n) + Σ_lm (A_l/π) L'_lm Y_lm(n) − Σ_k D̃_k(p) L̃_k )
// — the kBrightTexels brightest texels of the cube, b, exactly on the cube (U_b: the clamped
// cosine's integral over the texel, cube_texels.hpp), and the rest of the environment, L', in
// SH. The split is for the shadows: where a sun is occluded, the unshadowed part and the
// occluded part both hold it, and they must hold it the same way to cancel; a sun in SH and in
// the occlusion on the cube differ by the SH's ringing of the sun. Without the sun, the rest is
// smooth and few bands hold it. A data type only: project_light.hpp makes it, relight/relight_haar.hpp uses it,
// io/light_file.hpp stores it.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/sh/sh.hpp"

namespace prt::haar {

/// The light's terms a viewer relights with unless told otherwise (prt render --terms, prt view,
/// the page, Python's relight of an environment): Ng et al. 2003 relight with about 200.
inline constexpr std::size_t kDefaultLightTerms = 200;

/// The brightest texels of the cube (by power L·Ω) that relight the unshadowed part exactly.
inline constexpr std::size_t kBrightTexels = 16;

/// One of them: the texel and its mean radiance.
struct BrightTexel {
  std::uint32_t texel = 0;
  Rgb radiance;
};

/// Bands of the light's SH that relight the rest of the unshadowed part U(n): the clamped
/// cosine's A_l fall as l^−5/2, and the rest has no sun. Measured under builtin:sky, unshadowed
/// (2,000 vertices, docs/haar.md): the sphere over a plane relights to 1.72% rel. RMSE at 5
/// bands with the split, against the reference's own noise of 1.87%; with the sun in the SH too
/// it took 12 bands to reach 2.07% (5: 4.0%, 8: 2.8%).
inline constexpr int kUnshadowedBands = 5;

struct HaarLight {
  int resolution = 0;                ///< the cube's N
  std::vector<std::uint32_t> index;  ///< the terms' coefficients, ascending, < 6 N²
  std::vector<Rgb> value;            ///< their RGB values (one per index)
  /// The environment's SH (kUnshadowedBands bands, rotated as the terms are) less the bright
  /// texels', and those texels.
  sh::RgbSh unshadowed;
  std::vector<BrightTexel> bright;
  /// Of the whole projection (all 6 N² coefficients): Σ|c|² of what was kept over Σ|c|² of all
  /// (RGB summed), the share of the light's energy the terms hold.
  double energyKept = 1;

  std::size_t terms() const { return index.size(); }
  /// The 6 N² coefficients with zeros where no term is kept.
  std::vector<Rgb> dense() const;
  /// Throws prt::Error("WHAT: ...") unless the resolution is valid, indices ascend below 6 N²,
  /// the SH has kUnshadowedBands bands, at most kBrightTexels distinct bright texels lie in the
  /// cube and every value is finite.
  void check(const std::string& what) const;
};

}  // namespace prt::haar
