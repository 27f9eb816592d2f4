#pragma once
// A procedural clear sky with sun: Preetham, Shirley & Smits, "A Practical Analytic Model for
// Daylight", SIGGRAPH 1999 (Perez et al. 1993 luminance distribution, zenith luminance and
// chromaticity fits of their appendix A.2, CIE xyY → XYZ → linear Rec. 709 RGB).
//
// Frame: +Y up. The sun direction from elevation e and azimuth a (degrees):
//   (cos e sin a, sin e, −cos e cos a)   — azimuth 0 looks along −Z, 90 along +X.
// Units: the sky is scaled so that its zenith luminance equals `skyScale` (1 by default). The
// sun is a uniform disc of angular radius `sunRadiusDeg` whose integrated radiance ∫ L dω is
// `sunPower` (luminance units × sr) above the atmosphere, times a per-channel transmittance
// exp(−τ_λ m) with the Kasten–Young (1989) air mass m and τ = (0.1, 0.2, 0.4)·turbidity/3 (our
// rough approximation, not part of Preetham's model). The disc vanishes below the horizon. Below
// the horizon the model is undefined: we return the horizon's sky radiance of the same azimuth
// times `groundAlbedo` (a dim ground).

#include "prt/envmap/environment.hpp"

namespace prt::envmap {

struct SkyParams {
  double turbidity = 3.0;      ///< 1.7 .. 10
  double elevationDeg = 30.0;  ///< sun elevation above the horizon
  double azimuthDeg = 120.0;   ///< sun azimuth (see above)
  double skyScale = 1.0;       ///< zenith luminance
  double sunPower = 20.0;      ///< ∫ L dω over the sun disc (luminance)
  double sunRadiusDeg = 0.5;   ///< angular radius of the disc (the real sun: 0.27°)
  double groundAlbedo = 0.3;
};

class PreethamSky {
 public:
  explicit PreethamSky(const SkyParams& p);
  /// Sky radiance without the sun disc.
  Rgb sky(const Vec3f& dir) const;
  Vec3f sunDirection() const { return sun_; }
  /// The sun disc as a cap.
  Cap sunCap() const;

 private:
  SkyParams p_;
  Vec3f sun_;
  double thetaS_;
  double coef_[3][5];  // Perez A..E for Y, x, y
  double zenith_[3];   // Y_z, x_z, y_z
  double norm_[3];     // F(0, θs) per channel
  double scale_;
  double perez(int c, double cosTheta, double gamma) const;
};

}  // namespace prt::envmap
