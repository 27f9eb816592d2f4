#include "prt/envmap/sky.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"

namespace prt::envmap {

PreethamSky::PreethamSky(const SkyParams& p) : p_(p) {
  if (!(p.turbidity >= 1.0 && p.turbidity <= 20.0)) throw Error("sky turbidity must be in 1..20");
  if (!(p.elevationDeg >= -90 && p.elevationDeg <= 90))
    throw Error("sky elevation must be in -90..90 degrees");
  if (!(p.sunRadiusDeg > 0 && p.sunRadiusDeg < 90))
    throw Error("sun size must be in (0, 90) degrees");
  if (!(p.sunPower >= 0 && p.skyScale >= 0 && p.groundAlbedo >= 0))
    throw Error("sky intensities must be >= 0");
  const double e = p.elevationDeg * kPi / 180, a = p.azimuthDeg * kPi / 180;
  sun_ = Vec3f(Vec3d(std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a)));
  // Preetham's fits hold for the sun above the horizon; clamp just above it.
  thetaS_ = std::min(kPi / 2 - e, kPi / 2 - 0.01);
  const double T = p.turbidity;
  const double perezY[5] = {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251,
                            0.1206 * T - 2.5771, -0.0670 * T + 0.3703};
  const double perezX[5] = {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125,
                            -0.0641 * T - 0.8989, -0.0033 * T + 0.0452};
  const double perezy[5] = {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102,
                            -0.0441 * T - 1.6537, -0.0109 * T + 0.0529};
  for (int i = 0; i < 5; ++i) {
    coef_[0][i] = perezY[i];
    coef_[1][i] = perezX[i];
    coef_[2][i] = perezy[i];
  }
  const double ts = thetaS_, ts2 = ts * ts, ts3 = ts2 * ts, T2 = T * T;
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2 * ts);
  zenith_[0] = (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
  zenith_[1] = T2 * (0.00166 * ts3 - 0.00375 * ts2 + 0.00209 * ts) +
               T * (-0.02903 * ts3 + 0.06377 * ts2 - 0.03202 * ts + 0.00394) +
               (0.11693 * ts3 - 0.21196 * ts2 + 0.06052 * ts + 0.25886);
  zenith_[2] = T2 * (0.00275 * ts3 - 0.00610 * ts2 + 0.00317 * ts) +
               T * (-0.04214 * ts3 + 0.08970 * ts2 - 0.04153 * ts + 0.00516) +
               (0.15346 * ts3 - 0.26756 * ts2 + 0.06670 * ts + 0.26688);
  for (int c = 0; c < 3; ++c) norm_[c] = perez(c, 1.0, ts);
  scale_ = zenith_[0] > 0 ? p.skyScale / zenith_[0] : 0.0;
}

double PreethamSky::perez(int c, double cosTheta, double gamma) const {
  const double* k = coef_[c];
  const double cg = std::cos(gamma);
  return (1 + k[0] * std::exp(k[1] / std::max(cosTheta, 1e-3))) *
         (1 + k[2] * std::exp(k[3] * gamma) + k[4] * cg * cg);
}

Rgb PreethamSky::sky(const Vec3f& dirIn) const {
  Vec3d d = normalize(Vec3d(dirIn));
  double factor = 1.0;
  if (d.y < 0) {  // below the horizon: the horizon of the same azimuth, dimmed
    d.y = 0;
    factor = p_.groundAlbedo;
    const double h = std::hypot(d.x, d.z);
    d = h > 0 ? Vec3d(d.x / h, 0, d.z / h) : Vec3d(1, 0, 0);
  }
  const double cosTheta = std::max(d.y, 0.0);
  // Sun direction with the clamped zenith angle (matches the fits above).
  const double h = std::hypot(static_cast<double>(sun_.x), static_cast<double>(sun_.z));
  const Vec3d sunDir = h > 0 ? Vec3d(std::sin(thetaS_) * sun_.x / h, std::cos(thetaS_),
                                     std::sin(thetaS_) * sun_.z / h)
                             : Vec3d(0, 1, 0);
  const double gamma = std::acos(std::clamp(dot(d, sunDir), -1.0, 1.0));
  const double Y = zenith_[0] * perez(0, cosTheta, gamma) / norm_[0] * scale_ * factor;
  const double x = zenith_[1] * perez(1, cosTheta, gamma) / norm_[1];
  const double y = zenith_[2] * perez(2, cosTheta, gamma) / norm_[2];
  if (!(y > 0) || !(Y > 0)) return Rgb(0.0f);
  const double X = x / y * Y, Z = (1 - x - y) / y * Y;
  // CIE XYZ → linear Rec. 709 (D65).
  const double r = 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z;
  const double g = -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z;
  const double b = 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z;
  return {static_cast<float>(std::max(r, 0.0)), static_cast<float>(std::max(g, 0.0)),
          static_cast<float>(std::max(b, 0.0))};
}

Cap PreethamSky::sunCap() const {
  Cap c;
  c.direction = sun_;
  c.halfAngle = p_.sunRadiusDeg * kPi / 180;
  const double solid = 2 * kPi * (1 - std::cos(c.halfAngle));
  // Extinction tint: Kasten & Young (1989) relative air mass at the sun's zenith angle.
  const double zenithDeg = std::min(90.0 - p_.elevationDeg, 90.0);
  const double m =
      1.0 / (std::cos(zenithDeg * kPi / 180) + 0.50572 * std::pow(96.07995 - zenithDeg, -1.6364));
  const double tau[3] = {0.1, 0.2, 0.4};
  Rgb tint;
  for (int i = 0; i < 3; ++i)
    (&tint.x)[i] = static_cast<float>(std::exp(-tau[i] * p_.turbidity / 3.0 * m));
  // sunPower is the power outside the atmosphere; the tint is the transmittance per channel.
  c.radiance = p_.elevationDeg > -p_.sunRadiusDeg ? tint * static_cast<float>(p_.sunPower / solid)
                                                  : Rgb(0.0f);
  return c;
}

}  // namespace prt::envmap
