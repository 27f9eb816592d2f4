#include "prt/transport/bake.hpp"

// Diffuse PRT baking (Sloan, Kautz & Snyder 2002, §5). See docs/transport.md for the
// derivation of each estimator and of the error estimates reported in BakeStats.
//
// Structure: one "pass" per transport order. Pass 0 (direct) gathers Y_i(ω)·V(ω) over
// cosine-distributed directions; pass k ≥ 1 gathers ρ(h)·Tᵏ⁻¹(h) at the closest front-facing hit
// h. Each vertex draws its own, independent sample set per pass from
// (seed, pass, global vertex index) — the same scrambled Sobol' points shared by all vertices,
// Owen-scrambled with per-vertex seeds — so results never depend on threads or on the range.
//
// Memory: the direct and shadowed modes keep nothing per sample: per worker only B² (×3)
// accumulators and a batch of 64 rays. Inter-reflection needs the previous order Tᵏ⁻¹ for the
// whole mesh (hits land anywhere), so it holds two full-mesh working buffers (Tᵏ⁻¹ and Tᵏ) beside
// the output; for K = 1 bounce the working Tᵏ is added straight into the output.

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>
#include <string>

#include "bake_common.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"
#include "prt/sh/sh_fixed.hpp"
#include "prt/transport/passes.hpp"

namespace prt {

namespace {

using namespace bakedetail;

constexpr std::size_t kBatch = 64;            // rays traced per batch
constexpr int kFlushEvery = 4 * kBatch;       // samples summed in float before going to double
constexpr std::size_t kVertexGrain = 4;       // vertices per parallel task
constexpr double kY00 = 0.28209479177387814;  // 1/√(4π)

/// SH evaluation for the bake's band count: the unrolled evaluator for B ≤ sh::kFixedBands,
/// picked once (sh::dispatchBands), else the general one.
struct ShEval {
  using Fn = void (*)(const Vec3f&, float*);
  int bands;
  Fn fixed;
  explicit ShEval(int b)
      : bands(b),
        fixed(sh::dispatchBands<sh::kFixedBands>(
            b,
            []<int B>() -> Fn {
              return [](const Vec3f& d, float* out) { sh::evalFixed<B>(d, out); };
            },
            []() -> Fn { return nullptr; })) {}
  void operator()(const Vec3f& d, float* out) const {
    if (fixed)
      fixed(d, out);
    else
      sh::eval(bands, d, out);
  }
};

/// The previous pass at a hit, for a vertex-domain transfer: the barycentric blend of the hit
/// triangle's vertex rows (`stride` floats each).
struct VertexLookup {
  const Mesh& mesh;
  const float* rows;
  std::size_t stride;
  void operator()(const Hit& h, const std::array<std::uint32_t, 3>& tri, float* out) const {
    const float b0 = 1.0f - h.u - h.v;
    const float* r0 = rows + tri[0] * stride;
    const float* r1 = rows + tri[1] * stride;
    const float* r2 = rows + tri[2] * stride;
    for (std::size_t i = 0; i < stride; ++i) out[i] = b0 * r0[i] + h.u * r1[i] + h.v * r2[i];
  }
};

/// The previous pass at a hit, for a texel-domain transfer: its lightmap image (dilated) read
/// bilinearly at the hit's lightmap UV (the hit triangle's UVs blended; bilinearTaps).
struct TexelLookup {
  const TexelImage& image;
  void operator()(const Hit& h, const std::array<std::uint32_t, 3>& tri, float* out) const {
    const TexelTaps taps = image.tapsAt(tri, h.u, h.v);
    const std::size_t s = image.stride;
    const float* r00 = image.row(taps.texel[0]);
    const float* r10 = image.row(taps.texel[1]);
    const float* r01 = image.row(taps.texel[2]);
    const float* r11 = image.row(taps.texel[3]);
    const auto& w = taps.weight;
    for (std::size_t i = 0; i < s; ++i)
      out[i] = w[0] * r00[i] + w[1] * r10[i] + w[2] * r01[i] + w[3] * r11[i];
  }
};

/// Sample directions of one row in one pass: sample s has direction dir and weight w such
/// that T ≈ (1/N) Σ_s w_s f(dir_s) with f the integrand without the (1/π) cos factor.
class RowSampler {
 public:
  RowSampler(const BakeSettings& s, const OwenSobol2D* sobol, std::size_t row, int pass,
             const Vec3f& n)
      : sobol_(sobol), n_(n), rng_(0) {
    const std::uint64_t key = deriveSeed(deriveSeed(s.seed, static_cast<std::uint64_t>(pass)),
                                         static_cast<std::uint64_t>(row));
    seed0_ = static_cast<std::uint32_t>(key);
    seed1_ = static_cast<std::uint32_t>(key >> 32);
    if (sobol_)
      orthonormalBasis(n_, t_, b_);
    else
      rng_ = Pcg32(key);
  }
  /// The next `count` (<= 64) samples' directions and weights; w == 0: below the horizon
  /// (uniform sampling only), cast no ray. Same values as `count` calls of next().
  void batch(int count, Vec3f* dir, float* w) {
    if (!sobol_) {
      for (int j = 0; j < count; ++j) next(dir[j], w[j]);
      return;
    }
    float x[64], y[64], z[64];
    sobol_->cosineBatch(index_, static_cast<std::uint32_t>(count), seed0_, seed1_, x, y, z);
    index_ += static_cast<std::uint32_t>(count);
    for (int j = 0; j < count; ++j) {
      dir[j] = t_ * x[j] + b_ * y[j] + n_ * z[j];
      w[j] = 1.0f;
    }
  }
  /// The unit-square point of sample i (cosine-Sobol' only): where it lies in the net.
  Point2 unitPoint(std::uint32_t i) const { return sobol_->point(i, seed0_, seed1_); }
  /// Next sample. w == 0: below the horizon (uniform sampling only), cast no ray.
  void next(Vec3f& dir, float& w) {
    if (sobol_) {
      // Cosine-weighted: (1/π) Y V cos / (cos/π) = Y V, weight 1.
      const Point2 u = sobol_->point(index_++, seed0_, seed1_);
      const Vec3f l = cosineHemisphere(u.x, u.y);
      dir = t_ * l.x + b_ * l.y + n_ * l.z;
      w = 1.0f;
    } else {
      // Uniform sphere, pdf 1/(4π): (1/π) Y V max(cos,0) · 4π = 4 max(cos,0) Y V.
      const float u1 = rng_.uniform(), u2 = rng_.uniform();
      dir = uniformSphere(u1, u2);
      const float c = dot(n_, dir);
      w = c > 0.0f ? 4.0f * c : 0.0f;
    }
  }

 private:
  const OwenSobol2D* sobol_;
  Vec3f n_, t_, b_;
  std::uint32_t seed0_ = 0, seed1_ = 0, index_ = 0;
  Pcg32 rng_;
};

/// The error of a row's pilot, as a scrambled net knows it. The pilot's 64 points are a
/// scrambled (0,6,2)-net (Owen 1995), so each of the 32 elementary boxes of 1/8 × 1/4 of the
/// unit square holds two of them: the pilot is a stratified sample with two points per stratum,
/// and Var(Î) ≈ Σ_h (k_h/64)² s_h²/k_h over the boxes h (k_h points, sample variance s_h²) —
/// which measures how much of the integrand's jump (the visibility's edge) the boxes cut, not
/// its i.i.d. variance, and is conservative for the net, whose two points in a box are
/// themselves stratified. (The i.i.d. variance p(1−p)/N of a row blocked over a share p
/// would spend most rays on half-blocked rows, whose net error is small, and too few on thinly
/// blocked ones: at equal rays it loses to equal sampling; tests/transport.)
class PilotStrata {
 public:
  void add(Point2 u, double x) {
    const int cell = std::min(int(u.x * 8.0f), 7) * 4 + std::min(int(u.y * 4.0f), 3);
    sum_[cell] += x;
    squares_[cell] += x * x;
    ++count_[cell];
    ++total_;
  }
  /// The variance of the pilot's mean (0 when every box holds equal values).
  double varianceOfMean() const {
    double var = 0;
    for (int h = 0; h < kCells; ++h) {
      const int k = count_[h];
      if (k < 2) continue;
      const double s2 = std::max(0.0, (squares_[h] - sum_[h] * sum_[h] / k) / (k - 1));
      const double w = double(k) / total_;
      var += w * w * s2 / k;
    }
    return var;
  }

 private:
  static constexpr int kCells = 32;
  std::array<double, kCells> sum_{}, squares_{};
  std::array<int, kCells> count_{};
  int total_ = 0;
};

struct Context {
  const Mesh& mesh;
  const Occluder& occluder;
  const BakeSettings& settings;
  int nc;  // B²
  ShEval eval;
  const OwenSobol2D* sobol;  ///< null: uniform random sampling
  const BounceAlbedo& albedo;
  const std::vector<double>& lobe;  ///< A_l/π of the clamped cosine, l = 0..B-1
  /// Adaptive sampling (BakeRecipe::targetError): the standard error of √(4π)·T₀ each pass aims
  /// for, E/√P over the P passes (adaptivePassTarget); 0: every row casts `samples`.
  double passTarget = 0;
  std::atomic<std::uint64_t> rays{0};
  /// The directions a row casts first: all of them, or the pilot when adaptive.
  int firstSamples() const {
    return passTarget > 0 ? std::min(settings.samples, kAdaptivePilotSamples) : settings.samples;
  }
  /// After the pilot: the directions the row casts in all, from the variance `pilotVar` of the
  /// pilot's estimate of √(4π)·T₀ (PilotStrata) — the power of two N within [pilot, samples]
  /// at which
  ///   pilotVar · (64/N)^{3/2} ≤ E²   (the net's error, falling as N^-3/4, reaches the target)
  ///   and N ≥ 1/E,
  /// the second because a pilot that saw nothing blocked estimates 0 yet may have missed a
  /// blocked cosine-weighted share of about 1/N (a sliver at the horizon): N ≥ 1/E makes a
  /// share of E show up about once. Decided once, from the pilot (the second stage of Stein's
  /// rule), so the samples after it are not chosen by what they show.
  int samplesAfterPilot(double pilotVar) const {
    const double e2 = passTarget * passTarget;
    const double byError = kAdaptivePilotSamples * std::pow(pilotVar / e2, 2.0 / 3.0);
    const double needed = std::max(byError, 1.0 / passTarget);
    int n = firstSamples();
    while (n < settings.samples && double(n) < needed) n = std::min(settings.samples, 2 * n);
    return n;
  }
};

/// Float partial sums over a few batches, then double: accurate to ~1e-7 relative even at
/// 2^24 samples, and in a fixed order.
struct Accumulator {
  std::vector<float> part;
  std::vector<double> total;
  std::vector<double> lobe;  ///< the vertex's unshadowed transfer (A_l/π) Y_lm(n)
  explicit Accumulator(std::size_t n) : part(n, 0.0f), total(n, 0.0), lobe(n, 0.0) {}
  void flush() {
    for (std::size_t i = 0; i < part.size(); ++i) {
      total[i] += part[i];
      part[i] = 0.0f;
    }
  }
  void reset() {
    std::fill(part.begin(), part.end(), 0.0f);
    std::fill(total.begin(), total.end(), 0.0);
  }
};

/// Pass 0: T⁰_i(v) = (1/π) ∫ Y_i V max(n·ω,0) dω, written to out[0..B²). Returns Var(T⁰₀).
/// Adaptive (ctx.passTarget > 0): the pilot first, then as many more as samplesAfterPilot
/// asks, all summed into the one estimate over the row's N.
///
/// Cosine-Sobol' uses the unshadowed transfer as a control variate: V = 1 − (1 − V), and the
/// unshadowed part is known in closed form, U_lm(n) = (A_l/π) Y_lm(n) (the clamped-cosine lobe,
/// Ramamoorthi & Hanrahan 2001), so
///   T⁰_i ≈ U_i(n) − (1/N) Σ_s Y_i(ω_s) [ω_s blocked].
/// Unbiased (E[(1/N) Σ Y_i] = U_i), and with scrambled Sobol' points its error equals that of the
/// plain estimator (1/N) Σ Y_i V up to the QMC error of the smooth integral (1/N) Σ Y_i ≈ U_i
/// (≤ 1e-3 per coefficient at 1024 samples, typically far less; tests/transport). SH is then
/// evaluated for blocked rays only, and unshadowed transfer and unoccluded vertices come out
/// exact. Uniform random sampling keeps the course's plain
/// estimator (1/N) Σ 4 max(n·ω,0) Y_i V.
double directRow(Context& ctx, const RowPoint& q, float* out, Accumulator& acc,
                 std::vector<float>& y) {
  int n = ctx.firstSamples();
  const int nc = ctx.nc;
  const bool shadowed = ctx.settings.mode != TransferMode::Unshadowed;
  const bool controlVariate = ctx.sobol != nullptr;
  const Vec3f p = q.position, nrm = q.normal;
  if (controlVariate) {
    sh::eval(ctx.settings.bands, Vec3d(nrm), acc.lobe.data());
    for (int l = 0; l < ctx.settings.bands; ++l)
      for (int i = l * l; i < (l + 1) * (l + 1); ++i) acc.lobe[i] *= ctx.lobe[l];
    if (!shadowed) {
      for (int i = 0; i < nc; ++i) out[i] = static_cast<float>(acc.lobe[i]);
      return 0.0;
    }
  }
  const Vec3f origin = shadowed ? p + nrm * ctx.occluder.rayOffset(p) : p;
  RowSampler sampler(ctx.settings, ctx.sobol, q.id, 0, nrm);

  std::array<Ray, kBatch> rays;
  std::array<float, kBatch> w, ws;
  std::array<Vec3f, kBatch> dirs;
  std::array<std::uint8_t, kBatch> blocked;
  Moments m;
  PilotStrata pilot;
  std::uint64_t cast = 0;
  acc.reset();
  float* part = acc.part.data();
  // Samples that contribute: blocked ones for the control variate, visible ones otherwise.
  const std::uint8_t counted = controlVariate ? 1 : 0;
  for (int base = 0; base < n; base += static_cast<int>(kBatch)) {
    const int count = std::min<int>(kBatch, n - base);
    std::size_t nr = 0;
    sampler.batch(count, dirs.data(), ws.data());
    for (int j = 0; j < count; ++j) {
      if (ws[j] <= 0.0f) continue;
      rays[nr] = Ray{origin, dirs[j], 0.0f, std::numeric_limits<float>::infinity()};
      w[nr++] = ws[j];
    }
    if (shadowed && nr > 0) {
      ctx.occluder.occluded(std::span<const Ray>(rays.data(), nr),
                            std::span<std::uint8_t>(blocked.data(), nr));
      cast += nr;
    } else {
      std::fill_n(blocked.begin(), nr, std::uint8_t(0));
    }
    if (ctx.passTarget > 0 && base < ctx.firstSamples())  // the pilot (cosine-Sobol': nr = count)
      for (std::size_t j = 0; j < nr; ++j)
        pilot.add(sampler.unitPoint(static_cast<std::uint32_t>(base + j)),
                  blocked[j] == counted ? w[j] : 0.0f);
    for (std::size_t j = 0; j < nr; ++j) {
      if (blocked[j] != counted) continue;
      ctx.eval(rays[j].dir, y.data());
      const float wj = w[j];
      for (int i = 0; i < nc; ++i) part[i] += wj * y[i];
      m.add(wj);
    }
    if ((base + static_cast<int>(kBatch)) % kFlushEvery == 0) acc.flush();
    // √(4π)·T₀'s integrand is w [blocked] (√(4π)·Y00 = 1).
    if (ctx.passTarget > 0 && base + count == ctx.firstSamples())
      n = ctx.samplesAfterPilot(pilot.varianceOfMean());
  }
  acc.flush();
  for (int i = 0; i < nc; ++i)
    out[i] = static_cast<float>(controlVariate ? acc.lobe[i] - acc.total[i] / n : acc.total[i] / n);
  ctx.rays.fetch_add(cast, std::memory_order_relaxed);
  // T⁰₀ = Y00 · (U-part or 0 − or +) mean(w [counted]): variance Y00² Var(mean).
  return kY00 * kY00 * m.varianceOfMean(n);
}

/// Pass k ≥ 1: Tᵏ(v) = (1/N) Σ w ρ(h) ⊙ Tᵏ⁻¹(h) over samples whose closest hit h is a front face
/// (the light a diffuse surface sends toward v leaves its front side only; a back face blocks
/// the direction and contributes nothing). prev(h, triangle, t) puts Tᵏ⁻¹ at the hit into t
/// (prevChannels per coefficient; VertexLookup for vertex rows); out gets B² × outChannels
/// values (added to when accumulate). Returns Var(Tᵏ₀, channel 0). Adaptive as directRow.
template <typename Lookup>
double bounceRow(Context& ctx, const RowPoint& q, int pass, const Lookup& prev, int prevChannels,
                 float* out, int outChannels, bool accumulate, Accumulator& acc,
                 std::vector<float>& t) {
  const Mesh& mesh = ctx.mesh;
  int n = ctx.firstSamples();
  const int nc = ctx.nc;
  const int width = nc * outChannels;
  const Vec3f p = q.position, nrm = q.normal;
  const Vec3f origin = p + nrm * ctx.occluder.rayOffset(p);
  RowSampler sampler(ctx.settings, ctx.sobol, q.id, pass, nrm);

  Moments m;
  PilotStrata pilot;
  std::uint64_t cast = 0;
  acc.reset();
  float* part = acc.part.data();
  for (int s = 0; s < n; ++s) {
    Vec3f d;
    float wt;
    sampler.next(d, wt);
    double x = 0;  // this sample's T₀ contribution (channel 0)
    if (wt > 0.0f) {
      ++cast;
      const Hit h =
          ctx.occluder.intersect(Ray{origin, d, 0.0f, std::numeric_limits<float>::infinity()});
      if (h.hit) {
        const auto& tri = mesh.triangles[h.triangle];
        const Vec3f p0 = mesh.positions[tri[0]];
        const Vec3f ng = cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
        if (dot(ng, d) < 0.0f) {
          prev(h, tri, t.data());
          const Rgb rho = ctx.albedo.at(tri, h.u, h.v) * wt;
          if (outChannels == 1) {
            for (int i = 0; i < nc; ++i) part[i] += rho.x * t[i];
          } else if (prevChannels == 1) {
            for (int i = 0; i < nc; ++i) {
              part[3 * i + 0] += rho.x * t[i];
              part[3 * i + 1] += rho.y * t[i];
              part[3 * i + 2] += rho.z * t[i];
            }
          } else {
            for (int i = 0; i < nc; ++i) {
              part[3 * i + 0] += rho.x * t[3 * i + 0];
              part[3 * i + 1] += rho.y * t[3 * i + 1];
              part[3 * i + 2] += rho.z * t[3 * i + 2];
            }
          }
          x = double(rho.x) * t[0];
          m.add(x);
        }
      }
    }
    if ((s + 1) % kFlushEvery == 0) acc.flush();
    if (ctx.passTarget > 0 && s < ctx.firstSamples()) {
      pilot.add(sampler.unitPoint(static_cast<std::uint32_t>(s)), x);
      if (s + 1 == ctx.firstSamples())
        n = ctx.samplesAfterPilot(4.0 * kPi * pilot.varianceOfMean());
    }
  }
  acc.flush();
  for (int i = 0; i < width; ++i) {
    const float value = static_cast<float>(acc.total[i] / n);
    out[i] = accumulate ? out[i] + value : value;
  }
  ctx.rays.fetch_add(cast, std::memory_order_relaxed);
  return m.varianceOfMean(n);
}

/// The ray rate over the ray-casting passes (the direct pass only when it cast rays) and the
/// standard errors of T₀ and of the radiance under the constant light.
BakeStats finishStats(BakeStats st, std::uint64_t directRays, const std::vector<double>& variance) {
  double traceSeconds = directRays > 0 ? st.secondsDirect : 0.0;
  for (double b : st.secondsBounce) traceSeconds += b;
  st.raysPerSecond = raysPerSecondOf(st.rays, traceSeconds);
  const StandardErrors t0 = standardErrors(variance);
  const double scale = std::sqrt(4.0 * kPi);  // T·L for L = 1 is √(4π) T₀
  st.stdErrT0Mean = t0.mean;
  st.stdErrT0Max = t0.max;
  st.stdErrConstMean = st.stdErrT0Mean * scale;
  st.stdErrConstMax = st.stdErrT0Max * scale;
  return st;
}

}  // namespace

Material materialFromGloss(const SurfaceGloss& g) {
  const auto clamp01 = [](float x) { return std::clamp(x, 0.0f, 1.0f); };
  Material m;
  m.specular = Rgb(clamp01(g.specular.x), clamp01(g.specular.y), clamp01(g.specular.z));
  if (g.model == SurfaceGloss::Model::Phong) {
    m.lobe.kind = LobeKind::Phong;
    m.lobe.exponent = std::clamp(double(g.exponent), 0.0, kMaxPhongExponent);
  } else {
    m.lobe.kind = LobeKind::Ggx;
    m.lobe.roughness = std::clamp(double(g.roughness), kMinGgxRoughness, 1.0);
  }
  return m;
}

namespace bakedetail {

/// What every pass of a vector bake shares: the sample table, the clamped-cosine lobe, the
/// bounce albedo.
struct VectorSetup {
  BakeSettings settings;
  std::unique_ptr<OwenSobol2D> sobol;
  BounceAlbedo albedo;
  std::vector<double> lobe;
};

std::shared_ptr<const VectorSetup> makeVectorSetup(const Mesh& mesh, const BakeSettings& s) {
  auto setup = std::make_shared<VectorSetup>();
  setup->settings = s;
  setup->albedo = resolveAlbedo(mesh, setup->settings);
  for (double a : sh::clampedCosineKernel(s.bands)) setup->lobe.push_back(a / kPi);
  if (s.sampling == Sampling::CosineSobol)
    setup->sobol = std::make_unique<OwenSobol2D>(static_cast<std::uint32_t>(s.samples));
  return setup;
}

bool vectorAlbedoGrey(const VectorSetup& setup) {
  return setup.albedo.grey;
}

namespace {

/// Context::passTarget of a vector bake: its target error E shared among its P = 1 + bounces
/// passes (independent estimators, so their variances add): E/√P each.
double adaptivePassTarget(const BakeSettings& s) {
  return s.adaptive() ? s.targetError / std::sqrt(1.0 + s.effectiveBounces()) : 0.0;
}

/// Rows 0..count−1 of vector pass `pass` at pointOf(r), the previous pass read through `lookup`
/// (pass ≥ 1), in parallel: the loop every domain shares.
template <typename PointOf, typename Lookup>
std::uint64_t computeRows(const Mesh& mesh, const Occluder& occluder, const VectorSetup& setup,
                          int pass, std::size_t count, const PointOf& pointOf, const Lookup& lookup,
                          int prevChannels, int outChannels, float* out, double* variance,
                          Progress* progress) {
  Context ctx{mesh,
              occluder,
              setup.settings,
              setup.settings.bands * setup.settings.bands,
              ShEval(setup.settings.bands),
              setup.sobol.get(),
              setup.albedo,
              setup.lobe,
              adaptivePassTarget(setup.settings),
              {}};
  const int nc = ctx.nc;
  const std::size_t width = static_cast<std::size_t>(nc) * (pass == 0 ? 1 : outChannels);
  parallelFor(count, kVertexGrain, [&](std::size_t b, std::size_t e) {
    if (progress) progress->check();
    Accumulator acc(static_cast<std::size_t>(nc) * 3);
    std::vector<float> tmp(static_cast<std::size_t>(nc) * 3);
    for (std::size_t r = b; r < e; ++r) {
      const RowPoint q = pointOf(r);
      const double var = pass == 0 ? directRow(ctx, q, out + r * width, acc, tmp)
                                   : bounceRow(ctx, q, pass, lookup, prevChannels, out + r * width,
                                               outChannels, false, acc, tmp);
      if (variance) variance[r] = var;
    }
    if (progress) progress->advance(e - b);
  });
  return ctx.rays.load();
}

}  // namespace

std::uint64_t computeVectorRows(const Mesh& mesh, const Occluder& occluder,
                                const VectorSetup& setup, int pass, RowRange rows,
                                const Transfer* prev, int outChannels, float* out, double* variance,
                                Progress* progress) {
  const int nc = setup.settings.bands * setup.settings.bands;
  const float* prevData = pass > 0 ? prev->values().data() : nullptr;
  const int prevChannels = pass > 0 ? prev->channels() : 1;
  const VertexLookup lookup{mesh, prevData, static_cast<std::size_t>(nc) * prevChannels};
  const auto vertex = [&](std::size_t r) {
    const std::size_t v = rows.first + r;
    return RowPoint{mesh.positions[v], mesh.normals[v], v};
  };
  return computeRows(mesh, occluder, setup, pass, rows.count, vertex, lookup, prevChannels,
                     outChannels, out, variance, progress);
}

std::uint64_t computeTexelRows(const Mesh& mesh, const Occluder& occluder, const VectorSetup& setup,
                               int pass, std::span<const RowPoint> points, const TexelImage* prev,
                               int outChannels, float* out, double* variance, Progress* progress) {
  const int nc = setup.settings.bands * setup.settings.bands;
  const TexelImage none{};
  const TexelLookup lookup{prev ? *prev : none};
  const int prevChannels = prev ? int(prev->stride / std::size_t(nc)) : 1;
  return computeRows(
      mesh, occluder, setup, pass, points.size(), [&](std::size_t r) { return points[r]; }, lookup,
      prevChannels, outChannels, out, variance, progress);
}

BakeStats vectorStats(const std::vector<std::uint64_t>& rays, const std::vector<double>& seconds,
                      const std::vector<double>& variance) {
  BakeStats st;
  for (std::uint64_t r : rays) st.rays += r;
  st.secondsDirect = seconds.empty() ? 0.0 : seconds[0];
  for (std::size_t k = 1; k < seconds.size(); ++k) {
    st.secondsBounce.push_back(seconds[k]);
    st.raysBounce.push_back(rays[k]);
  }
  return finishStats(std::move(st), rays.empty() ? 0 : rays[0], variance);
}

}  // namespace bakedetail

Transfer bake(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
              BakeStats* stats, const ProgressFn& progressFn) {
  ThreadExecutor threads;
  return bake(mesh, occluder, settings, threads, stats, progressFn);
}

}  // namespace prt
