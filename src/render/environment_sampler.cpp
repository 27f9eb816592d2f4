#include "prt/render/environment_sampler.hpp"

// The reference's environment: texel footprints and solid angles from envmap/layout.hpp, an
// alias table (Vose 1991) over lum_k ΔΩ_k for sampling, and the density within a texel for MIS.

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/image/color.hpp"

namespace prt::render {

using envmap::Environment;

// ---------------------------------------------------------------------------------------------
// EnvironmentSampler

EnvironmentSampler::EnvironmentSampler(const Environment& env) : env_(env) {
  const std::size_t n = env.texelCount();
  if (n == 0) throw Error("environment has no texels");
  if (n >= (std::size_t(1) << 32)) throw Error("environment has too many texels to sample");
  texels_.resize(n);
  direction_.resize(n);
  solidAngle_.resize(n);
  std::vector<double> prob(n);
  double sum = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const envmap::Texel t = env.texel(k);
    texels_[k].radiance = t.radiance;
    direction_[k] = t.direction;
    solidAngle_[k] = t.solidAngle;
    // |luminance|: an environment may be signed (validation's residual L − L_b); sampling by
    // magnitude keeps the estimator unbiased and is the same for every non-negative one.
    const double w = std::abs(image::luminance(t.radiance)) * env.texelSolidAngle(k);
    prob[k] = std::isfinite(w) ? w : 0.0;
    sum += prob[k];
  }
  total_ = sum;
  alias_.resize(n);
  if (total_ <= 0) return;
  for (std::size_t k = 0; k < n; ++k) {
    prob[k] /= total_;
    texels_[k].prob = static_cast<float>(prob[k]);
  }

  // Vose: scaled probabilities n P_k; pair each "small" (< 1) with a "large" (≥ 1) one. Both
  // work lists are filled in index order and drained from the back, so the table is a pure
  // function of the environment.
  std::vector<double> scaled(n);
  std::vector<std::uint32_t> small, large;
  for (std::size_t k = 0; k < n; ++k) {
    scaled[k] = prob[k] * static_cast<double>(n);
    (scaled[k] < 1.0 ? small : large).push_back(static_cast<std::uint32_t>(k));
  }
  while (!small.empty() && !large.empty()) {
    const std::uint32_t s = small.back(), l = large.back();
    small.pop_back();
    alias_[s] = {static_cast<float>(scaled[s]), l};
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What is left holds probability 1 up to rounding: it keeps itself. A texel of zero
  // probability can be left only through rounding; it forwards to the most probable texel.
  const auto best =
      static_cast<std::uint32_t>(std::max_element(prob.begin(), prob.end()) - prob.begin());
  for (std::uint32_t l : large) alias_[l] = {1.0f, l};
  for (std::uint32_t s : small)
    alias_[s] = prob[s] > 0 ? AliasEntry{1.0f, s} : AliasEntry{0.0f, best};
  for (AliasEntry& a : alias_)
    if (a.accept < 1.0f && texels_[a.alias].prob == 0.0f) a.alias = best;
}

std::size_t EnvironmentSampler::texelOf(const Vec3f& dir) const {
  const auto& imgs = env_.images();
  switch (env_.kind()) {
    case Environment::Kind::LatLong:
    case Environment::Kind::Analytic: {
      const int w = imgs[0].width, h = imgs[0].height;
      float px, py;
      envmap::latLongPixel(dir, w, h, px, py);
      const int x = std::clamp(static_cast<int>(std::floor(px)), 0, w - 1);
      const int y = std::clamp(static_cast<int>(std::floor(py)), 0, h - 1);
      return static_cast<std::size_t>(y) * w + x;
    }
    case Environment::Kind::Cube: {
      const int n = imgs[0].width;
      float s, t;
      const int face = envmap::cubeFaceCoords(dir, s, t);
      const int x = std::clamp(static_cast<int>(std::floor((s + 1) * 0.5f * n)), 0, n - 1);
      const int y = std::clamp(static_cast<int>(std::floor((t + 1) * 0.5f * n)), 0, n - 1);
      return static_cast<std::size_t>(face) * n * n + static_cast<std::size_t>(y) * n + x;
    }
    case Environment::Kind::Probe: {
      // Inverse of the angular map (layout.hpp): r = angle to −Z / π, (a, b) = r (x, y)/|(x, y)|.
      const int w = imgs[0].width, h = imgs[0].height;
      const double len = length(Vec3d(dir));
      const double dx = dir.x / len, dy = dir.y / len, dz = dir.z / len;
      const double rho = std::sqrt(dx * dx + dy * dy);
      const double r = std::acos(std::clamp(-dz, -1.0, 1.0)) / kPi;
      const double a = rho > 0 ? dx * r / rho : 0, b = rho > 0 ? dy * r / rho : 0;
      const int x = std::clamp(static_cast<int>(std::floor((a + 1) * 0.5 * w)), 0, w - 1);
      const int y = std::clamp(static_cast<int>(std::floor((1 - b) * 0.5 * h)), 0, h - 1);
      return static_cast<std::size_t>(y) * w + x;
    }
  }
  return npos;
}

// Density (per steradian) of a point drawn uniformly in texel k's parametrisation:
//  * lat-long: uniform in φ and in cos θ, which is uniform in solid angle: 1/ΔΩ_k;
//  * cube: uniform in (s, t) over a texel of area (2/N)²; at unit distance the face point
//    (s, t) subtends dω = dA / (1 + s² + t²)^{3/2}, so q = (1 + s² + t²)^{3/2} / (2/N)²;
//  * probe: uniform in (a, b) over a texel of area (2/W)(2/H); dω = π sin(πr)/r dA, so
//    q = r / (π sin(πr)) / ((2/W)(2/H)).
double EnvironmentSampler::densityWithin(std::size_t k, const Vec3f& dir) const {
  const auto& imgs = env_.images();
  switch (env_.kind()) {
    case Environment::Kind::LatLong:
    case Environment::Kind::Analytic:
      return 1.0 / env_.texelSolidAngle(k);
    case Environment::Kind::Cube: {
      const double n = imgs[0].width;
      float s, t;
      envmap::cubeFaceCoords(dir, s, t);
      const double q = 1.0 + double(s) * s + double(t) * t;
      return q * std::sqrt(q) * (n * n / 4.0);
    }
    case Environment::Kind::Probe: {
      const double w = imgs[0].width, h = imgs[0].height;
      const double len = length(Vec3d(dir));
      const double r = std::acos(std::clamp(-double(dir.z) / len, -1.0, 1.0)) / kPi;
      const double sinPr = std::sin(kPi * r);
      const double jac = r < 1e-6 ? 1.0 / (kPi * kPi) : (sinPr > 0 ? r / (kPi * sinPr) : 0.0);
      return jac * (w * h / 4.0);
    }
  }
  return 0;
}

Rgb EnvironmentSampler::radiance(const Vec3f& dir) const {
  const std::size_t k = texelOf(dir);
  return k == npos ? Rgb(0.0f) : texels_[k].radiance;
}

double EnvironmentSampler::pdf(const Vec3f& dir) const {
  double p = 0;
  lookup(dir, p);
  return p;
}

Rgb EnvironmentSampler::lookup(const Vec3f& dir, double& pdf) const {
  pdf = 0;
  const std::size_t k = texelOf(dir);
  if (k == npos) return Rgb(0.0f);
  const TexelEntry& t = texels_[k];
  if (total_ > 0 && t.prob > 0) pdf = t.prob * densityWithin(k, dir);
  return t.radiance;
}

bool EnvironmentSampler::sample(double u0, float u1, float u2, Vec3f& dir, double& pdf,
                                Rgb& radiance) const {
  if (total_ <= 0) return false;
  // The alias table: column j = ⌊u0 n⌋, kept on the fraction of u0 n below accept_[j].
  const double un = u0 * static_cast<double>(alias_.size());
  const std::size_t j = std::min(static_cast<std::size_t>(un), alias_.size() - 1);
  const AliasEntry a = alias_[j];
  const std::size_t k = un - static_cast<double>(j) < a.accept ? j : a.alias;
  const auto& imgs = env_.images();
  switch (env_.kind()) {
    case Environment::Kind::LatLong:
    case Environment::Kind::Analytic: {
      const int w = imgs[0].width, h = imgs[0].height;
      const std::size_t y = k / w, x = k % w;
      const double phi = 2 * kPi * ((x + double(u1)) / w - 0.5);
      const double c0 = std::cos(kPi * y / h), c1 = std::cos(kPi * (y + 1) / h);
      const double ct = c0 + (c1 - c0) * u2, st = std::sqrt(std::max(0.0, 1 - ct * ct));
      dir = Vec3f(Vec3d(st * std::cos(phi), ct, st * std::sin(phi)));
      break;
    }
    case Environment::Kind::Cube: {
      const int n = imgs[0].width;
      const int face = static_cast<int>(k / (static_cast<std::size_t>(n) * n));
      const std::size_t r = k % (static_cast<std::size_t>(n) * n);
      const double s = 2.0 * (r % n + double(u1)) / n - 1, t = 2.0 * (r / n + double(u2)) / n - 1;
      dir = Vec3f(normalize(envmap::cubeFaceDirection(face, s, t)));
      break;
    }
    case Environment::Kind::Probe: {
      const int w = imgs[0].width, h = imgs[0].height;
      const double a = 2.0 * (k % w + double(u1)) / w - 1, b = 1 - 2.0 * (k / w + double(u2)) / h;
      bool inside = false;
      const Vec3d d = envmap::probeDirection(a, b, &inside);
      if (!inside) return false;
      dir = Vec3f(normalize(d));
      break;
    }
  }
  // The point may fall in a neighbour by rounding: evaluate pdf and radiance where it landed,
  // so sample and lookup stay one function.
  radiance = lookup(dir, pdf);
  return pdf > 0;
}

Rgb EnvironmentSampler::irradianceQuadrature(const Vec3f& n, const Mat3d& rotation) const {
  // n · (R ω) = (Rᵀ n) · ω.
  const Vec3f m = Vec3f(rotation.transposed() * Vec3d(n));
  double r = 0, g = 0, b = 0;
  for (std::size_t k = 0; k < texels_.size(); ++k) {
    const float c = dot(m, direction_[k]);
    if (c <= 0) continue;
    const double w = double(c) * solidAngle_[k];
    const Rgb& l = texels_[k].radiance;
    r += w * l.x;
    g += w * l.y;
    b += w * l.z;
  }
  return Rgb(Vec3d(r, g, b));
}

}  // namespace prt::render
