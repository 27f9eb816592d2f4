#include "prt/render/reference.hpp"

// Brute-force Monte Carlo reference for PRT (see the header for the integral and the
// estimator). Multiple importance sampling: Veach & Guibas, SIGGRAPH 1995; Veach's thesis
// (1997) §9.2 for the balance and power heuristics. Sampling the GGX distribution of normals:
// Walter, Marschner, Li & Torrance, "Microfacet Models for Refraction through Rough Surfaces",
// EGSR 2007, eq. 35–36 (tan² θ_h = α² u/(1 − u) draws h with density D(h) cos θ_h).

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/quadrature.hpp"
#include "prt/envmap/layout.hpp"
#include "prt/image/color.hpp"
#include "prt/sh/convolve.hpp"

namespace prt::render {

using envmap::Environment;

// ---------------------------------------------------------------------------------------------
// ReferenceIntegrator

/// A path's radiance under the environment L (`full`) and under each band-limited light L_b
/// (`band[k]`, k < n). Every operation the estimators apply to a radiance acts on all lanes
/// alike, and `full` sees exactly the operations an Rgb would, so it is the plain estimate bit
/// for bit. Entries from n on are zero, so a default Lanes is the zero of any width.
struct ReferenceIntegrator::Lanes {
  Rgb full;
  int n = 0;
  std::array<Rgb, sh::kMaxBands> band{};

  Lanes& operator+=(const Lanes& o) {
    full += o.full;
    for (int k = 0; k < o.n; ++k) band[k] += o.band[k];
    n = std::max(n, o.n);
    return *this;
  }
  friend Lanes operator*(const Lanes& a, float s) {
    Lanes r;
    r.full = a.full * s;
    r.n = a.n;
    for (int k = 0; k < a.n; ++k) r.band[k] = a.band[k] * s;
    return r;
  }
  friend Lanes operator*(const Rgb& c, const Lanes& a) {
    Lanes r;
    r.full = c * a.full;
    r.n = a.n;
    for (int k = 0; k < a.n; ++k) r.band[k] = c * a.band[k];
    return r;
  }
};

/// The band limits, ready for the lanes: per band l the light's coefficients, per lane k the
/// factor of band l (the window, 0 from b_k on), and the zonal coefficients of the kernels.
struct ReferenceIntegrator::BandLimitData {
  int lanes = 0;
  int lightBands = 0;          ///< max b_k: the bands evaluated at an escape
  std::vector<Rgbd> light;     ///< L_i, i < lightBands²
  std::vector<double> factor;  ///< [k·lightBands + l]
  std::vector<int> laneBands;  ///< b_k
  bool truncateKernel = false;
  bool wholeSphere = false;      ///< K − K_b over the whole sphere (a probe's), not n's side
  std::vector<double> cosCoef;   ///< (A_l/π)(2l+1)/(4π): K_b's cosine part is Σ_l c_l P_l(n·ω)
  std::vector<double> lobeCoef;  ///< Λ_l (2l+1)/(4π): its lobe part Σ_l g_l P_l(r·ω)
};

ReferenceIntegrator::ReferenceIntegrator(const Mesh& mesh, const Occluder& occluder,
                                         const EnvironmentSampler& sampler,
                                         const ReferenceSettings& settings)
    : mesh_(mesh),
      albedo_(mesh.hasAlbedo() || mesh.baseColour ? albedoAtVertices(mesh) : std::vector<Rgb>()),
      occluder_(occluder),
      sampler_(sampler),
      settings_(settings),
      rotT_(settings.rotation.transposed()) {
  settings_.vertices.clear();
  if (!settings_.bandLimit) return;
  const BandLimitSettings& bl = *settings_.bandLimit;
  if (bl.limits.empty() || bl.limits.size() > std::size_t(sh::kMaxBands))
    throw Error("band-limited reference: 1 to " + std::to_string(sh::kMaxBands) +
                " band limits (got " + std::to_string(bl.limits.size()) + ")");
  auto d = std::make_shared<BandLimitData>();
  d->lanes = static_cast<int>(bl.limits.size());
  for (const BandLimit& b : bl.limits) {
    if (b.bands < 1 || b.bands > bl.light.bands)
      throw Error("band-limited reference: " + std::to_string(b.bands) + " bands, the light has " +
                  std::to_string(bl.light.bands));
    if (b.window.size() > std::size_t(b.bands))
      throw Error("band-limited reference: a window longer than its band count");
    d->lightBands = std::max(d->lightBands, b.bands);
    d->laneBands.push_back(b.bands);
  }
  const int nb = d->lightBands;
  d->light.resize(std::size_t(nb) * nb);
  for (std::size_t i = 0; i < d->light.size(); ++i) d->light[i] = Rgbd(bl.light.c[i]);
  d->factor.assign(std::size_t(d->lanes) * nb, 0.0);
  for (int k = 0; k < d->lanes; ++k)
    for (int l = 0; l < bl.limits[k].bands; ++l)
      d->factor[std::size_t(k) * nb + l] =
          std::size_t(l) < bl.limits[k].window.size() ? bl.limits[k].window[l] : 1.0;
  d->truncateKernel = bl.truncateKernel;
  d->wholeSphere = bl.wholeSphere;
  if (d->truncateKernel) {
    const std::vector<double> a = sh::clampedCosineKernel(nb);
    const std::vector<double> lambda = settings_.material.lobe.zonal(nb);
    for (int l = 0; l < nb; ++l) {
      const double addition = (2 * l + 1) / (4 * kPi);  // Σ_m Y_lm(a) Y_lm(b) = that × P_l(a·b)
      d->cosCoef.push_back(a[l] / kPi * addition);
      d->lobeCoef.push_back(lambda[l] * addition);
    }
  }
  band_ = std::move(d);
}

double ReferenceIntegrator::misWeight(double pa, double pb, double pc) const {
  if (settings_.heuristic == MisHeuristic::Balance) return pa / (pa + pb + pc);
  return pa * pa / (pa * pa + pb * pb + pc * pc);
}

Rgb ReferenceIntegrator::hitAlbedo(std::uint32_t tri, float u, float v) const {
  if (settings_.material.diffuse) return *settings_.material.diffuse;
  if (albedo_.empty()) return Rgb(1.0f);
  const auto& t = mesh_.triangles[tri];
  return albedo_[t[0]] * (1.0f - u - v) + albedo_[t[1]] * u + albedo_[t[2]] * v;
}

namespace {

/// A double in [0, 1) from 53 random bits, so texels of tiny probability are reachable.
double uniform53(Pcg32& rng) {
  const std::uint64_t hi = rng.next() >> 5, lo = rng.next() >> 6;  // 27 + 26 bits
  return double((hi << 26) | lo) * 0x1p-53;
}

}  // namespace

template <>
Rgb ReferenceIntegrator::sky<Rgb>(const Vec3f&, const Rgb& texel) const {
  return texel;
}

// L_b(d) = Σ_{l<b} w_l Σ_m L_lm Y_lm(d): the SH once at the largest b, per band its sum over m,
// then each lane's weighted sum over bands.
template <>
ReferenceIntegrator::Lanes ReferenceIntegrator::sky<ReferenceIntegrator::Lanes>(
    const Vec3f& envDir, const Rgb& texel) const {
  const BandLimitData& b = *band_;
  std::array<float, sh::kMaxBands * sh::kMaxBands> y;
  sh::eval(b.lightBands, envDir, y.data());
  std::array<Rgbd, sh::kMaxBands> perBand;
  for (int l = 0; l < b.lightBands; ++l) {
    Rgbd s(0.0);
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) s += b.light[i] * double(y[i]);
    perBand[l] = s;
  }
  Lanes r;
  r.full = texel;
  r.n = b.lanes;
  for (int k = 0; k < b.lanes; ++k) {
    Rgbd s(0.0);
    const double* f = &b.factor[std::size_t(k) * b.lightBands];
    for (int l = 0; l < b.laneBands[k]; ++l) s += perBand[l] * f[l];
    r.band[k] = Rgb(s);
  }
  return r;
}

// One environment direction w (world, the environment turned by the rotation; envDir before
// the turn) with its density pe and radiance le, from three draws of rng; false where the
// environment has no light.
bool ReferenceIntegrator::sampleEnvironment(Pcg32& rng, Vec3f& w, Vec3f& envDir, double& pe,
                                            Rgb& le) const {
  const double u0 = uniform53(rng);
  const float u1 = rng.uniform(), u2 = rng.uniform();
  if (!sampler_.sample(u0, u1, u2, envDir, pe, le)) return false;
  w = Vec3f(settings_.rotation * Vec3d(envDir));
  return true;
}

// True when nothing blocks the ray (origin, w); unshadowed mode never looks (and casts no ray).
bool ReferenceIntegrator::unblocked(const Vec3f& origin, const Vec3f& w,
                                    std::uint64_t& rays) const {
  if (settings_.mode == TransferMode::Unshadowed) return true;
  ++rays;
  return !occluder_.occluded(Ray{origin, w, 0.0f, std::numeric_limits<float>::infinity()});
}

// The light a hit h of the ray in direction w sends back along it, 0 at a back face. At a front
// face, one sample of what its surface reflects with one bounce less: ρ(h) ⊙ (1/π) ∫ L_in(h, ω')
// max(n_h·ω', 0) dω' for a diffuse material; for a glossy one also ks ⊙ ∫ L_in(h, ω') G(R·ω') dω'
// about R = −w reflected in n_h. Of the two terms one is followed, picked with probability in
// proportion to its weight (Σ ρ_c against Σ ks_c) and divided by it: unbiased, and the path
// stays a path instead of a tree.
template <class R>
R ReferenceIntegrator::frontHit(const Hit& h, const Vec3f& w, int bouncesLeft, Pcg32& rng,
                                std::uint64_t& rays) const {
  const auto& tri = mesh_.triangles[h.triangle];
  const Vec3f p0 = mesh_.positions[tri[0]], p1 = mesh_.positions[tri[1]],
              p2 = mesh_.positions[tri[2]];
  const Vec3f ng = cross(p1 - p0, p2 - p0);
  if (dot(ng, w) >= 0.0f) return R{};  // back face: blocks, sends nothing
  const float b0 = 1.0f - h.u - h.v;
  const Vec3f q = p0 * b0 + p1 * h.u + p2 * h.v;
  Vec3f nq = mesh_.normals[tri[0]] * b0 + mesh_.normals[tri[1]] * h.u + mesh_.normals[tri[2]] * h.v;
  const float len = length(nq);
  nq = len > 0 ? nq / len : normalize(ng);
  const Rgb rho = hitAlbedo(h.triangle, h.u, h.v);
  const double wd = double(rho.x) + rho.y + rho.z;
  if (!settings_.material.glossy()) {
    if (wd <= 0) return R{};
    return rho * incoming<R>(q, nq, bouncesLeft - 1, rng, rays);
  }
  const Rgb ks = settings_.material.specular;
  const double wg = double(ks.x) + ks.y + ks.z, pd = wd / (wd + wg);
  if (rng.uniform() < pd)
    return rho * incoming<R>(q, nq, bouncesLeft - 1, rng, rays) * static_cast<float>(1.0 / pd);
  const Vec3f r = normalize(reflectView(nq, -w));
  return ks * glossy<R>(q, nq, r, bouncesLeft - 1, rng, rays) *
         static_cast<float>(1.0 / (1.0 - pd));
}

// One sample of (1/π) ∫ L_in(p, ω) max(n·ω, 0) dω: one environment direction and one cosine
// direction, MIS-weighted; the cosine direction continues the path at a front-facing hit.
//   environment sample ω_e ~ p_env:  w_e(ω_e) · L(ω_e) V(ω_e) (n·ω_e)/π / p_env(ω_e)
//   cosine sample ω_c ~ cos/π:       w_c(ω_c) · L(ω_c) V(ω_c)            (f cos / p_cos = 1)
//                                    + ρ(h) ⊙ L_in-estimate at h        (if ω_c hits a front face)
// The emitted term is counted only once, by the two MIS-weighted strategies; the reflected term
// by the cosine strategy alone (weight 1), as the environment strategy cannot reach surfaces.
// (The cosine density covers the whole hemisphere, so with a band-limited light — which need
// not vanish where the environment is black, and so where p_env = 0 — the estimate is still
// unbiased.)
template <class R>
R ReferenceIntegrator::incoming(const Vec3f& p, const Vec3f& n, int bouncesLeft, Pcg32& rng,
                                std::uint64_t& rays) const {
  const bool shadowed = settings_.mode != TransferMode::Unshadowed;
  const Vec3f origin = shadowed ? p + n * occluder_.rayOffset(p) : p;
  const float inf = std::numeric_limits<float>::infinity();
  R result{};

  // (a) Environment sample.
  {
    Vec3f w, d;
    double pe;
    Rgb le;
    if (sampleEnvironment(rng, w, d, pe, le)) {
      const double c = dot(n, w);
      if (c > 0 && unblocked(origin, w, rays)) {
        const double pc = c / kPi;
        const double f = misWeight(pe, pc) * (c / kPi) / pe;
        result += sky<R>(d, le) * static_cast<float>(f);
      }
    }
  }

  // (b) Cosine sample.
  {
    const float u1 = rng.uniform(), u2 = rng.uniform();
    Vec3f t, b;
    orthonormalBasis(n, t, b);
    const Vec3f l = cosineHemisphere(u1, u2);
    const Vec3f w = normalize(t * l.x + b * l.y + n * l.z);
    const double c = dot(n, w);
    if (c > 0) {
      Hit h;
      if (shadowed) {
        ++rays;
        h = occluder_.intersect(Ray{origin, w, 0.0f, inf});
      }
      if (!h.hit) {
        const Vec3f de = Vec3f(rotT_ * Vec3d(w));
        double pe = 0;
        const Rgb le = sampler_.lookup(de, pe);
        result += sky<R>(de, le) * static_cast<float>(misWeight(c / kPi, pe));
      } else if (bouncesLeft > 0) {
        result += frontHit<R>(h, w, bouncesLeft, rng, rays);
      }
    }
  }
  return result;
}

namespace {

/// A direction about the unit `axis` with density G(axis·ω) per steradian (the lobe is a
/// normalised density), from (u1, u2) in [0, 1)²; `ct` receives the drawn cos θ to the axis,
/// exact (without the rounding of the returned float direction). cos θ inverts the lobe's CDF:
///   Phong: P(cos θ ≤ t) = t^{s+1}  →  cos θ = u^{1/(s+1)};
///   GGX:   θ = 2θ_h, the half angle from the NDF: tan² θ_h = α² u/(1 − u) (density
///          D(θ_h) cos θ_h dω_h = D/4 dω = G dω), so cos θ = (1 − tan²θ_h)/(1 + tan²θ_h) and
///          sin θ = 2 tan θ_h/(1 + tan² θ_h).
Vec3f sampleLobe(const GlossyLobe& lobe, const Vec3f& axis, double u1, double u2, double& ct) {
  double st = 0;
  if (lobe.kind == LobeKind::Phong) {
    ct = std::pow(u1, 1.0 / (lobe.exponent + 1.0));
    st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
  } else {
    const double a2 = std::pow(lobe.roughness, 4.0);  // α², α = roughness²
    const double t2 = a2 * u1 / (1.0 - u1);
    ct = (1.0 - t2) / (1.0 + t2);
    st = 2.0 * std::sqrt(t2) / (1.0 + t2);
  }
  const double phi = 2.0 * kPi * u2;
  Vec3f t, b;
  orthonormalBasis(axis, t, b);
  return normalize(t * float(st * std::cos(phi)) + b * float(st * std::sin(phi)) +
                   axis * float(ct));
}

/// The horizon point nearest r about normal n (r − (n·r)n normalised; any horizon point when
/// r = −n): the axis of the horizon lobe when n·r < 0.
Vec3f horizonAxis(const Vec3f& n, const Vec3f& r, double nr) {
  const Vec3f x = r - n * float(nr);
  const float len = length(x);
  Vec3f t, b;
  orthonormalBasis(n, t, b);
  return len > 1e-6f ? x / len : t;
}

}  // namespace

// One sample of ∫_{n·ω>0} L_in(p, ω) G(r·ω) dω: one environment direction, one lobe direction
// and, when r lies below the horizon, one horizon-lobe direction, MIS-weighted (the header gives
// the terms); the directional strategies continue the path at a front-facing hit, into the
// diffuse estimator with one bounce less.
template <class R>
R ReferenceIntegrator::glossy(const Vec3f& p, const Vec3f& n, const Vec3f& r, int bounces,
                              Pcg32& rng, std::uint64_t& rays) const {
  const GlossyLobe& lobe = settings_.material.lobe;
  const bool shadowed = settings_.mode != TransferMode::Unshadowed;
  const Vec3f origin = shadowed ? p + n * occluder_.rayOffset(p) : p;
  const float inf = std::numeric_limits<float>::infinity();
  R result{};

  // The horizon lobe: G about r_h, the point of the horizon nearest r, used when n·r < 0. Its
  // density is G(r_h·ω).
  const double nr = dot(Vec3d(n), Vec3d(r));
  const bool horizon = nr < 0;
  const Vec3f rh = horizon ? horizonAxis(n, r, nr) : r;
  const auto horizonPdf = [&](const Vec3f& w) {
    return horizon ? lobe.value(dot(Vec3d(rh), Vec3d(w))) : 0.0;
  };
  // The light along a traced direction w, as the strategy with density `pdf` sees it: escaping,
  // L·weight over {env, lobe, horizon}; at a front face, ρ(h) L_in(h) weighted over {lobe,
  // horizon} (the environment strategy cannot reach surfaces).
  const auto traced = [&](const Vec3f& w, double pdf, double other) -> R {
    Hit h;
    if (shadowed) {
      ++rays;
      h = occluder_.intersect(Ray{origin, w, 0.0f, inf});
    }
    if (!h.hit) {
      double pe = 0;
      const Vec3f de = Vec3f(rotT_ * Vec3d(w));
      const Rgb le = sampler_.lookup(de, pe);
      return sky<R>(de, le) * static_cast<float>(misWeight(pdf, pe, other));
    }
    if (bounces > 0)
      return frontHit<R>(h, w, bounces, rng, rays) * static_cast<float>(misWeight(pdf, 0.0, other));
    return R{};
  };

  // (a) Environment sample: L V G / p_env, weighted by w(p_env; p_lobe = G, p_horizon).
  {
    Vec3f w, d;
    double pe;
    Rgb le;
    if (sampleEnvironment(rng, w, d, pe, le)) {
      const double g = lobe.value(dot(Vec3d(r), Vec3d(w)));
      if (dot(n, w) > 0 && g > 0 && unblocked(origin, w, rays))
        result += sky<R>(d, le) * static_cast<float>(misWeight(pe, g, horizonPdf(w)) * g / pe);
    }
  }

  // (b) Lobe sample about r, density G: the integrand over the density is L_in (G/p = 1).
  {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    double ct;
    const Vec3f w = sampleLobe(lobe, r, u1, u2, ct);
    const double g = lobe.value(ct);
    if (g > 0 && dot(n, w) > 0) result += traced(w, g, horizonPdf(w));
  }

  // (c) Horizon-lobe sample, density p_h = G(r_h·ω): the integrand over the density is
  // L_in G(r·ω)/G(r_h·ω), and G(r·ω) ≤ G(r_h·ω) above the horizon (in the right spherical
  // triangle r, r_h, h' of any horizon point h', cos∠(r, h') = cos∠(r, r_h) cos∠(r_h, h'), so
  // r_h is nearer than r to every point above the horizon, and G falls with the angle). The
  // ratio stays ≤ 1 where neither the environment nor the lobe about r puts samples — the
  // horizon point nearest r, where a mostly clipped lobe has all of its remaining mass.
  if (horizon) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    double ct;
    const Vec3f w = sampleLobe(lobe, rh, u1, u2, ct);
    const double ph = lobe.value(ct);
    const double g = lobe.value(dot(Vec3d(r), Vec3d(w)));
    if (ph > 0 && g > 0 && dot(n, w) > 0) result += traced(w, ph, g) * static_cast<float>(g / ph);
  }
  return result;
}

// One sample of ∫_{n·ω>0} (K − K_b)(ω) L_in[L_b](ω) dω for every band limit: the part of the
// exact band-limited relighting of matrix transfer that comes from cutting the kernels (the
// header). K − K_b is the lobe's peak where b bands cannot hold it and K_b's ringing over the
// whole hemisphere, also where G = 0 (Phong behind r): so MIS of a uniform hemisphere direction
// (density 1/2π, covering everything), the lobe about r (its peak) and, when r is below the
// horizon, the horizon lobe — every strategy directional, so one weight over the three for
// escapes and hits alike. L_in[L_b] is the band-limited lanes of the traced path. With
// wholeSphere (a probe's, where no surface hides the lower hemisphere and K_b rings there too,
// K = 0) the integral is over the whole sphere, the uniform direction's density 1/4π.
void ReferenceIntegrator::kernelResidual(const Vec3f& p, const Vec3f& n, const Vec3f& r,
                                         const Rgb& kd, int bounces, Pcg32& rng,
                                         std::uint64_t& rays, Rgb* out) const {
  const BandLimitData& bd = *band_;
  for (int k = 0; k < bd.lanes; ++k) out[k] = Rgb(0.0f);
  const bool gloss = settings_.material.glossy();
  const GlossyLobe& lobe = settings_.material.lobe;
  const Vec3d ks(settings_.material.specular);
  const bool shadowed = settings_.mode != TransferMode::Unshadowed;
  const Vec3f origin = shadowed ? p + n * occluder_.rayOffset(p) : p;
  const double nr = dot(Vec3d(n), Vec3d(r));
  const bool horizon = gloss && nr < 0;
  const Vec3f rh = horizon ? horizonAxis(n, r, nr) : r;
  const double pu = bd.wholeSphere ? 1.0 / (4.0 * kPi) : 1.0 / (2.0 * kPi);
  const auto lobePdf = [&](const Vec3f& w) {
    return gloss ? lobe.value(dot(Vec3d(r), Vec3d(w))) : 0.0;
  };
  const auto horizonPdf = [&](const Vec3f& w) {
    return horizon ? lobe.value(dot(Vec3d(rh), Vec3d(w))) : 0.0;
  };
  const auto add = [&](const Vec3f& w, double pa, double pb, double pc) {
    const double cn = dot(Vec3d(n), Vec3d(w));
    if ((cn <= 0 && !bd.wholeSphere) || pa <= 0) return;
    Hit h;
    if (shadowed) {
      ++rays;
      h = occluder_.intersect(Ray{origin, w, 0.0f, std::numeric_limits<float>::infinity()});
    }
    Lanes li;
    if (!h.hit) {
      double pe = 0;
      const Vec3f de = Vec3f(rotT_ * Vec3d(w));
      li = sky<Lanes>(de, sampler_.lookup(de, pe));
    } else if (bounces > 0) {
      li = frontHit<Lanes>(h, w, bounces, rng, rays);
    } else {
      return;
    }
    const double weight = misWeight(pa, pb, pc) / pa;
    const int nb = bd.lightBands;
    std::array<double, sh::kMaxBands> pn{}, pr{};
    legendrePolynomials(nb, cn, pn.data());
    const double cr = dot(Vec3d(r), Vec3d(w));
    if (gloss) legendrePolynomials(nb, cr, pr.data());
    const double c = std::max(cn, 0.0) / kPi, g = gloss ? lobe.value(cr) : 0.0;
    // Partial sums over bands: lane k takes those up to its b_k (lanes in any order).
    std::array<double, sh::kMaxBands + 1> cb{}, gb{};
    for (int l = 0; l < nb; ++l) {
      cb[l + 1] = cb[l] + bd.cosCoef[l] * pn[l];
      gb[l + 1] = gb[l] + (gloss ? bd.lobeCoef[l] * pr[l] : 0.0);
    }
    for (int k = 0; k < bd.lanes; ++k) {
      const int b = bd.laneBands[k];
      const Vec3d kernel = Vec3d(kd) * (c - cb[b]) + ks * (g - gb[b]);
      out[k] += Rgb(kernel * Vec3d(li.band[k]) * weight);
    }
  };

  // (u) Uniform on the hemisphere: a uniform sphere direction, mirrored to n's side (over the
  // whole sphere: as drawn).
  {
    const float u1 = rng.uniform(), u2 = rng.uniform();
    Vec3f w = uniformSphere(u1, u2);
    if (dot(n, w) < 0 && !bd.wholeSphere) w = -w;
    add(w, pu, lobePdf(w), horizonPdf(w));
  }
  // (g) The lobe about r.
  if (gloss) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    double ct;
    const Vec3f w = sampleLobe(lobe, r, u1, u2, ct);
    add(w, lobe.value(ct), pu, horizonPdf(w));
  }
  // (h) The horizon lobe.
  if (horizon) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    double ct;
    const Vec3f w = sampleLobe(lobe, rh, u1, u2, ct);
    add(w, lobe.value(ct), pu, lobePdf(w));
  }
}

Estimate ReferenceIntegrator::estimate(const Vec3f& p, const Vec3f& n, const Vec3f& v,
                                       const Rgb& kd, int samples, std::uint64_t seed,
                                       std::uint64_t* rays) const {
  const int bounces = effectiveBounces(settings_.mode, settings_.bounces);
  const bool gloss = settings_.material.glossy();
  const Vec3d ks(settings_.material.specular);
  const Vec3f r = gloss ? normalize(reflectView(n, v)) : n;
  // Two independent streams: the diffuse one is what a diffuse-only material draws.
  Pcg32 rng(seed), rngGloss(seed, 0x9e3779b97f4a7c15ull);
  std::uint64_t cast = 0;
  // One sample X = kd ⊙ D + ks ⊙ S; Welford's running mean and variance of X, per channel, in
  // double.
  Vec3d mean(0.0), m2(0.0);
  for (int s = 0; s < samples; ++s) {
    Vec3d x = Vec3d(kd) * Vec3d(incoming<Rgb>(p, n, bounces, rng, cast));
    if (gloss) x += ks * Vec3d(glossy<Rgb>(p, n, r, bounces, rngGloss, cast));
    const Vec3d delta = x - mean;
    mean += delta / double(s + 1);
    m2 += delta * (x - mean);
  }
  if (rays) *rays += cast;
  Estimate e;
  const Vec3d var = samples > 1 ? m2 / double(samples - 1) : Vec3d(0.0);
  e.mean = Rgb(mean);
  e.stdError = Rgb(
      Vec3d(std::sqrt(var.x / samples), std::sqrt(var.y / samples), std::sqrt(var.z / samples)));
  return e;
}

namespace {

/// Welford's running mean and sum of squared deviations, per channel, in double.
struct Running {
  Vec3d mean{0.0}, m2{0.0};
  void add(const Vec3d& x, int count) {  // count: samples so far, this one included
    const Vec3d delta = x - mean;
    mean += delta / double(count);
    m2 += delta * (x - mean);
  }
  Estimate result(int samples) const {
    const Vec3d var = samples > 1 ? m2 / double(samples - 1) : Vec3d(0.0);
    return {Rgb(mean), Rgb(Vec3d(std::sqrt(var.x / samples), std::sqrt(var.y / samples),
                                 std::sqrt(var.z / samples)))};
  }
};

}  // namespace

// estimate() with Lanes: per sample X under L (the same operations, so the same value) and X_b
// under each L_b along the same paths; with truncateKernel also one sample of the kernel part
// from a third stream (so the first two stay those of estimate()). Per sample, X_b − (kernel
// part) is one of e_b, X_b − X − (kernel part) one of e_b − e, X_b − X one of the light part.
Estimate ReferenceIntegrator::estimateBandLimited(const Vec3f& p, const Vec3f& n, const Vec3f& v,
                                                  const Rgb& kd, int samples, std::uint64_t seed,
                                                  std::span<BandLimitedEstimate> out,
                                                  std::uint64_t* rays) const {
  if (!band_) throw Error("estimateBandLimited: the settings have no band limits");
  const int lanes = band_->lanes;
  if (out.size() != std::size_t(lanes))
    throw Error("estimateBandLimited: one estimate per band limit");
  const int bounces = effectiveBounces(settings_.mode, settings_.bounces);
  const bool gloss = settings_.material.glossy();
  const Vec3d ks(settings_.material.specular);
  const Vec3f r = gloss ? normalize(reflectView(n, v)) : n;
  Pcg32 rng(seed), rngGloss(seed, 0x9e3779b97f4a7c15ull), rngKernel(seed, 0x2545f4914f6cdd1dull);
  std::uint64_t cast = 0;
  Vec3d mean(0.0), m2(0.0);
  std::array<Running, sh::kMaxBands> value, diff, lightPart;
  std::array<Rgb, sh::kMaxBands> residual{};
  for (int s = 0; s < samples; ++s) {
    const Lanes xd = incoming<Lanes>(p, n, bounces, rng, cast);
    Vec3d x = Vec3d(kd) * Vec3d(xd.full);
    Lanes xg;
    if (gloss) {
      xg = glossy<Lanes>(p, n, r, bounces, rngGloss, cast);
      x += ks * Vec3d(xg.full);
    }
    const Vec3d delta = x - mean;
    mean += delta / double(s + 1);
    m2 += delta * (x - mean);
    if (band_->truncateKernel)
      kernelResidual(p, n, r, kd, bounces, rngKernel, cast, residual.data());
    for (int k = 0; k < lanes; ++k) {
      Vec3d xb = Vec3d(kd) * Vec3d(xd.band[k]);
      if (gloss) xb += ks * Vec3d(xg.band[k]);
      const Vec3d a = xb - x;
      value[k].add(xb - Vec3d(residual[k]), s + 1);
      lightPart[k].add(a, s + 1);
      diff[k].add(a - Vec3d(residual[k]), s + 1);
    }
  }
  if (rays) *rays += cast;
  for (int k = 0; k < lanes; ++k)
    out[k] = {value[k].result(samples), diff[k].result(samples), lightPart[k].result(samples)};
  Estimate e;
  const Vec3d var = samples > 1 ? m2 / double(samples - 1) : Vec3d(0.0);
  e.mean = Rgb(mean);
  e.stdError = Rgb(
      Vec3d(std::sqrt(var.x / samples), std::sqrt(var.y / samples), std::sqrt(var.z / samples)));
  return e;
}

// ---------------------------------------------------------------------------------------------

ReferenceRows::ReferenceRows(const Mesh& mesh, const Occluder& occluder, const Environment& env,
                             const ReferenceSettings& settings)
    : mesh_(mesh),
      albedo_(mesh.hasAlbedo() || mesh.baseColour ? albedoAtVertices(mesh) : std::vector<Rgb>()),
      settings_(settings) {
  if (settings.samples < 1 || settings.samples > (1 << 24))
    throw Error("reference samples must be in 1..16777216 (got " +
                std::to_string(settings.samples) + ")");
  if (settings.bounces < 0 || settings.bounces > 16)
    throw Error("reference bounces must be in 0..16 (got " + std::to_string(settings.bounces) +
                ")");
  const RowPoints* points = settings.points.get();
  const std::size_t entries = points ? points->positions.size() : mesh.vertexCount();
  if (mesh.normals.size() != mesh.vertexCount())
    throw Error(mesh.source, "has no per-vertex normals");
  if (mesh.hasAlbedo() && mesh.albedo.size() != mesh.vertexCount())
    throw Error(mesh.source, "albedo count differs from vertex count");
  if (points && (points->normals.size() != entries ||
                 (!points->albedo.empty() && points->albedo.size() != entries) ||
                 (!points->rows.empty() && points->rows.size() != entries)))
    throw Error(mesh.source, "the reference's row points lack normals or albedo");
  if (settings.material.glossy() && !settings.eye)
    throw Error("a glossy reference (" + settings.material.spec() +
                ") needs the eye position for its view directions");
  if (!settings.vertices.empty()) {
    vertices_ = settings.vertices;
  } else if (points && !points->rows.empty()) {
    vertices_ = points->rows;  // the rows held
  } else {
    vertices_.resize(entries);
    for (std::size_t v = 0; v < entries; ++v) vertices_[v] = static_cast<std::uint32_t>(v);
  }
  // Where each row's point is: its entry in the points (looked up once), or the vertex itself.
  entries_.reserve(vertices_.size());
  for (std::uint32_t v : vertices_) {
    const std::size_t e = points ? points->entry(v) : (v < entries ? v : RowPoints::kAbsent);
    if (e == RowPoints::kAbsent)
      throw Error(points && !points->rows.empty()
                      ? "reference row " + std::to_string(v) + " is not among the rows' points"
                      : "reference vertex " + std::to_string(v) + " out of range (mesh has " +
                            std::to_string(entries) + ")");
    entries_.push_back(e);
  }
  lanes_ = settings.bandLimit ? settings.bandLimit->limits.size() : 0;
  sampler_ = std::make_unique<EnvironmentSampler>(env);
  integrator_ = std::make_unique<ReferenceIntegrator>(mesh, occluder, *sampler_, settings);
}

ReferenceRows::~ReferenceRows() = default;

void ReferenceRows::compute(std::size_t first, std::size_t count, Rgb* radiance, Rgb* stdError,
                            BandLimitedEstimate* bandLimited, std::uint64_t* rays,
                            Progress* progress) const {
  const Mesh& mesh = mesh_;
  const ReferenceSettings& settings = settings_;
  const std::size_t lanes = lanes_;
  parallelFor(count, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      if (progress) progress->check();
      const std::uint32_t v = vertices_[first + i];
      const std::size_t at = entries_[first + i];
      const RowPoints* points = settings.points.get();
      const Vec3f& p = points ? points->positions[at] : mesh.positions[v];
      const Vec3f& n = points ? points->normals[at] : mesh.normals[v];
      const Rgb kd = settings.material.diffuse           ? *settings.material.diffuse
                     : points && !points->albedo.empty() ? points->albedo[at]
                     : !points && !albedo_.empty()       ? albedo_[v]
                                                         : Rgb(1.0f);
      // v = normalize(eye − p); an eye on the vertex (or none) looks along the normal.
      const Vec3f toEye = settings.eye ? *settings.eye - p : n;
      const Vec3f view = length(toEye) > 0 ? normalize(toEye) : n;
      const std::uint64_t seed = deriveSeed(settings.seed, v);
      rays[i] = 0;
      const Estimate est =
          lanes == 0
              ? integrator_->estimate(p, n, view, kd, settings.samples, seed, &rays[i])
              : integrator_->estimateBandLimited(
                    p, n, view, kd, settings.samples, seed,
                    std::span<BandLimitedEstimate>(bandLimited + i * lanes, lanes), &rays[i]);
      radiance[i] = est.mean;
      stdError[i] = est.stdError;
      if (progress) progress->advance(1);
    }
  });
}

ReferenceResult renderReference(const Mesh& mesh, const Occluder& occluder, const Environment& env,
                                const ReferenceSettings& settings, const ProgressFn& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const ReferenceRows job(mesh, occluder, env, settings);
  ReferenceResult out;
  out.vertices = job.vertices();
  const std::size_t count = out.vertices.size();
  out.radiance.assign(count, Rgb(0.0f));
  out.stdError.assign(count, Rgb(0.0f));
  out.bandLimited.assign(count * job.lanes(), BandLimitedEstimate{});
  std::vector<std::uint64_t> rays(count, 0);
  Progress prog(progress, count);
  job.compute(0, count, out.radiance.data(), out.stdError.data(), out.bandLimited.data(),
              rays.data(), &prog);
  for (std::uint64_t r : rays) out.rays += r;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

std::size_t RowPoints::entry(std::size_t r) const {
  if (rows.empty()) return r < positions.size() ? r : kAbsent;
  const auto it = std::lower_bound(rows.begin(), rows.end(), r);
  return it != rows.end() && *it == r ? static_cast<std::size_t>(it - rows.begin()) : kAbsent;
}

Material referenceMaterial(const Material& material, TransferLayout layout) {
  Material m = material;
  if (layout != TransferLayout::Matrix) {
    m.lobe = {};
    m.specular = Rgb(0.0f);
  }
  return m;
}

}  // namespace prt::render
