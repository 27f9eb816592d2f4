// Glossy transfer matrices per vertex or per texel sample point (Sloan, Kautz & Snyder 2002, §6):
//
//   M_ij(p) = ∫_{n·ω>0} Y_i(ω) V(p,ω) Y_j(ω) dω   (+ the light bounced off the scene)
//
// maps the source light's SH L to the SH of the light arriving at p, L'_p = M_p L. See
// prt/transport/bake.hpp for the bounce term and docs/transport.md for the estimators.
//
// Estimator. Directions are uniform over the hemisphere about n (Owen-scrambled Sobol' points,
// per-vertex seeds; pdf 1/(2π)): the integrand Y_i Y_j V has no cosine to importance-sample, and
// the lobe that will meet it is chosen at relighting time. As in the vector bake, the visibility
// enters through a control variate: V = 1 − (1 − V), and the unshadowed part is exact,
//
//   M_ij ≈ H_ij(n) − (2π/N) Σ_{s blocked} Y_i(ω_s) Y_j(ω_s),
//
// H(n) = ∫_{n·ω>0} Y Yᵀ dω the hemisphere product matrix. H about +Z is computed once by a
// quadrature that is exact for it (Gauss–Legendre in cos θ, uniform in φ) and turned to n by
// the SH rotation D(R) (R z = n): H(n) = D H_z Dᵀ. Unshadowed transfer is H(n) itself; an
// unoccluded vertex comes out exact.
//
// Bounces. The light a front-facing hit h sends back toward p is what its surface reflects of
// the light arriving at h. A diffuse surface reflects ρ(h) (T^{K−1}(h)·L) with T^{K−1} the
// diffuse vector transfer of one bounce less, whatever the direction; a glossy one (the
// material's lobe, ks > 0) sends (M^{K−1}(h) L)·r(h, −ω) with
//
//   r(h, −ω) = ρ(h) d(n_h) + ks g(R_h(−ω)),   d_i = (A_l/π) Y_i(n_h),  g_i = Λ_l Y_i(R_h(−ω)),
//
// R_h(−ω) the direction back toward p reflected in h's normal (prepared_material.hpp): the same
// exit radiance relighting computes, seen from p. So the bounced term's column is
// z = M^{K−1}(h)ᵀ r, with M^{K−1} the matrices of K − 1 bounces, baked first over the whole mesh
// (the recursion ends at the shadowed matrices) and interpolated over the hit triangle as
// Σ_k b_k M_kᵀ r — per texel, the previous order's lightmap is read at the hit's lightmap UV
// through its four bilinear taps instead, Σ_k w_k M_kᵀ r (bake_texels.cpp). Each order draws its
// own directions (the seed is derived per order), so the orders' errors are independent.
//
// Probes (the probe domain, prt/transfer/probe_grid.hpp) integrate over the whole sphere: no
// surface, no normal. Directions are uniform over S² (pdf 1/(4π)), the unshadowed part is
// ∫_{S²} Y Yᵀ dω = I (orthonormality), so
//
//   M_ij ≈ δ_ij − (4π/N) Σ_{s blocked} Y_i(ω_s) Y_j(ω_s)  (+ (4π/N) Σ_{s front hit} Y_i z_j),
//
// with the bounce columns z of the surfaces' diffuse transfer as above, and a probe in open
// space comes out exactly the identity. Rays leave the probe itself (no offset: it lies on no
// surface). Every probe casts the same N directions ω'_s (Owen-scrambled Sobol' points of the
// pass's seed, made once with their SH Y(ω'_s)) turned by its own uniformly random rotation R_p
// (Shoemake's quaternion from three uniforms of the probe's seed): a randomly rotated QMC set,
// unbiased and independent from probe to probe as per-probe scrambles are. Since
// Y(R ω') = D(R) Y(ω') (D the SH rotation, sh/rotate.hpp), the sums are taken over the set's
// own Y and turned once per probe, Σ Y Yᵀ = D (Σ Y' Y'ᵀ) Dᵀ and Σ Y zᵀ = D (Σ Y' zᵀ): no SH
// evaluation and no direction sampling per ray, only R ω'.
//
// Speed. Samples are batched 64 at a time; the blocked ones form the columns of Y (B² × k) and
// enter as one symmetric rank-k update P += Y Yᵀ (Eigen's selfadjointView::rankUpdate, the
// lower triangle only), the bounce term as one GEMM G += Y Zᵀ with Z the hit points' bounced
// transfer. Probes skip both the SH and the rank update: a blocked ray's direction is one of the
// set's, whose packed Y Yᵀ (B²(B² + 1)/2 floats) the pass tabulated, so a batch adds the table's
// columns weighted by its blocked mask (one GEMV); the table is kept up to 64 MiB (past it the
// set's Y columns go through the rank update). Float within a batch group, double across groups
// (as the vector bake), per vertex in a fixed order: bit-identical for any thread count and any
// vertex range.

#include <Eigen/Dense>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <span>
#include <string>

#include "bake_common.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/quadrature.hpp"
#include "prt/core/sampling.hpp"
#include "prt/sh/rotate.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/prepared_material.hpp"

namespace prt::bakedetail {

namespace {

constexpr std::size_t kBatch = 64;
constexpr int kFlushBatches = 4;  // float rank updates summed before going to double
/// Probes: the largest packed Y Yᵀ table of a direction set (B²(B² + 1)/2 × N floats) kept.
constexpr std::size_t kMaxPackedSetBytes = std::size_t(64) << 20;
constexpr std::size_t kVertexGrain = 2;
constexpr std::uint64_t kMatrixPass = 0x6d61747269780000ull;   // decorrelates from vector passes
constexpr std::uint64_t kBounceOrder = 0x626f756e63650000ull;  // one seed per bounce order

using MatF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic>;
using MatD = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;
using RowMatF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

MatD hemisphereProductZ(int bands) {
  // Y_i Y_j restricted to one m is a polynomial of degree ≤ 2(B−1) in cos θ times a
  // trigonometric polynomial of degree ≤ 2(B−1) in φ: B Gauss points and 4B φ steps are exact.
  const int nc = bands * bands;
  const QuadratureRule rule = gaussLegendre(bands + 1, 0.0, 1.0);
  const std::vector<double>& t = rule.nodes;
  const std::vector<double>& w = rule.weights;
  const int nphi = 4 * bands;
  MatD h = MatD::Zero(nc, nc);
  std::vector<double> y(nc);
  for (std::size_t a = 0; a < t.size(); ++a) {
    const double s = std::sqrt(std::max(0.0, 1 - t[a] * t[a]));
    for (int k = 0; k < nphi; ++k) {
      const double phi = 2 * kPi * (k + 0.5) / nphi;
      sh::eval(bands, Vec3d(s * std::cos(phi), s * std::sin(phi), t[a]), y.data());
      const double wk = w[a] * 2 * kPi / nphi;
      for (int i = 0; i < nc; ++i)
        for (int j = 0; j < nc; ++j) h(i, j) += wk * y[i] * y[j];
    }
  }
  return h;
}

/// H(n) = D H_z Dᵀ with D the SH rotation of R = [t b n] (R z = n).
void hemisphereProduct(const MatD& hz, int bands, const Vec3d& n, MatD& out, MatD& tmp,
                       MatD& tmpT) {
  Vec3d t, b;
  orthonormalBasis(n, t, b);
  Mat3d r;
  for (int k = 0; k < 3; ++k) {
    r.m[k][0] = t[k];
    r.m[k][1] = b[k];
    r.m[k][2] = n[k];
  }
  const sh::Rotation rot(bands, r);
  const int nc = bands * bands;
  tmp.resize(nc, nc);
  out.resize(nc, nc);
  for (int j = 0; j < nc; ++j) rot.apply(hz.col(j).data(), tmp.col(j).data());  // D H_z
  tmpT = tmp.transpose();  // H_z Dᵀ (into a reused buffer: no allocation per vertex)
  for (int j = 0; j < nc; ++j) rot.apply(tmpT.col(j).data(), out.col(j).data());  // D H_z Dᵀ
}

/// Uniform directions over the hemisphere about n (or, `sphere`, over the whole sphere) from
/// scrambled Sobol' points.
class HemisphereSampler {
 public:
  HemisphereSampler(const BakeSettings& s, const OwenSobol2D& sobol, std::size_t vertex,
                    const Vec3f& n, bool sphere = false)
      : sobol_(sobol), n_(sphere ? Vec3f(0.0f, 0.0f, 1.0f) : n), sphere_(sphere) {
    const std::uint64_t key =
        deriveSeed(deriveSeed(s.seed, kMatrixPass), static_cast<std::uint64_t>(vertex));
    seed0_ = static_cast<std::uint32_t>(key);
    seed1_ = static_cast<std::uint32_t>(key >> 32);
    orthonormalBasis(n_, t_, b_);
  }
  Vec3f next() {
    const Point2 u = sobol_.point(index_++, seed0_, seed1_);
    const float z = sphere_ ? 1.0f - 2.0f * u.x : u.x;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float sinPhi, cosPhi;
    sinCos2Pi(u.y, sinPhi, cosPhi);  // φ = 2π u.y, without libm (core/sampling.hpp)
    return t_ * (r * cosPhi) + b_ * (r * sinPhi) + n_ * z;
  }

 private:
  const OwenSobol2D& sobol_;
  Vec3f n_, t_, b_;
  bool sphere_ = false;
  std::uint32_t seed0_ = 0, seed1_ = 0, index_ = 0;
};

/// A uniformly random rotation (Shoemake, "Uniform random rotations", Graphics Gems III, 1992:
/// the unit quaternion (√(1−u₁) sin 2πu₂, √(1−u₁) cos 2πu₂, √u₁ sin 2πu₃, √u₁ cos 2πu₃)) from
/// three uniforms of `key`.
Mat3d randomRotation(std::uint64_t key) {
  const auto uniform = [&](std::uint64_t k) {
    return double(deriveSeed(key, k) >> 11) * (1.0 / 9007199254740992.0);  // [0, 1), 53 bits
  };
  const double u1 = uniform(1), u2 = uniform(2), u3 = uniform(3);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const double x = a * std::sin(2 * kPi * u2), y = a * std::cos(2 * kPi * u2);
  const double z = b * std::sin(2 * kPi * u3), w = b * std::cos(2 * kPi * u3);
  Mat3d r;
  r.m[0][0] = 1 - 2 * (y * y + z * z), r.m[0][1] = 2 * (x * y - z * w), r.m[0][2] = 2 * (x * z + y * w);
  r.m[1][0] = 2 * (x * y + z * w), r.m[1][1] = 1 - 2 * (x * x + z * z), r.m[1][2] = 2 * (y * z - x * w);
  r.m[2][0] = 2 * (x * z - y * w), r.m[2][1] = 2 * (y * z + x * w), r.m[2][2] = 1 - 2 * (x * x + y * y);
  return r;
}

/// out = D m Dᵀ (both sides) or D m (`leftOnly`), D the SH rotation `rot`; tmp is scratch.
void rotateRows(const sh::Rotation& rot, MatD& m, MatD& tmp, bool leftOnly) {
  const int nc = int(m.rows());
  tmp.resize(nc, nc);
  for (int j = 0; j < nc; ++j) rot.apply(m.col(j).data(), tmp.col(j).data());  // D m
  if (leftOnly) {
    m = tmp;
    return;
  }
  m = tmp.transpose();
  for (int j = 0; j < nc; ++j) rot.apply(m.col(j).data(), tmp.col(j).data());  // D (D m)ᵀ
  m = tmp.transpose();  // (D (D m)ᵀ)ᵀ = D m Dᵀ
}

/// Where a bounce reads the transfer of one order less at a hit: the barycentric blend of the
/// hit triangle's vertex rows (vertex domain), or the four bilinear taps of its dilated lightmap
/// at the hit's lightmap UV (texel domain, bake_texels.cpp; bilinearTaps).
struct BouncedSource {
  const Transfer* vertices = nullptr;
  const TexelImage* texels = nullptr;
  int channels = 1;  ///< of the bounced rows (interleaved after each coefficient)
  bool present() const { return vertices != nullptr || texels != nullptr; }
};

/// The rows a hit reads and their weights (3 vertices or 4 texels).
struct BounceTaps {
  std::array<const float*, 4> row{};
  std::array<float, 4> weight{};
  int count = 0;
};

BounceTaps bounceTaps(const BouncedSource& src, const Mesh& mesh, const Hit& h) {
  const auto& tri = mesh.triangles[h.triangle];
  const float b0 = 1.0f - h.u - h.v;
  BounceTaps t;
  if (src.vertices) {
    t.count = 3;
    for (int k = 0; k < 3; ++k) t.row[k] = src.vertices->row(tri[k]);
    t.weight = {b0, h.u, h.v, 0.0f};
    return t;
  }
  const TexelTaps taps = src.texels->tapsAt(tri, h.u, h.v);
  t.count = 4;
  for (int k = 0; k < 4; ++k) {
    t.row[k] = src.texels->row(taps.texel[k]);
    t.weight[k] = taps.weight[k];
  }
  return t;
}

struct MatrixContext {
  const Mesh& mesh;
  const Occluder& occluder;
  const BakeSettings& settings;
  int bands, nc, channels;
  const MatD& hz;
  const OwenSobol2D* sobol;
  const BounceAlbedo& albedo;
  /// The bounced light's source over the whole mesh: diffuse vector transfer T^{K−1}, or for
  /// glossy bounce surfaces the matrices M^{K−1} (then `glossy` is set). Empty without bounces.
  BouncedSource bounced;
  bool glossy = false;
  const PreparedMaterial& kernels;  ///< the material's d and g kernels (glossy bounces)
  bool sphere = false;              ///< probes: the whole sphere about a point (see the top)
  const std::vector<Vec3f>* sphereDirs = nullptr;  ///< probes: the pass's directions ω'_s
  const MatF* sphereY = nullptr;                   ///< probes: their SH, B² × N
  /// Probes: the packed lower triangles of Y(ω'_s) Y(ω'_s)ᵀ, B²(B² + 1)/2 × N (null past
  /// kMaxPackedSetBytes: the blocked columns then go through the rank update).
  const MatF* sphereYY = nullptr;
  std::atomic<std::uint64_t> rays{0};
};

/// Per-thread working storage.
struct Workspace {
  MatD h, tmp, tmpT, total;    // H(n), scratch (and its transpose), Σ over the vertex (double)
  MatF y, part;                // batch columns Y (nc × 64), float partial P
  std::vector<MatF> z, gpart;  // per channel: Z (nc × 64), float partial G
  std::vector<MatD> gtotal;
  std::vector<float> interp;
  std::vector<float> d, g, scratch, response;  // glossy bounces: d, g, SH scratch, r per channel
  Eigen::VectorXf mask;                        // probes: 1 for each blocked ray of the batch
  Eigen::VectorXf packedPart;                  // probes: Σ Y'Y'ᵀ packed, float partial
  Eigen::VectorXd packedTotal;                 // ... and its double total
  explicit Workspace(int nc, int channels)
      : total(nc, nc),
        y(nc, kBatch),
        part(nc, nc),
        interp(static_cast<std::size_t>(nc) * 3),
        d(nc),
        g(nc),
        scratch(nc),
        response(static_cast<std::size_t>(nc) * channels),
        mask(Eigen::VectorXf::Zero(kBatch)),
        packedPart(Eigen::VectorXf::Zero(nc * (nc + 1) / 2)),
        packedTotal(Eigen::VectorXd::Zero(nc * (nc + 1) / 2)) {
    for (int c = 0; c < channels; ++c) {
      z.emplace_back(nc, kBatch);
      gpart.emplace_back(nc, nc);
      gtotal.emplace_back(nc, nc);
    }
  }
};

/// Column `col` of Z for a front-facing hit h of the ray in direction w, glossy bounce surfaces:
/// z_c = Σ_k b_k M^{K−1}_{k,c}ᵀ r_c with r_c = ρ_c d(n_h) + ks_c g(R_h(−w)) (see the top).
void glossyBounceColumn(const MatrixContext& ctx, const Hit& h, const Vec3f& w, Workspace& ws,
                        int col) {
  const Mesh& mesh = ctx.mesh;
  const auto& tri = mesh.triangles[h.triangle];
  const float b[3] = {1.0f - h.u - h.v, h.u, h.v};
  const Vec3f p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
  const Vec3f q = p0 * b[0] + p1 * b[1] + p2 * b[2];
  Vec3f nq =
      mesh.normals[tri[0]] * b[0] + mesh.normals[tri[1]] * b[1] + mesh.normals[tri[2]] * b[2];
  const float len = length(nq);
  nq = len > 0 ? nq / len : normalize(cross(p1 - p0, p2 - p0));
  // Seen from one unit back along the ray: the view at h is exactly −w.
  ctx.kernels.responses(q, nq, q - w, ws.d.data(), ws.g.data(), ws.scratch.data());
  const Rgb rho = ctx.albedo.at(tri, h.u, h.v);
  const Rgb ks = ctx.settings.material.specular;
  const int nc = ctx.nc, bChannels = ctx.bounced.channels;
  const BounceTaps taps = bounceTaps(ctx.bounced, mesh, h);
  for (int c = 0; c < ctx.channels; ++c) {
    float* r = ws.response.data() + static_cast<std::size_t>(c) * nc;
    for (int i = 0; i < nc; ++i) r[i] = rho[c] * ws.d[i] + ks[c] * ws.g[i];
    auto z = ws.z[c].col(col);
    z.setZero();
    const Eigen::Map<const Eigen::VectorXf> rc(r, nc);
    const int src = bChannels == 1 ? 0 : c;
    for (int k = 0; k < taps.count; ++k) {
      if (taps.weight[k] == 0.0f) continue;
      // M_k row-major (row i = arriving coefficient, column j = source), channels interleaved.
      const float* m = taps.row[k] + src;
      if (bChannels == 1) {
        const Eigen::Map<const RowMatF> mk(m, nc, nc);
        z.noalias() += taps.weight[k] * (mk.transpose() * rc);
      } else {
        const Eigen::Map<const RowMatF, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>> mk(
            m, nc, nc, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(nc * bChannels, bChannels));
        z.noalias() += taps.weight[k] * (mk.transpose() * rc);
      }
    }
  }
}

/// Column kz of Z for a front-face hit of a diffuse bounce: the previous order's vector transfer
/// interpolated at the hit, times the albedo there (per channel).
void diffuseBounceColumn(const MatrixContext& ctx, const Hit& h, Workspace& ws, int kz) {
  const auto& tri = ctx.mesh.triangles[h.triangle];
  const int bChannels = ctx.bounced.channels;
  const std::size_t stride = static_cast<std::size_t>(ctx.nc) * bChannels;
  const BounceTaps taps = bounceTaps(ctx.bounced, ctx.mesh, h);
  std::fill_n(ws.interp.begin(), stride, 0.0f);
  for (int k = 0; k < taps.count; ++k)
    for (std::size_t i = 0; i < stride; ++i) ws.interp[i] += taps.weight[k] * taps.row[k][i];
  const Rgb rho = ctx.albedo.at(tri, h.u, h.v);
  for (int c = 0; c < ctx.channels; ++c) {
    float* zc = ws.z[c].col(kz).data();
    const int src = bChannels == 1 ? 0 : c;
    for (int i = 0; i < ctx.nc; ++i) zc[i] = rho[c] * ws.interp[i * bChannels + src];
  }
}

/// One row at `point` (a vertex, or a texel's sample point): writes its B² × B² (× C) row to
/// out; returns Var of the M_00 estimator's mean.
double matrixRow(MatrixContext& ctx, const RowPoint& point, float* out, Workspace& ws) {
  const Mesh& mesh = ctx.mesh;
  const int nc = ctx.nc, channels = ctx.channels;
  const Vec3f p = point.position, nrm = point.normal;
  if (ctx.sphere)
    ws.h.setIdentity(nc, nc);  // ∫_{S²} Y Yᵀ dω
  else
    hemisphereProduct(ctx.hz, ctx.bands, Vec3d(nrm), ws.h, ws.tmp, ws.tmpT);
  auto write = [&](const MatD& m, int c) {
    for (int i = 0; i < nc; ++i)
      for (int j = 0; j < nc; ++j)
        out[(static_cast<std::size_t>(i) * nc + j) * channels + c] = static_cast<float>(m(i, j));
  };
  if (ctx.settings.mode == TransferMode::Unshadowed) {
    for (int c = 0; c < channels; ++c) write(ws.h, c);
    return 0.0;
  }
  const bool inter = ctx.bounced.present();
  const int n = ctx.settings.samples;
  const Vec3f origin = ctx.sphere ? p : p + nrm * ctx.occluder.rayOffset(p);
  HemisphereSampler sampler(ctx.settings, *ctx.sobol, point.id, nrm, ctx.sphere);
  // Probes: the pass's direction set turned by this probe's rotation (see the top).
  Mat3d turn = Mat3d::identity();
  float turnF[3][3] = {};
  if (ctx.sphere) {
    turn = randomRotation(deriveSeed(deriveSeed(ctx.settings.seed, kMatrixPass), point.id));
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) turnF[a][b] = float(turn.m[a][b]);
  }
  const auto direction = [&](int s) {
    if (!ctx.sphere) return sampler.next();
    const Vec3f w = (*ctx.sphereDirs)[std::size_t(s)];
    return Vec3f(turnF[0][0] * w.x + turnF[0][1] * w.y + turnF[0][2] * w.z,
                 turnF[1][0] * w.x + turnF[1][1] * w.y + turnF[1][2] * w.z,
                 turnF[2][0] * w.x + turnF[2][1] * w.y + turnF[2][2] * w.z);
  };
  // Column j of the batch's Y: evaluated at the ray's direction, or the set's own (probes).
  const auto yColumn = [&](int base, int j, const Vec3f& dir, int col) {
    if (ctx.sphere)
      ws.y.col(col) = ctx.sphereY->col(base + j);
    else
      sh::eval(ctx.bands, dir, ws.y.col(col).data());
  };
  // The solid angle the directions are spread over: 2π (hemisphere) or 4π (sphere).
  const double omega = ctx.sphere ? 4.0 * kPi : 2.0 * kPi;
  // Probes with the packed table: a blocked ray adds its direction's Y'Y'ᵀ (one GEMV per
  // batch: the table's columns times the batch's mask), no Y column, no rank update.
  const bool packed = ctx.sphereYY != nullptr;
  ws.total.setZero();
  ws.part.setZero();
  ws.packedPart.setZero();
  ws.packedTotal.setZero();
  for (int c = 0; c < channels; ++c) {
    ws.gtotal[c].setZero();
    ws.gpart[c].setZero();
  }
  std::array<Ray, kBatch> rays;
  std::array<std::uint8_t, kBatch> blocked;
  Moments m;
  std::uint64_t cast = 0;
  int batches = 0;
  const float y00sq = 1.0f / (4.0f * kPif);
  for (int base = 0; base < n; base += static_cast<int>(kBatch)) {
    const int count = std::min<int>(kBatch, n - base);
    for (int j = 0; j < count; ++j)
      rays[j] = Ray{origin, direction(base + j), 0.0f, std::numeric_limits<float>::infinity()};
    cast += static_cast<std::uint64_t>(count);
    int k = 0, kz = 0;  // blocked columns; of those, front-face hits (bounce columns)
    if (!inter) {
      ctx.occluder.occluded(std::span<const Ray>(rays.data(), count),
                            std::span<std::uint8_t>(blocked.data(), count));
      for (int j = 0; j < count; ++j) {
        m.add(blocked[j] ? omega * y00sq : 0.0);
        if (packed) {
          ws.mask[j] = blocked[j] ? 1.0f : 0.0f;
          continue;
        }
        if (!blocked[j]) continue;
        yColumn(base, j, rays[j].dir, k++);
      }
    } else {
      // Closest hits: every hit blocks; a front-face hit also sends its bounced light toward p.
      // Blocked columns come first in Y; the front-face ones are Y's first kz columns too, so
      // they are evaluated first.
      std::array<Hit, kBatch> hits;
      std::array<int, kBatch> front, back;
      int nf = 0, nb = 0;
      for (int j = 0; j < count; ++j) {
        hits[j] = ctx.occluder.intersect(rays[j]);
        if (packed) ws.mask[j] = hits[j].hit ? 1.0f : 0.0f;
        if (!hits[j].hit) {
          m.add(0.0);
          continue;
        }
        const auto& tri = mesh.triangles[hits[j].triangle];
        const Vec3f p0 = mesh.positions[tri[0]];
        const Vec3f ng = cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
        if (dot(ng, rays[j].dir) < 0.0f) {
          front[nf++] = j;  // its sample of M_00 once its bounce column is known (below)
        } else {
          back[nb++] = j;
          m.add(omega * y00sq);
        }
      }
      for (int q = 0; q < nf; ++q) {
        const int j = front[q];
        yColumn(base, j, rays[j].dir, k++);
        const Hit& h = hits[j];
        // Its sample of M_00's estimator: blocked (Ω Y00²) less the bounce (Ω Y00 z_0).
        const auto addSample = [&](int col) {
          m.add(omega * (y00sq - std::sqrt(y00sq) * ws.z[0](0, col)));
        };
        if (ctx.glossy) {
          glossyBounceColumn(ctx, h, rays[j].dir, ws, kz);
          addSample(kz++);
          continue;
        }
        diffuseBounceColumn(ctx, h, ws, kz);
        addSample(kz++);
      }
      for (int q = 0; q < nb && !packed; ++q) yColumn(base, back[q], rays[back[q]].dir, k++);
    }
    if (packed)
      ws.packedPart.noalias() += ctx.sphereYY->middleCols(base, count) * ws.mask.head(count);
    else if (k > 0)
      ws.part.selfadjointView<Eigen::Lower>().rankUpdate(ws.y.leftCols(k));
    if (kz > 0)
      for (int c = 0; c < channels; ++c)
        ws.gpart[c].noalias() += ws.y.leftCols(kz) * ws.z[c].leftCols(kz).transpose();
    if (++batches % kFlushBatches == 0 || base + static_cast<int>(kBatch) >= n) {
      if (packed) {
        ws.packedTotal += ws.packedPart.cast<double>();
        ws.packedPart.setZero();
      } else {
        ws.total += ws.part.cast<double>();
        ws.part.setZero();
      }
      for (int c = 0; c < channels && inter; ++c) {
        ws.gtotal[c] += ws.gpart[c].cast<double>();
        ws.gpart[c].setZero();
      }
    }
  }
  ctx.rays.fetch_add(cast, std::memory_order_relaxed);
  const double scale = omega / n;
  if (packed)  // unpack the lower triangle, column by column (as the table packs it)
    for (int j = 0, e = 0; j < nc; ++j)
      for (int i = j; i < nc; ++i) ws.total(i, j) = ws.packedTotal[e++];
  ws.total.triangularView<Eigen::StrictlyUpper>() = ws.total.transpose();
  if (ctx.sphere) {
    // Sums over the set's own Y, turned to the probe's directions: D (Σ Y'Y'ᵀ) Dᵀ, D (Σ Y'zᵀ).
    const sh::Rotation rot(ctx.bands, turn);
    rotateRows(rot, ws.total, ws.tmpT, false);
    for (int c = 0; c < channels && inter; ++c) rotateRows(rot, ws.gtotal[c], ws.tmpT, true);
  }
  for (int c = 0; c < channels; ++c) {
    ws.tmp = ws.h - scale * ws.total;
    if (inter) ws.tmp += scale * ws.gtotal[c];
    write(ws.tmp, c);
  }
  // M_00 = H_00 − mean(2π Y00² [blocked] − 2π Y00 z_0 [front-face hit]): this pass's variance,
  // bounce included (the lower orders' own noise reaches it through z and is not counted).
  return m.varianceOfMean(n);
}

}  // namespace

/// What one matrix pass needs besides its input: its settings (seed, mode), the hemisphere
/// product matrix about +Z, the sample table, the bounce albedo and the material's kernels.
struct MatrixSetup {
  BakeSettings settings;
  int channels = 1;
  bool bounce = false;  ///< reads a bounced transfer (diffuse vectors or glossy matrices)
  bool glossy = false;  ///< ... and it is matrices seen through the material's lobe
  bool sphere = false;  ///< probes: over the whole sphere about a point
  MatD hz;
  std::unique_ptr<OwenSobol2D> sobol;
  std::vector<Vec3f> sphereDirs;  ///< probes: the pass's N directions (see the top)
  MatF sphereY;                   ///< probes: their SH, B² × N
  MatF sphereYY;                  ///< probes: Y Yᵀ's lower triangles, packed (or empty)
  BounceAlbedo albedo;
  PreparedMaterial kernels;
};

std::shared_ptr<const MatrixSetup> makeMatrixSetup(const Mesh& mesh, const BakeSettings& s,
                                                   bool bounce, bool glossy, int channels) {
  auto setup = std::make_shared<MatrixSetup>();
  setup->settings = s;
  setup->channels = channels;
  setup->bounce = bounce;
  setup->glossy = glossy;
  setup->sphere = s.domain == TransferDomain::Probes;
  if (!setup->sphere) setup->hz = hemisphereProductZ(s.bands);
  if (s.mode != TransferMode::Unshadowed)
    setup->sobol = std::make_unique<OwenSobol2D>(static_cast<std::uint32_t>(s.samples));
  if (setup->sphere && setup->sobol) {
    // One set for the pass, from a point id no row has (rows are < 2⁶³).
    HemisphereSampler set(s, *setup->sobol, std::numeric_limits<std::size_t>::max(), Vec3f(0.0f),
                          true);
    const int nc = s.bands * s.bands;
    setup->sphereDirs.resize(std::size_t(s.samples));
    setup->sphereY.resize(nc, s.samples);
    for (int k = 0; k < s.samples; ++k) {
      setup->sphereDirs[std::size_t(k)] = set.next();
      sh::eval(s.bands, setup->sphereDirs[std::size_t(k)], setup->sphereY.col(k).data());
    }
    const std::size_t np = std::size_t(nc) * std::size_t(nc + 1) / 2;
    if (np * std::size_t(s.samples) * sizeof(float) <= kMaxPackedSetBytes) {
      setup->sphereYY.resize(Eigen::Index(np), s.samples);
      for (int k = 0; k < s.samples; ++k)
        for (int j = 0, e = 0; j < nc; ++j)
          for (int i = j; i < nc; ++i, ++e)
            setup->sphereYY(e, k) = setup->sphereY(i, k) * setup->sphereY(j, k);
    }
  }
  setup->albedo = resolveAlbedo(mesh, setup->settings);
  if (glossy) setup->kernels = prepareMaterial(s.material, s.bands);
  return setup;
}

namespace {

/// Rows 0..count−1 at point(r), in parallel, reading `bounced` at the hits.
template <class PointOf>
std::uint64_t matrixRows(const Mesh& mesh, const Occluder& occluder, const MatrixSetup& setup,
                         std::size_t count, const PointOf& pointOf, BouncedSource bounced,
                         float* out, double* variance, Progress* progress) {
  const BakeSettings& s = setup.settings;
  MatrixContext ctx{mesh,
                    occluder,
                    s,
                    s.bands,
                    s.bands * s.bands,
                    setup.channels,
                    setup.hz,
                    setup.sobol.get(),
                    setup.albedo,
                    setup.bounce ? bounced : BouncedSource{},
                    setup.glossy,
                    setup.kernels,
                    setup.sphere,
                    setup.sphere ? &setup.sphereDirs : nullptr,
                    setup.sphere ? &setup.sphereY : nullptr,
                    setup.sphereYY.size() > 0 ? &setup.sphereYY : nullptr,
                    {}};
  const std::size_t stride =
      static_cast<std::size_t>(ctx.nc) * static_cast<std::size_t>(ctx.nc) * setup.channels;
  parallelFor(count, kVertexGrain, [&](std::size_t b, std::size_t e) {
    if (progress) progress->check();
    Workspace ws(ctx.nc, ctx.channels);
    for (std::size_t r = b; r < e; ++r) {
      const double var = matrixRow(ctx, pointOf(r), out + r * stride, ws);
      if (variance) variance[r] = var;
    }
    if (progress) progress->advance(e - b);
  });
  return ctx.rays.load();
}

}  // namespace

std::uint64_t computeMatrixRows(const Mesh& mesh, const Occluder& occluder,
                                const MatrixSetup& setup, RowRange rows, const Transfer* bounced,
                                float* out, double* variance, Progress* progress) {
  BouncedSource src;
  if (setup.bounce) src = {bounced, nullptr, bounced->channels()};
  const auto vertex = [&](std::size_t r) {
    const std::size_t v = rows.first + r;
    return RowPoint{mesh.positions[v], mesh.normals[v], v};
  };
  return matrixRows(mesh, occluder, setup, rows.count, vertex, src, out, variance, progress);
}

std::uint64_t computeMatrixTexelRows(const Mesh& mesh, const Occluder& occluder,
                                     const MatrixSetup& setup, std::span<const RowPoint> points,
                                     const TexelImage* bounced, float* out, double* variance,
                                     Progress* progress) {
  BouncedSource src;
  if (setup.bounce) {
    const std::size_t nc = std::size_t(setup.settings.bands) * setup.settings.bands;
    const std::size_t perChannel = setup.glossy ? nc * nc : nc;
    src = {nullptr, bounced, int(bounced->stride / perChannel)};
  }
  return matrixRows(
      mesh, occluder, setup, points.size(), [&](std::size_t r) { return points[r]; }, src, out,
      variance, progress);
}

std::uint64_t computeMatrixProbeRows(const Mesh& mesh, const Occluder& occluder,
                                     const MatrixSetup& setup, std::span<const RowPoint> points,
                                     const Transfer* bounced, float* out, double* variance,
                                     Progress* progress) {
  BouncedSource src;
  if (setup.bounce) src = {bounced, nullptr, bounced->channels()};
  return matrixRows(
      mesh, occluder, setup, points.size(), [&](std::size_t r) { return points[r]; }, src, out,
      variance, progress);
}

std::vector<float> unshadowedMatrixRows(int bands, std::span<const Vec3f> normals) {
  const MatD hz = hemisphereProductZ(bands);
  const std::size_t nc = std::size_t(bands) * std::size_t(bands);
  std::vector<float> out(normals.size() * nc * nc);
  parallelFor(normals.size(), 64, [&](std::size_t b, std::size_t e) {
    MatD h, tmp, tmpT;
    for (std::size_t r = b; r < e; ++r) {
      hemisphereProduct(hz, bands, Vec3d(normals[r]), h, tmp, tmpT);
      for (std::size_t i = 0; i < nc; ++i)
        for (std::size_t j = 0; j < nc; ++j)
          out[(r * nc + i) * nc + j] = float(h(Eigen::Index(i), Eigen::Index(j)));
    }
  });
  return out;
}

std::uint64_t matrixBounceOrderSeed(std::uint64_t seed, int order) {
  return deriveSeed(seed, kBounceOrder + static_cast<std::uint64_t>(order));
}

}  // namespace prt::bakedetail
