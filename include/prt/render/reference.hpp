#pragma once
// The brute-force Monte Carlo reference: an estimate of the same per-vertex exit radiance that
// PRT computes, with no spherical harmonics anywhere, so that a comparison measures the SH
// truncation and the bake's noise rather than shared mistakes.
//
// What is integrated. The environment is taken AS ITS TEXELS: L(ω) is the radiance of the texel
// whose (exact) footprint on the sphere contains ω — a piecewise-constant function, the same
// one whose texel-midpoint projection envmap::projectEnvironment computes. For an analytic
// environment (Environment::analytic) that is its lat-long texel sampling, in which the caps
// (the sun) are present by their covered fraction. The sampled radiance and the looked-up
// radiance are therefore one function, as multiple importance sampling requires. With the
// environment rotated by R (a feature at d appears at R d), L'(ω) = L(Rᵀ ω). Then, for the
// material of transfer/material.hpp (kd, ks, a lobe G about the reflected view direction),
//
//   e(p, v) = kd(p) ⊙ (1/π) ∫ L_in(p, ω) max(n·ω, 0) dω  +  ks ⊙ ∫_{n·ω>0} L_in(p, ω) G(r·ω) dω,
//   r = 2(n·v)n − v,  v = normalize(eye − p),
//   L_in(p, ω) = L'(ω)                   if the ray (p, ω) escapes,
//              = e(h, −ω) with one bounce less   at its closest hit h if h is a front face and
//                                        bounces remain: the same material seen from p,
//                                        kd = ρ(h) (recursively),
//              = 0                       otherwise (back faces block and send nothing),
//
// matching transport::bake's conventions (docs/transport.md): unshadowed mode drops V (but keeps
// n·ω > 0 in both terms); the offset origin p + n·rayOffset(p); kd(p) and the bounce albedo ρ =
// Material::diffuse, else the mesh's per-vertex albedo (interpolated at a hit), else 1; the
// shading normal at a hit is the barycentric interpolation of the vertex normals. Surfaces the
// light bounces off have the same material: glossy ones reflect about −ω mirrored in n_h, as in
// the bake's glossy transfer matrices (a vector bake's bounces are diffuse; validation then
// drops the lobe from the reference). G is Material::lobe.value, the same zonal lobe PRT convolves
// with; Fresnel, masking-shadowing and the (n·ω) of a BRDF-times-cosine are omitted on both sides
// so that PRT and reference differ only by band limit and noise. (The bake interpolates the
// *transfer* of the hit triangle's vertices instead of integrating at the hit: that
// discretisation is part of what a validation measures.)
//
// Estimator. Every sample of the diffuse term combines two strategies by multiple importance
// sampling (Veach & Guibas, "Optimally Combining Sampling Techniques for Monte Carlo
// Rendering", SIGGRAPH 1995):
//  (a) the environment: a texel k drawn with probability P_k ∝ lum(L_k)·ΔΩ_k from an alias table
//      built once (ΔΩ_k the texel's exact solid angle), then a direction within the texel
//      uniformly in its parametrisation, so p_env(ω) = P_k · q_k(ω) with q_k the density within
//      the texel (1/ΔΩ_k for lat-long texels, where sampling is uniform in φ and cos θ);
//  (b) the cosine-weighted hemisphere, p_cos(ω) = max(n·ω, 0)/π.
// One direction of each per sample, weighted by the balance heuristic w_a = p_a/(p_a + p_b) or
// the power heuristic w_a = p_a²/(p_a² + p_b²). The cosine direction also carries the path on:
// at a front-facing hit the estimate recurses (next-event estimation at every vertex of the
// path).
//
// The glossy term (when Material::glossy()) is estimated alongside, by MIS of
//  (a) the environment, as above;
//  (b) the lobe itself about r: G is a normalised density on the sphere (∫ G dω = 1), drawn
//      exactly — Phong: cos θ = u^{1/(s+1)}; GGX: the half-angle from the NDF,
//      tan² θ_h = α² u/(1 − u), and θ = 2θ_h (D(θ_h) cos θ_h dω_h = D/4 dω = G dω) — so
//      p_lobe(ω) = G(r·ω) over the whole sphere, and a direction with n·ω ≤ 0 contributes 0;
//  (c) when r lies below the horizon (n·r < 0), the same lobe about r_h, the horizon point
//      nearest r: p_h(ω) = G(r_h·ω). A mostly clipped lobe keeps its mass next to r_h, where
//      (a) and (b) rarely sample; r_h is nearer than r to every direction above the horizon, so
//      G(r·ω)/p_h(ω) ≤ 1 there and the estimate no longer rests on rare samples.
// With p_h = 0 when (c) is off, and w(a; b, c) the heuristic's weight of a among a, b, c:
//   environment ω_e:  w(p_env; G, p_h) · L V G / p_env
//   lobe ω_g:         w(G; p_env, p_h) · L V                        (G / p_lobe = 1)
//   horizon ω_h:      w(p_h; p_env, G) · L V G / p_h
// and where ω_g or ω_h hits a front face, instead the light h reflects toward p (one bounce less)
// times G/p and w(p; 0, other) (the environment strategy cannot reach surfaces). At a glossy hit
// one of its two terms, diffuse or glossy, is followed, chosen in proportion to Σρ_c : Σks_c
// and divided by that probability (unbiased; the path does not branch).
//
// One sample of e is X = kd ⊙ D + ks ⊙ S, D and S one diffuse and one glossy sample from two
// PCG32 streams of the same vertex (the diffuse stream is the one a diffuse-only material draws,
// so kd-only results are unchanged; any dependence between D and S is inside X, whose sample
// variance then includes it). Each vertex draws its streams from (seed,
// vertex index), so results do not depend on the thread count, and the per-vertex standard
// error sqrt(s²(X)/N) per channel is an honest i.i.d. error bar for the whole of e.
//
// Exact band-limited relighting (ReferenceSettings::bandLimit; validation's truncation floor,
// validate.hpp, docs/validation.md). PRT with a noise-free b-band transfer computes
//   vector transfer:  e_b = ∫ K L_in[L_b] dω                (T_i exact: only the light is cut)
//   matrix transfer:  e_b = ∫_{n·ω>0} K_b L_in[L_b] dω      (d, g and M L cut to b bands too)
// with K(ω) = kd max(n·ω, 0)/π + ks G(r·ω) the reference's kernel at p, L_in[L_b] the light
// arriving at p when the source is the b-band light L_b(ω) = Σ_{i<b²} w_l L_i Y_i(Rᵀω) (w a
// window, 1 by default) and K_b = kd Σ_{l<b} (A_l/π)(2l+1)/(4π) P_l(n·ω) + ks Σ_{l<b} Λ_l
// (2l+1)/(4π) P_l(r·ω) its b-band projection (addition theorem: dᵀY(ω), gᵀY(ω)). Split
//   e_b − e = (e[L_b] − e) − ∫_{n·ω>0} (K − K_b) L_in[L_b] dω:
//  * the light part, e[L_b] − e, from the reference's own samples: every path is traced once
//    and carries, beside its radiance under L, its radiance under each L_b (`Lanes`: at an
//    escape L_b is evaluated from the SH, everything else — directions, MIS weights, hits, the
//    choice of term at a glossy hit — is shared). As L_b → L the two estimates' noise cancels;
//  * the kernel part (matrix transfer only), by its own MIS of a uniform hemisphere direction
//    (density 1/2π: K_b rings over the whole hemisphere, where the lobe has no density), the
//    lobe about r and, when r is below the horizon, the horizon lobe, from a third stream; its
//    paths carry the same band-limited lanes.
// Each sample gives one value of e_b − e per band limit, so the standard error of the
// difference comes from the same samples. Bounce hits keep the exact kernels (a matrix bake's
// hits use its own band count's kernels: that, like interpolating transfer across a hit
// triangle, is the bake's discretisation, not truncation at b).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/core/sampling.hpp"
#include "prt/core/vec.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/environment_sampler.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/material.hpp"

namespace prt::render {

enum class MisHeuristic { Balance, Power };

/// One band-limited light: L cut to `bands`, band l scaled by window[l] (empty: 1).
struct BandLimit {
  int bands = 0;
  std::vector<double> window;
};

/// Exact band-limited relighting estimated beside the reference (see the top of this file).
struct BandLimitSettings {
  sh::RgbSh light;                ///< the SH light PRT relights with (environment frame)
  std::vector<BandLimit> limits;  ///< one lane each, at most sh::kMaxBands
  /// Matrix (glossy) transfer: the cosine and lobe kernels at the vertex and the transferred
  /// light are cut to b bands too. False for vector transfer (exact cosine kernel).
  bool truncateKernel = false;
  /// With truncateKernel: the b-band kernel is integrated over the whole sphere, not the
  /// hemisphere above n — a probe's relit SH (probe_points.hpp) covers every direction, and its
  /// cosine kernel K_b rings below the horizon too, where K = 0:
  ///   e_b = ∫_{S²} K_b L_in[L_b] dω,  e_b − e = (e[L_b] − e) − ∫_{S²} (K − K_b) L_in[L_b] dω.
  bool wholeSphere = false;
};

/// The material the reference of a transfer integrates: the material itself for matrix
/// (glossy) transfer; for vector transfer its diffuse part alone (a vector holds no lobe, so
/// its relighting is diffuse, and so is the reference it is compared with). The one rule for
/// prt reference, prt validate and a reference file's check.
Material referenceMaterial(const Material& material, TransferLayout layout);

/// Where the rows are when they are not the mesh's vertices — per-texel transfer: each texel's
/// sample point (transport/bake_texels.hpp) — one position, unit normal and albedo per entry:
/// an entry per row of the domain, or per row of a subset (`rows`), all that a reference or a
/// validation of that subset reads (render/texel_points.hpp). Rows no triangle covers hold
/// anything: they are never estimated.
struct RowPoints {
  std::vector<Vec3f> positions, normals;  ///< per entry
  std::vector<Rgb> albedo;                ///< per entry, or empty: white (or the material's kd)
  /// The rows that may be estimated (covered, not inside geometry) among those held, ascending.
  std::vector<std::uint32_t> valid;
  /// The rows the entries are of, ascending, when they are some rows only; empty: entry r is
  /// row r, of every row.
  std::vector<std::uint32_t> rows;

  /// The entry of row r, or kAbsent when the points do not hold it.
  std::size_t entry(std::size_t r) const;
  static constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);
};

struct ReferenceSettings {
  /// Samples per vertex (each: an environment and a cosine direction, and when glossy an
  /// environment and a lobe direction).
  int samples = 1024;
  TransferMode mode = TransferMode::Shadowed;
  int bounces = 0;  ///< Interreflected only
  /// kd override and bounce albedo (Material::diffuse, as BakeSettings::material), ks and lobe.
  Material material;
  /// World position of the camera: v = normalize(eye − p) per vertex. Required when glossy.
  std::optional<Vec3f> eye;
  std::uint64_t seed = 0;
  Mat3d rotation = Mat3d::identity();  ///< environment rotation (a feature at d moves to R d)
  MisHeuristic heuristic = MisHeuristic::Power;
  /// The vertices to estimate (global indices); empty: every vertex (every row `points` hold).
  std::vector<std::uint32_t> vertices;
  /// When set, the rows are these points instead of the mesh's vertices (`vertices` then name
  /// rows they hold, each seeded by its index as a vertex is); the mesh and occluder are still
  /// the scene.
  std::shared_ptr<const RowPoints> points;
  /// When set, also e_b − e per band limit (ReferenceResult::bandLimited); the radiance is the
  /// same, bit for bit (the band-limited lanes draw no random numbers of the main streams).
  std::optional<BandLimitSettings> bandLimit;
};

/// One estimate: the mean and its standard error sqrt(s²/N), per channel.
struct Estimate {
  Rgb mean;
  Rgb stdError;
};

/// The band-limited estimates at one vertex for one band limit b (same samples as e's).
struct BandLimitedEstimate {
  Estimate radiance;    ///< e_b: the exact band-limited relighting, what a noise-free bake gives
  Estimate difference;  ///< e_b − e (its error bar from the per-sample differences)
  Estimate light;       ///< e[L_b] − e: the light cut alone, exact kernels (= difference for
                        ///< vector transfer)
};

struct ReferenceResult {
  std::vector<std::uint32_t> vertices;  ///< the vertices estimated (global indices)
  std::vector<Rgb> radiance;            ///< exit radiance R(p), one per entry of `vertices`
  std::vector<Rgb> stdError;            ///< its standard error, per channel
  /// With settings.bandLimit, at [i·K + k] for vertex entry i and limit k of K.
  std::vector<BandLimitedEstimate> bandLimited;
  std::uint64_t rays = 0;
  double seconds = 0;
};

/// The path-tracing estimator over one scene, environment and settings. Thread-safe (const).
class ReferenceIntegrator {
 public:
  /// `mesh` (whose triangles `occluder` was built from) and `sampler` must outlive it.
  ReferenceIntegrator(const Mesh& mesh, const Occluder& occluder, const EnvironmentSampler& sampler,
                      const ReferenceSettings& settings);

  /// e(p, v) at point p with unit normal n, unit direction v toward the eye (used only when the
  /// material is glossy) and diffuse colour kd: kd/π ∫ L_in max(n·ω,0) dω + ks ∫ L_in G(r·ω) dω
  /// from `samples` samples of the random streams `seed`. `rays` (if given) is incremented by
  /// the rays cast.
  Estimate estimate(const Vec3f& p, const Vec3f& n, const Vec3f& v, const Rgb& kd, int samples,
                    std::uint64_t seed, std::uint64_t* rays = nullptr) const;
  /// estimate() (the same value, bit for bit) and, from the same samples, the estimates of
  /// each band limit k of settings.bandLimit (required) into out[k].
  Estimate estimateBandLimited(const Vec3f& p, const Vec3f& n, const Vec3f& v, const Rgb& kd,
                               int samples, std::uint64_t seed, std::span<BandLimitedEstimate> out,
                               std::uint64_t* rays = nullptr) const;

 private:
  struct Lanes;          ///< a path's radiance under L and under each band-limited light
  struct BandLimitData;  ///< the lanes' light and kernel coefficients

  template <class R>
  R incoming(const Vec3f& p, const Vec3f& n, int bouncesLeft, Pcg32& rng,
             std::uint64_t& rays) const;
  template <class R>
  R glossy(const Vec3f& p, const Vec3f& n, const Vec3f& r, int bounces, Pcg32& rng,
           std::uint64_t& rays) const;
  template <class R>
  R frontHit(const Hit& h, const Vec3f& w, int bouncesLeft, Pcg32& rng, std::uint64_t& rays) const;
  /// The environment's radiance along an escaping ray, `texel` in direction `envDir`
  /// (environment frame): the texel itself, or for Lanes also each L_b(envDir).
  template <class R>
  R sky(const Vec3f& envDir, const Rgb& texel) const;
  /// One sample of ∫_{n·ω>0} (K − K_b)(ω) L_in[L_b](ω) dω per band limit, into out[k].
  void kernelResidual(const Vec3f& p, const Vec3f& n, const Vec3f& r, const Rgb& kd, int bounces,
                      Pcg32& rng, std::uint64_t& rays, Rgb* out) const;
  bool sampleEnvironment(Pcg32& rng, Vec3f& w, Vec3f& envDir, double& pe, Rgb& le) const;
  bool unblocked(const Vec3f& origin, const Vec3f& w, std::uint64_t& rays) const;
  /// The heuristic's weight of strategy a among those with densities pa, pb, pc.
  double misWeight(double pa, double pb, double pc = 0.0) const;
  Rgb hitAlbedo(std::uint32_t tri, float u, float v) const;

  const Mesh& mesh_;
  std::vector<Rgb> albedo_;  ///< the diffuse colour at each vertex (geometry: albedoAtVertices)
  const Occluder& occluder_;
  const EnvironmentSampler& sampler_;
  ReferenceSettings settings_;
  Mat3d rotT_;                                 ///< Rᵀ: world → environment frame
  std::shared_ptr<const BandLimitData> band_;  ///< set with settings.bandLimit
};

/// The per-vertex work of renderReference over entries of its vertex list, for schedulers that
/// split it (MPI ranks, prt/distributed/): every entry is a pure function of the scene, the
/// settings and its vertex index, so computing all entries in any pieces gives renderReference's
/// result bit for bit. Validates the settings as renderReference does.
class ReferenceRows {
 public:
  /// `mesh`, `occluder` and `env` must outlive it.
  ReferenceRows(const Mesh& mesh, const Occluder& occluder, const envmap::Environment& env,
                const ReferenceSettings& settings);
  ~ReferenceRows();
  /// The vertices estimated, one entry each (settings.vertices, or every vertex).
  const std::vector<std::uint32_t>& vertices() const { return vertices_; }
  /// Band-limited estimates per entry (settings.bandLimit's limits; 0 without).
  std::size_t lanes() const { return lanes_; }
  /// Entries [first, first + count): radiance and stdError (count each), bandLimited
  /// (count × lanes(); may be null when lanes() is 0) and rays (count). Parallel over the
  /// entries; advances `progress` per entry.
  void compute(std::size_t first, std::size_t count, Rgb* radiance, Rgb* stdError,
               BandLimitedEstimate* bandLimited, std::uint64_t* rays,
               Progress* progress = nullptr) const;

 private:
  const Mesh& mesh_;
  std::vector<Rgb> albedo_;  ///< the diffuse colour at each vertex (geometry: albedoAtVertices)
  ReferenceSettings settings_;
  std::vector<std::uint32_t> vertices_;
  std::vector<std::size_t> entries_;  ///< per vertex: its entry in settings.points (or itself)
  std::size_t lanes_ = 0;
  std::unique_ptr<EnvironmentSampler> sampler_;
  std::unique_ptr<ReferenceIntegrator> integrator_;
};

/// Per-vertex reference radiance e(p, v), v = normalize(eye − p). kd: material.diffuse, else the
/// mesh's albedo, else 1. Parallel over vertices, progress per vertex; throws prt::Error on bad
/// settings (samples < 1 or > 2^24, bounces out of 0..16, vertex index out of range, a glossy
/// material without an eye, a band limit beyond the light or sh::kMaxBands of them) and
/// prt::Cancelled.
ReferenceResult renderReference(const Mesh& mesh, const Occluder& occluder,
                                const envmap::Environment& env, const ReferenceSettings& settings,
                                const ProgressFn& progress = {});

}  // namespace prt::render
