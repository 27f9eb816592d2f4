#include "prt/transfer/material.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/quadrature.hpp"
#include "prt/core/spec.hpp"

namespace prt {

namespace {

/// Angular width (radians) of the lobe's peak, to pick a quadrature step that resolves it.
double lobeWidth(const GlossyLobe& g) {
  if (g.kind == LobeKind::Phong) return 1.0 / std::sqrt(g.exponent + 1.0);
  if (g.kind == LobeKind::Ggx) return 2.0 * g.roughness * g.roughness;
  return kPi;
}

/// Calls f(t, weight) for a midpoint rule in θ over [0, π] with weight 2π sinθ dθ (the measure
/// of dω for a function of t = cos θ), fine enough to resolve the lobe (≥ 16 steps per width).
template <typename F>
void integrateOverSphere(const GlossyLobe& g, F&& f) {
  const int n = std::clamp(static_cast<int>(std::ceil(16.0 * kPi / lobeWidth(g))), 4096, 1 << 17);
  const double h = kPi / n;
  for (int k = 0; k < n; ++k) {
    const double theta = (k + 0.5) * h;
    f(std::cos(theta), 2.0 * kPi * std::sin(theta) * h);
  }
}

/// The shortest text that reads back as exactly x.
template <typename T>
std::string number(T x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string colour(const Rgb& c) {
  if (c.x == c.y && c.y == c.z) return number(c.x);
  return number(c.x) + "," + number(c.y) + "," + number(c.z);
}

}  // namespace

double GlossyLobe::value(double t) const {
  switch (kind) {
    case LobeKind::None:
      return 0.0;
    case LobeKind::Phong:
      return t > 0.0 ? (exponent + 1.0) / (2.0 * kPi) * std::pow(t, exponent) : 0.0;
    case LobeKind::Ggx: {
      const double a2 = roughness * roughness * roughness * roughness;  // α²
      const double c2 = 0.5 * (1.0 + std::clamp(t, -1.0, 1.0));         // cos² of θ/2
      const double d = c2 * (a2 - 1.0) + 1.0;
      return a2 / (kPi * d * d) / 4.0;
    }
  }
  return 0.0;
}

std::vector<double> GlossyLobe::zonal(int bands) const {
  std::vector<double> lambda(static_cast<std::size_t>(std::max(bands, 0)), 0.0);
  if (kind == LobeKind::None || bands <= 0) return lambda;
  std::vector<double> p(lambda.size());
  double norm = 0.0;
  integrateOverSphere(*this, [&](double t, double w) {
    const double gw = value(t) * w;
    norm += gw;
    legendrePolynomials(bands, t, p.data());
    for (int l = 0; l < bands; ++l) lambda[l] += gw * p[l];
  });
  // Λ_0 = ∫ G dω = 1 analytically; dividing by the quadrature's value makes it exact.
  for (double& x : lambda) x /= norm;
  return lambda;
}

double GlossyLobe::energyBeyond(int bands) const {
  if (kind == LobeKind::None) return 0.0;
  double total = 0.0, norm = 0.0;
  integrateOverSphere(*this, [&](double t, double w) {
    const double g = value(t);
    total += g * g * w;
    norm += g * w;
  });
  total /= norm * norm;  // the same normalisation as zonal()
  const std::vector<double> lambda = zonal(bands);
  double held = 0.0;
  for (int l = 0; l < bands; ++l) held += lambda[l] * lambda[l] * (2 * l + 1) / (4.0 * kPi);
  return std::clamp(1.0 - held / total, 0.0, 1.0);
}

std::string describe(const GlossyLobe& lobe) {
  switch (lobe.kind) {
    case LobeKind::None:
      return "Lambertian (no lobe)";
    case LobeKind::Phong:
      return "normalised Phong lobe (s+1)/(2 pi) cos^s about the reflected view, s = " +
             number(lobe.exponent) + " (no Fresnel)";
    case LobeKind::Ggx:
      return "GGX-shaped lobe symmetric about the reflected view: the normal-incidence GGX NDF, "
             "alpha = roughness^2 = " +
             number(lobe.roughness * lobe.roughness) +
             " (no Fresnel, masking or 1/(4 n.l n.v): not a microfacet BRDF)";
  }
  return "";
}

bool Material::glossy() const {
  return lobe.kind != LobeKind::None && (specular.x > 0 || specular.y > 0 || specular.z > 0);
}

std::string Material::spec() const {
  std::string s;
  std::string params;
  auto add = [&](const std::string& kv) { params += (params.empty() ? "?" : "&") + kv; };
  switch (lobe.kind) {
    case LobeKind::None:
      s = "lambert";
      break;
    case LobeKind::Phong:
      s = "phong";
      add("exponent=" + number(lobe.exponent));
      break;
    case LobeKind::Ggx:
      s = "ggx";
      add("roughness=" + number(lobe.roughness));
      break;
  }
  if (lobe.kind != LobeKind::None) add("ks=" + colour(specular));
  if (diffuse) add("kd=" + colour(*diffuse));
  return s + params;
}

void checkMaterial(const Material& m) {
  const auto colourIn01 = [&](const Rgb& c, const char* what) {
    for (int i = 0; i < 3; ++i)
      if (!(c[i] >= 0.0f && c[i] <= 1.0f))
        throw Error("material " + m.spec() + ": " + what + " = " + colour(c) +
                    " is outside 0..1 (each component)");
  };
  if (m.diffuse) colourIn01(*m.diffuse, "kd");
  if (m.lobe.kind != LobeKind::None) colourIn01(m.specular, "ks");
  if (m.lobe.kind == LobeKind::Phong &&
      !(m.lobe.exponent >= 0 && m.lobe.exponent <= kMaxPhongExponent))
    throw Error("material " + m.spec() + ": the Phong exponent must lie in 0.." +
                number(kMaxPhongExponent));
  if (m.lobe.kind == LobeKind::Ggx &&
      !(m.lobe.roughness >= kMinGgxRoughness && m.lobe.roughness <= 1.0))
    throw Error("material " + m.spec() + ": the GGX roughness must lie in " +
                number(kMinGgxRoughness) + "..1");
}

Material parseMaterial(const std::string& text) {
  Spec spec(text);
  Material m;
  const std::string& name = spec.name();
  if (name == "lambert" || name == "diffuse") {
    m.lobe.kind = LobeKind::None;
  } else if (name == "phong") {
    m.lobe.kind = LobeKind::Phong;
    m.lobe.exponent = spec.number("exponent", kDefaultPhongExponent, 0.0, kMaxPhongExponent);
    m.specular = spec.colour("ks", Rgb(kDefaultSpecular), 0.0, 1.0);
  } else if (name == "ggx") {
    m.lobe.kind = LobeKind::Ggx;
    m.lobe.roughness = spec.number("roughness", kDefaultGgxRoughness, kMinGgxRoughness, 1.0);
    m.specular = spec.colour("ks", Rgb(kDefaultSpecular), 0.0, 1.0);
  } else {
    throw Error(text, "unknown material '" + name + "' (known: lambert, phong, ggx)");
  }
  const Rgb kd = spec.colour("kd", Rgb(1.0f), 0.0, 1.0);
  if (spec.has("kd")) m.diffuse = kd;
  spec.finish();
  return m;
}

}  // namespace prt
