#pragma once
// Encoding an SH light's irradiance in the forms engines store, evaluating them, and measuring
// what each loses (issue 34; the encodings and their papers: sh/irradiance_encoding.hpp).
//
// The reference every encoding is measured against is the irradiance of all the light's bands,
// E(n) = Σ_l Λ_l Σ_m L_lm Y_lm(n) (sh/convolve.hpp), on a Gauss–Legendre grid of the sphere.

#include "prt/sh/irradiance_encoding.hpp"
#include "prt/sh/sh.hpp"

namespace prt::sh {

/// The bands of the reference an encoding's error is measured against (prt light --encoding,
/// prt info): past band 11 the clamped cosine keeps < 0.1 % of a band's radiance
/// (Λ₁₀/π = 0.0012), so irradiance has converged.
inline constexpr int kIrradianceReferenceBands = 12;

/// Encodes the irradiance of `radiance` (any band count ≥ 1; bands it lacks count as zero).
EncodedIrradiance encodeIrradiance(const RgbSh& radiance, IrradianceEncoding encoding);

/// The encoded irradiance at unit normal n, as an engine reconstructs it.
Rgbd evaluate(const EncodedIrradiance& e, const Vec3d& n);

/// What an encoding loses against the reference, over the sphere of normals.
struct EncodingError {
  /// sqrt(∫ Σ_c (E_c − Ê_c)²) / sqrt(∫ Σ_c E_c²): relative RMS over normals and channels.
  double relativeRms = 0;
  /// Share of the sphere (solid angle) where some channel of the encoded irradiance is negative.
  double negativeShare = 0;
  /// The smallest value of any channel over the grid, over the reference's RMS value
  /// sqrt(∫ Σ_c E_c² / 12π) (negative: it rings below zero).
  double relativeMinimum = 0;
};
EncodingError encodingError(const RgbSh& radiance, const EncodedIrradiance& encoded);

/// The band-1 direction of scalar SH coefficients c[1..3] in the project's basis (Y₁,₋₁ ∝ −y,
/// Y₁,₀ ∝ z, Y₁,₁ ∝ −x): the v with c₁·Y₁(n) = 0.488603 v·n; |v| is band 1's norm.
Vec3d bandOneVector(double cm1, double c0, double cp1);

}  // namespace prt::sh
