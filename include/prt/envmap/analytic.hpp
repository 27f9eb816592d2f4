#pragma once
// Analytic lights straight to SH, through zonal harmonics rotated to their direction.
//
// A function symmetric about the axis d with zonal profile h(cos γ) has coefficients
//   L_lm = 2π ∫_{-1}^{1} h(t) P_l(t) dt · Y_lm(d)
// (Funk–Hecke; the zonal coefficient z_l = 2π √((2l+1)/4π) ∫ h P_l, rotated by
// L_lm = √(4π/(2l+1)) z_l Y_lm(d); Sloan, "Stupid SH Tricks" §2.3). So:
//  * constant c:                  L_00 = √(4π) c, all else 0;
//  * directional (a delta of integrated radiance E toward d): L_lm = E Y_lm(d);
//  * spherical cap of radius α and radiance L: L_lm = 2π L ∫_{cos α}^{1} P_l(t) dt · Y_lm(d),
//    with ∫_x^1 P_0 = 1 − x and ∫_x^1 P_l = (P_{l−1}(x) − P_{l+1}(x)) / (2l + 1) for l ≥ 1
//    (from (2l+1) P_l = P'_{l+1} − P'_{l−1} and P_l(1) = 1).

#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/sh/sh.hpp"

namespace prt::envmap {

/// ∫_{cos α}^{1} P_l(t) dt for l = 0..bands-1.
std::vector<double> capLegendreIntegrals(int bands, double halfAngle);

sh::RgbSh constantSh(int bands, const Rgb& radiance);
/// A delta light: ∫ L dω = `power` concentrated along unit `direction`.
sh::RgbSh directionalSh(int bands, const Vec3f& direction, const Rgb& power);
/// A uniform cap (disc) of radiance cap.radiance.
sh::RgbSh capSh(int bands, const Cap& cap);

}  // namespace prt::envmap
