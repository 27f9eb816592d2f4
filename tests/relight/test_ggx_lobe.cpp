// The `ggx` lobe (prt/transfer/material.hpp) against a standard microfacet BRDF: Walter,
// Marschner, Li & Torrance, "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007
// — GGX D (eq. 33), separable Smith G = G1(l) G1(v) with the GGX G1 (eq. 34), Schlick's Fresnel
// with F0 = ks, and the 1/(4 n·l n·v) of the microfacet BRDF, times n·l. prtkit's lobe is the
// normal-incidence GGX shape made symmetric about the reflected view: the two agree at normal
// incidence and part toward grazing views. The test measures by how much (the figures that
// docs/transport.md quotes) and, with PRT_UPDATE_DOC_FIGURES=1, draws docs/images/ggx-lobe.png:
// polar plots in the plane of incidence at view angles 0°, 45° and 70°, roughness 0.3.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "prt/image/image.hpp"
#include "prt/image/image_io.hpp"
#include "prt/transfer/material.hpp"

namespace prt {
namespace {

/// Walter et al. 2007's GGX microfacet BRDF times n·l, n = +Z, for unit l and v above the
/// surface: the kernel that multiplies incident radiance, comparable with ks·G(r·l).
double microfacetKernel(double roughness, double f0, const Vec3d& l, const Vec3d& v) {
  const double nl = l.z, nv = v.z;
  if (nl <= 0 || nv <= 0) return 0;
  const double a2 = std::pow(roughness, 4.0);  // α², α = roughness² as in the ggx spec
  const Vec3d h = normalize(l + v);
  const double c2 = h.z * h.z, d = c2 * (a2 - 1) + 1;
  const double D = a2 / (kPi * d * d);
  const auto g1 = [a2](double c) { return 2 * c / (c + std::sqrt(a2 + (1 - a2) * c * c)); };
  const double F = f0 + (1 - f0) * std::pow(1 - dot(l, h), 5.0);
  return F * D * g1(nl) * g1(nv) / (4 * nl * nv) * nl;
}

/// Direction in the plane of incidence (x, z) at signed angle θ from +Z (θ > 0 toward +x).
Vec3d inPlane(double theta) {
  return {std::sin(theta), 0.0, std::cos(theta)};
}

struct Comparison {
  double peakLobe = 0, peakMicrofacet = 0;      ///< maxima over the plane of incidence
  double peakAngleMicrofacet = 0;               ///< where the microfacet kernel peaks (degrees)
  double albedoLobe = 0, albedoMicrofacet = 0;  ///< ∫ over the hemisphere of each kernel
};

/// The view at θ_v on the −x side, so its reflection r lies at +θ_v.
Comparison compare(double roughness, double ks, double viewDeg) {
  const Material m =
      parseMaterial("ggx?roughness=" + std::to_string(roughness) + "&ks=" + std::to_string(ks));
  const double tv = viewDeg * kPi / 180;
  const Vec3d v = inPlane(-tv), r = inPlane(tv);
  Comparison c;
  const int n = 20000;
  for (int k = 0; k <= n; ++k) {
    const double t = -kPi / 2 + kPi * k / n;
    const Vec3d l = inPlane(t);
    const double a = ks * m.lobe.value(dot(r, l)), b = microfacetKernel(roughness, ks, l, v);
    c.peakLobe = std::max(c.peakLobe, a);
    if (b > c.peakMicrofacet) {
      c.peakMicrofacet = b;
      c.peakAngleMicrofacet = t * 180 / kPi;
    }
  }
  // Hemisphere integrals: midpoint rule in (θ, φ), fine enough for roughness 0.3.
  const int nt = 1200, np = 1200;
  for (int i = 0; i < nt; ++i) {
    const double th = (i + 0.5) * (kPi / 2) / nt;
    for (int j = 0; j < np; ++j) {
      const double ph = (j + 0.5) * 2 * kPi / np;
      const Vec3d l(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      const double w = std::sin(th) * (kPi / 2 / nt) * (2 * kPi / np);
      c.albedoLobe += ks * m.lobe.value(dot(r, l)) * w;
      c.albedoMicrofacet += microfacetKernel(roughness, ks, l, v) * w;
    }
  }
  return c;
}

// The polar plots: three panels (view 0°, 45°, 70°), each scaled to its larger curve; the
// surface is the horizontal line, the view the grey ray on the left, prtkit's lobe orange
// (thick, drawn first), Walter et al.'s BRDF × cos blue (thin, on top: where they agree, a blue
// line inside an orange one).
image::Image drawFigure(double roughness, double ks) {
  const int pw = 320, ph = 190, r0 = 160;
  image::Image img(3 * pw, ph, Rgb(1.0f));
  const auto plot = [&](int x, int y, const Rgb& c, int thick) {
    for (int dy = -thick; dy <= thick; ++dy)
      for (int dx = -thick; dx <= thick; ++dx)
        if (x + dx >= 0 && x + dx < img.width && y + dy >= 0 && y + dy < img.height)
          img.at(x + dx, y + dy) = c;
  };
  const auto line = [&](double x0, double y0, double x1, double y1, const Rgb& c, int thick) {
    const int steps = static_cast<int>(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
    for (int s = 0; s <= steps; ++s) {
      const double f = double(s) / steps;
      plot(static_cast<int>(std::lround(x0 + f * (x1 - x0))),
           static_cast<int>(std::lround(y0 + f * (y1 - y0))), c, thick);
    }
  };
  const Rgb grey(0.6f), orange(1.0f, 0.35f, 0.02f), blue(0.02f, 0.2f, 0.9f);
  const Material m =
      parseMaterial("ggx?roughness=" + std::to_string(roughness) + "&ks=" + std::to_string(ks));
  const double views[] = {0.0, 45.0, 70.0};
  for (int p = 0; p < 3; ++p) {
    const double cx = p * pw + pw / 2.0, cy = ph - 15.0;
    const double tv = views[p] * kPi / 180;
    const Vec3d v = inPlane(-tv), r = inPlane(tv);
    const Comparison c = compare(roughness, ks, views[p]);
    const double scale = r0 / std::max(c.peakLobe, c.peakMicrofacet);
    line(cx - r0, cy, cx + r0, cy, grey, 0);                          // the surface
    line(cx, cy, cx + r0 * v.x, cy - r0 * v.z, grey, 1);              // the view
    line(cx, cy, cx + r0 * r.x * 0.3, cy - r0 * r.z * 0.3, grey, 0);  // the reflection, short
    for (int curve = 0; curve < 2; ++curve) {
      double px = cx, py = cy;
      const int n = 3000;
      for (int k = 0; k <= n; ++k) {
        const double t = -kPi / 2 + kPi * k / n;
        const Vec3d l = inPlane(t);
        const double f =
            curve == 0 ? ks * m.lobe.value(dot(r, l)) : microfacetKernel(roughness, ks, l, v);
        const double x = cx + scale * f * l.x, y = cy - scale * f * l.z;
        if (k > 0) line(px, py, x, y, curve == 0 ? orange : blue, curve == 0 ? 2 : 1);
        px = x;
        py = y;
      }
    }
  }
  return img;
}

// At normal incidence the two kernels share their peak exactly (F = F0 = ks, G1(n) = 1, and the
// lobe is D(θ/2)/4 there by construction); toward grazing views the microfacet BRDF's peak
// grows, through 1/(4 n·l n·v), masking and Fresnel, while the lobe keeps its shape (only its
// clipped part grows). The figures docs/transport.md quotes, roughness 0.3, peak ratio
// microfacet / lobe at 45° and 70°: 1.41 and 2.84 for F0 = ks = 1 (the shape alone: Schlick's
// Fresnel is 1), 1.41 and 3.19 for 0.5, 1.48 and 11.5 for 0.04; hemisphere albedo at 70°
// 0.942 against 0.955 for F0 = 1 (the same energy, differently spread), 0.038 against 0.139
// for 0.04 (Fresnel).
TEST(Material, GgxLobeAgainstAWalterMicrofacetBrdf) {
  struct Expected {
    double ks, ratio45, ratio70;
  };
  for (const Expected& e :
       {Expected{1.0, 1.409, 2.838}, Expected{0.5, 1.412, 3.189}, Expected{0.04, 1.482, 11.55}}) {
    for (double view : {0.0, 45.0, 70.0}) {
      const Comparison c = compare(0.3, e.ks, view);
      const double ratio = c.peakMicrofacet / c.peakLobe;
      std::printf(
          "ks = F0 = %.2f, view %2.0f deg: peak microfacet/lobe %.3f (microfacet peak at %.1f "
          "deg, lobe at %.1f); hemisphere albedo lobe %.4f microfacet %.4f\n",
          e.ks, view, ratio, c.peakAngleMicrofacet, view, c.albedoLobe, c.albedoMicrofacet);
      const double expected = view == 0.0 ? 1.0 : view == 45.0 ? e.ratio45 : e.ratio70;
      EXPECT_NEAR(ratio, expected, 0.005 * expected) << e.ks << " " << view;
    }
  }
  const char* update = std::getenv("PRT_UPDATE_DOC_FIGURES");
  if (update && std::string(update) == "1") {
    image::WriteOptions o;
    o.toneMap = image::ToneMap::Clamp;
    const std::string path = std::string(PRT_SOURCE_DIR) + "/docs/images/ggx-lobe.png";
    image::writeImage(path, drawFigure(0.3, 0.5), o);
    std::printf("wrote %s\n", path.c_str());
  }
}

}  // namespace
}  // namespace prt
