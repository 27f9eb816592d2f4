#pragma once
// Irradiance in the compact forms engines store (issue 34): what an encoding keeps of the
// irradiance E(n) = ∫ L(ω) max(n·ω, 0) dω of an SH light, and how many numbers it costs.
//
//   l2                27 numbers   the irradiance SH of bands 0..2 (Ramamoorthi & Hanrahan 2001)
//   l2-deringed       27           l2 under the mildest Hanning window that leaves it
//                                  non-negative over the dense grid sh::dering uses (Sloan,
//                                  "Deringing Spherical Harmonics", 2017)
//   l1                12           bands 0..1: E(n) = E₀ + d·n, negative where |d| > E₀
//   l1-windowed       12           l1 with band 1 scaled by min(1, E₀/|d|) per channel: the
//                                  mildest window that makes it non-negative everywhere (for
//                                  band 1 the minimum, E₀ − |d|, is exact: Sloan 2017's deringing
//                                  reduces to this closed form)
//   l1-geomerics     12           Hazel's non-linear reconstruction of the same 12 numbers
//                                  (Geomerics, "Reconstructing diffuse lighting from spherical
//                                  harmonic data", 2014): E₀ (a + (1 − a)(p + 1) q^p), never
//                                  negative, its mean E₀ and its band 1 exact as |d|/E₀ → 0 or 1
//   zh3              15           l1 and, per channel, band 2 kept along one axis, the
//                                  luminance's band-1 direction: the zonal harmonic that carries
//                                  the most of band 2 that one number can (Roughton, Sloan et al.,
//                                  "ZH3: Quadratic Zonal Harmonics", I3D 2024)
//   zh3-shared       15           our variant of Roughton et al.'s zh3 (not in their paper): l1,
//                                  a stored axis a (2 numbers, octahedral) and ONE zonal number s
//                                  that the channels share in proportion to their means. zh3
//                                  spends its 3 extra numbers on a zonal per channel about an
//                                  axis band 1 guesses; band 2 is mostly of the light's own
//                                  colour, so 2 of them hold more as the axis that fits it:
//                                    z_c = s L₀₀,c,  s = Σ_c L₀₀,c ẑ_c(a) / Σ_c L₀₀,c²,
//                                    ẑ_c(a) = √(4π/5) Σ_m L₂ₘ,c Y₂ₘ(a),
//                                  a maximising (Σ_c L₀₀,c ẑ_c(a))² (zh3-optimal's search): the
//                                  least-squares best zonal term of that colour; the
//                                  irradiance's zonal is Λ₂ z_c
//   zh3-optimal      17           zh3 about the axis that holds the most of band 2 (summed over
//                                  channels: the least-squares best axis, found by search), which
//                                  the engine must then store (2 numbers, octahedral); the
//                                  paper's bound on what any axis can do
//   zh3-hallucinated 12           zh3 with each channel's zonal coefficient guessed from its own
//                                  band 1 along the luminance axis (the paper's fit:
//                                  L₀ (0.08 r + 0.6 r²), r = |L₁·axis|/L₀): no extra storage
//
// The data type only; sh/encode_irradiance.hpp makes and evaluates it.

#include <array>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt::sh {

enum class IrradianceEncoding {
  L2,
  L2Deringed,
  L1,
  L1Windowed,
  L1Geomerics,
  ZH3,
  ZH3Shared,
  ZH3Optimal,
  ZH3Hallucinated
};

/// Every encoding, in the order tables list them.
inline constexpr std::array<IrradianceEncoding, 9> kIrradianceEncodings = {
    IrradianceEncoding::L1,          IrradianceEncoding::L1Windowed,
    IrradianceEncoding::L1Geomerics, IrradianceEncoding::ZH3Hallucinated,
    IrradianceEncoding::ZH3,         IrradianceEncoding::ZH3Shared,
    IrradianceEncoding::ZH3Optimal,  IrradianceEncoding::L2,
    IrradianceEncoding::L2Deringed};

/// Whether the encoding keeps a zonal harmonic (axis and per-channel coefficient).
constexpr bool isZonal(IrradianceEncoding e) {
  return e == IrradianceEncoding::ZH3 || e == IrradianceEncoding::ZH3Shared ||
         e == IrradianceEncoding::ZH3Optimal || e == IrradianceEncoding::ZH3Hallucinated;
}

/// Whether the engine stores the zonal axis (zh3-shared, zh3-optimal) rather than deriving it
/// from band 1 (zh3, zh3-hallucinated).
constexpr bool storesAxis(IrradianceEncoding e) {
  return e == IrradianceEncoding::ZH3Shared || e == IrradianceEncoding::ZH3Optimal;
}

/// Whether the engine stores the zonal coefficients (every zh3 form but zh3-hallucinated, which
/// derives them from band 1).
constexpr bool storesZonal(IrradianceEncoding e) {
  return isZonal(e) && e != IrradianceEncoding::ZH3Hallucinated;
}

/// "l2", "l2-deringed", "l1", "l1-windowed", "l1-geomerics", "zh3", "zh3-shared",
/// "zh3-optimal", "zh3-hallucinated".
const char* toString(IrradianceEncoding e);
/// Parses a name above; throws prt::Error("encoding must be l1, l1-windowed, ..., got 'X'").
IrradianceEncoding parseIrradianceEncoding(const std::string& name);
/// Rows of irradiance SH kept ([r, g, b] each): 9 for l2 and l2-deringed, 4 for the others.
constexpr int shRows(IrradianceEncoding e) {
  return e == IrradianceEncoding::L2 || e == IrradianceEncoding::L2Deringed ? 9 : 4;
}
/// Numbers stored for RGB: 27, 17, 15 or 12.
int storedNumbers(IrradianceEncoding e);

/// An encoded irradiance. `sh` holds irradiance SH (E_lm = Λ_l L_lm, the project's basis and
/// order): 9 coefficients for l2 and l2-deringed, 4 for the others (windowed ones already
/// windowed). For the zh3 forms, `axis` is the zonal axis (the luminance's band-1 direction, +Z
/// when that is zero; for zh3-optimal and zh3-shared the searched one) and `zonal` each channel's
/// coefficient of the zonal harmonic Y₂₀(axis·n) in the irradiance (Λ₂ times the radiance's;
/// stored for zh3 and zh3-optimal, Λ₂ s L₀₀,c for zh3-shared, whose engine stores s alone,
/// derived from band 1 for zh3-hallucinated, where an engine derives it the same way).
struct EncodedIrradiance {
  IrradianceEncoding encoding = IrradianceEncoding::L2;
  std::vector<Rgbd> sh;
  Vec3d axis{0, 0, 1};
  Rgbd zonal{0, 0, 0};
};

}  // namespace prt::sh
