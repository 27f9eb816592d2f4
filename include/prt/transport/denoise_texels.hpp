#pragma once
// Denoising of per-texel transfer in lightmap space (issue 35; `prt denoise`, `prt bake
// --denoise`): an edge-avoiding à-trous filter (Dammertz, Sewtz, Hanika & Lensch,
// "Edge-Avoiding À-Trous Wavelet Transform for fast Global Illumination Filtering", HPG 2010)
// of the coefficient rows whose value weights follow each texel's own noise, as in SVGF (Schied
// et al., "Spatiotemporal Variance-Guided Filtering", HPG 2017), and whose output is a
// first-order fit, not a mean (weighted local regression: Moon, Carr & Yoon, "Adaptive
// Rendering Based on Weighted Local Regression", TOG 2014; Bitterli et al., "Nonlinearly
// Weighted First-order Regression for Denoising Monte Carlo Renderings", EGSR 2016).
//
// Level i = 0 .. iterations−1 takes, for each valid texel p, the 5 × 5 taps q = p + 2^i (a, b),
// a, b ∈ −2..2 (the footprint doubles with each level), weighted by
//
//   w(p, q) = h_a h_b · [chart(q) = chart(p)] · max(0, n_p·n_q)^σn
//             · exp(−‖x_p − x_q‖² / (2 (2^(i+1) s)²))
//             · exp(−‖T_p − T_q‖² / (2 k² (σ_p² + σ_q²)))
//
// h = (1, 4, 6, 4, 1)/16 the B3-spline kernel, chart the UV chart of the texel's triangle (its
// connected component through shared vertices), n and x the texel's sample normal and point, s
// the lightmap's texel size in the world (the median distance between neighbouring valid
// texels of one chart), σ_p² the noise variance of the row at p and k = `strength`; and replaces
// T_p by α, the value at p of the plane α + β a + γ b fitted to the taps' rows by weighted
// least squares (the same 3 × 3 normal equations for every coefficient): α = Σ λ_q T_q,
// λ_q = w_q (1, a, b)·A⁻¹e₁, A = Σ w (1, a, b)(1, a, b)ᵀ. A mean would bend every gradient
// of the light toward its neighbours' — on the Cornell box at 128² a plain 5 × 5 blur of a
// converged bake moves it by 3–4 % — and most at a chart's border, where its taps lie on one
// side; the plane follows a gradient and leaves only the light's curvature. Where the taps do
// not span a plane (a strip one texel wide) the weighted mean stands in.
//
// Only valid texels — covered, not inside geometry — are filtered or read, so the filter never
// mixes two charts; it leaves a crease (normals apart) and an edge of the signal (a shadow's: T
// jumps by many σ) as they are, and averages what differs by noise alone. After each level the
// variance follows the weights, σ_p'² = Σ λ_q² σ_q² (SVGF), so later levels stop at smaller
// differences.
//
// The noise of a row is not stored in a bake file, so it is estimated from the rows themselves:
// r_p = T_p − the mean of its 4-neighbours of its chart (for noise of variance σ² per
// coefficient, E‖r‖² = (1 + 1/m) Σσ² with m neighbours), σ_p² = the median of ‖r_q‖²/(1 + 1/m)
// over the 5 × 5 valid texels of its chart about p. The median keeps a signal's edge out (it
// raises the residual of the texels along it, less than half of the window), and a row the
// control variate made exact (an unoccluded texel: T = the unshadowed transfer) has no noise
// and is left as it is. (On the Cornell box at 64 samples the estimate, 0.0134 per row, is the
// noise measured against a 8,192-sample bake, 0.0139.)
//
// The rows are then laid out as the bake lays them out: the gutter dilated from the filtered
// rows, texels inside geometry refilled from them (transport/texel_validity.hpp).
// Deterministic: every level reads the previous level's rows only, in texel order.

#include <cstddef>

#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

struct DenoiseSettings {
  int iterations = 3;        ///< à-trous levels (taps 1, 2, 4 texels apart): 1..8
  double strength = 2.0;     ///< k: how many noise deviations a difference may span (> 0)
  double normalPower = 64;   ///< σn: the normals' exponent (creases)
};

struct DenoiseStats {
  std::size_t texels = 0;      ///< valid texels filtered
  std::size_t charts = 0;      ///< UV charts among them
  double texelSize = 0;        ///< s, world units
  /// The rows' estimated noise, sqrt of the mean σ_p² over the valid texels, before the filter
  /// and as its variance propagation leaves it (in the transfer's units, per row).
  double noiseBefore = 0, noiseAfter = 0;
  double seconds = 0;
};

/// Throws prt::Error naming the setting when a value is out of range.
void checkDenoiseSettings(const DenoiseSettings& settings);

/// The filtered transfer (see the top), its lightmap marked `denoised`. `transfer` must be a
/// complete, dense per-texel transfer over `mesh`'s lightmap UVs (what a bake file holds;
/// occluder built from `mesh` for the inside-geometry test, as the bake's). Throws prt::Error
/// naming the mesh otherwise (a range: merge first; compressed: denoise before compressing).
Transfer denoiseTexels(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                       const DenoiseSettings& settings = {}, DenoiseStats* stats = nullptr);

}  // namespace prt
