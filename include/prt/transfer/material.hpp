#pragma once
// Materials for relighting: a Lambertian part and an optional glossy lobe that is radially
// symmetric about the reflected view direction R = 2(n·v)n − v.
//
//   exit radiance  e(p, v) = kd(p) ⊙ (1/π) ∫ L'_p(ω) max(n·ω, 0) dω  +  ks ⊙ ∫ L'_p(ω) G(R·ω) dω
//
// with L'_p the light that arrives at p (shadowed, and bounced off the scene for inter-reflected
// transfer). With L'_p in SH (L'_p = M_p L for glossy transfer matrices, transfer.hpp), both
// integrals are zonal convolutions (Funk–Hecke), so
//
//   e(p, v) = Σ_lm L'_lm [ kd (A_l/π) Y_lm(n) + ks Λ_l Y_lm(R) ],    Λ_l = 2π ∫ G(t) P_l(t) dt,
//
// A_l the clamped-cosine kernel (Ramamoorthi & Hanrahan 2001). The lobe enters at relighting
// time only, so it can be changed without a new bake (Sloan, Kautz & Snyder 2002, §6; Kautz,
// Sloan & Snyder 2002 for arbitrary BRDFs in a local frame, not done here).
//
// Lobes (each normalised: ∫ G dω = 1, so Λ_0 = 1 and a white furnace returns ks):
//   * phong:  G(t) = (s + 1)/(2π) · max(t, 0)^s                       (s = exponent)
//   * ggx:    a GGX-shaped lobe symmetric about R — NOT a microfacet BRDF. The GGX/Trowbridge–
//             Reitz NDF D(h) (α = roughness²) as seen at normal incidence, carried to reflected
//             directions: ω at angle θ from R has half vector at θ/2 and G(cos θ) = D(θ/2)/4
//             (the Jacobian dω/dh = 4 h·v). The same shape at every view angle: no Fresnel, no
//             masking-shadowing, no 1/(4 n·l n·v) and no n·l, so it conserves energy exactly
//             and is zonal (one Λ_l per band). A standard microfacet BRDF (Walter et al. 2007:
//             D F G / (4 n·l n·v), times n·l) stretches and brightens toward grazing views —
//             docs/transport.md measures the difference (the name stays `ggx`: files store it).
// The brute-force reference (render/reference) evaluates the same G, so PRT and reference
// differ only by band limit and noise.
//
// Where a material comes from: `--material`, else the mesh file's own glossy surface
// (Mesh::gloss: OBJ/MTL Ks and Ns → phong; glTF metallic-roughness → ggx with F0 as ks), else
// lambert; the bake stores it and relighting uses it unless told otherwise.
//
// Spec strings (`--material`, bake metadata): `lambert`, `phong?exponent=32&ks=0.5`,
// `ggx?roughness=0.3&ks=0.04`; every kind takes `kd=x` or `kd=r,g,b` (the diffuse colour,
// replacing the mesh's own albedo) and `ks` likewise.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt {

enum class LobeKind { None, Phong, Ggx };

/// The ranges and defaults a material spec accepts — the one copy (the CLI, the viewer's panel
/// and the page's controls all use these).
inline constexpr double kMaxPhongExponent = 1e4;
/// α = roughness² ≥ 9e-4: narrower lobes need more than 32 bands anyway.
inline constexpr double kMinGgxRoughness = 0.03;
inline constexpr double kDefaultPhongExponent = 32.0;
inline constexpr double kDefaultGgxRoughness = 0.3;
inline constexpr float kDefaultSpecular = 0.5f;

struct GlossyLobe {
  LobeKind kind = LobeKind::None;
  double exponent = 0;   ///< Phong exponent s >= 0
  double roughness = 0;  ///< GGX perceptual roughness in (0, 1]; α = roughness²

  /// G(t), t = cos of the angle to R; zero for None.
  double value(double t) const;
  /// Λ_l = 2π ∫ G(t) P_l(t) dt for l = 0..bands-1 (Λ_0 = 1 for a lobe, all 0 for None).
  std::vector<double> zonal(int bands) const;
  /// Fraction of the lobe's energy ∫ G² dω in bands ≥ `bands`: what a B-band representation
  /// of the lobe cannot hold (Σ_{l≥B} Λ_l² (2l+1)/(4π) / ∫ G² dω). 0 for None.
  double energyBeyond(int bands) const;
  bool operator==(const GlossyLobe&) const = default;
};

/// The fraction of a lobe's energy beyond the relit bands (GlossyLobe::energyBeyond) past which
/// the highlight is visibly wrong — blurred and dimmed toward a broader lobe: render, validate,
/// view and web warn past it (GGX 0.3 at 6 bands loses 52 %, Phong 64 at 6 bands 19 %).
inline constexpr double kLobeEnergyLossWarning = 0.10;

struct Material {
  /// The diffuse colour kd; unset: the mesh's per-vertex albedo (glTF COLOR_0 / baseColor,
  /// OBJ Kd), else 1.
  std::optional<Rgb> diffuse;
  Rgb specular{0.0f};  ///< ks
  GlossyLobe lobe;

  /// True when the glossy term contributes (a lobe and ks > 0).
  bool glossy() const;
  /// The diffuse colours to relight with: the material's kd (one for all) when it sets one,
  /// else `perVertex` (the mesh's albedo, possibly empty = white). Views *this.
  std::span<const Rgb> diffuseOr(std::span<const Rgb> perVertex) const {
    return diffuse ? std::span<const Rgb>(&*diffuse, 1) : perVertex;
  }
  /// The spec string that parses back to this exact material (numbers in their shortest
  /// round-trip form).
  std::string spec() const;
  bool operator==(const Material&) const = default;
};

/// Parses a spec string (see above); throws prt::Error("SPEC: ...") on anything unknown or out
/// of range.
Material parseMaterial(const std::string& spec);
/// The one check of a material's ranges, for every way one arrives (a spec, a bake file, the
/// library's callers): kd and ks finite in [0, 1], a Phong exponent in [0, kMaxPhongExponent],
/// a GGX roughness in [kMinGgxRoughness, 1]. Throws prt::Error("material SPEC: WHAT").
void checkMaterial(const Material& m);

/// What the `ggx` spec is, in one plain-text line for --help texts.
inline constexpr const char* kGgxHelp =
    "ggx: a GGX-shaped lobe symmetric about the reflected view (normal-incidence GGX NDF; no "
    "Fresnel, masking or 1/(4 cos cos): not a microfacet BRDF)";

/// One line saying what `lobe` is (prt info): its shape, its parameter, what it leaves out.
std::string describe(const GlossyLobe& lobe);

/// The reflected view direction R = 2(n·v)n − v for unit n and v (v points away from the
/// surface, toward the eye).
inline Vec3f reflectView(const Vec3f& n, const Vec3f& v) {
  return n * (2.0f * dot(n, v)) - v;
}

}  // namespace prt
