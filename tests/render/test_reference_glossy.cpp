// Tests of the glossy term of the Monte Carlo reference (render/reference.hpp):
//   e(p, v) = kd ⊙ (1/π) ∫ L_in max(n·ω, 0) dω + ks ⊙ ∫_{n·ω>0} L_in G(r·ω) dω,  r = 2(n·v)n − v.
// The white furnace against an independent quadrature of the clipped lobe, the diffuse part
// unchanged by the glossy machinery, a sharp lobe under a sky with a sun against a plain
// lobe-sampling estimator written here, and the transport modes agreeing where nothing occludes.
// Every Monte Carlo comparison is within 4 standard errors (the estimator's own sqrt(s²/N)),
// with fixed seeds, so a test either always passes or always fails.

#include <gtest/gtest.h>

#include <cmath>

#include "prt/core/error.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/render/reference.hpp"
#include "prt/transfer/material.hpp"

namespace prt::render {
namespace {

using envmap::Environment;

/// ∫_{n·ω>0} G(r·ω) dω with a = n·r, by quadrature in polar coordinates about r, written
/// independently of the estimator: the ring at angle θ from r has measure 2π sin θ dθ, and a
/// direction on it, ω = cos θ r + sin θ (cos φ t + sin φ b) with t the unit component of n
/// orthogonal to r (n = a r + s t, s = √(1 − a²)), has n·ω = a cos θ + s sin θ cos φ. It is
/// positive on the fraction acos(clamp(−a cos θ / (s sin θ), −1, 1))/π of the ring, so only θ
/// needs a (midpoint) rule.
double clippedLobeIntegral(const GlossyLobe& lobe, double a, int steps = 20000) {
  a = std::clamp(a, -1.0, 1.0);
  const double s = std::sqrt(1.0 - a * a), h = kPi / steps;
  double sum = 0;
  for (int k = 0; k < steps; ++k) {
    const double theta = (k + 0.5) * h, ct = std::cos(theta), st = std::sin(theta);
    double frac;
    if (s * st <= 0)
      frac = a * ct > 0 ? 1.0 : 0.0;
    else
      frac = std::acos(std::clamp(-a * ct / (s * st), -1.0, 1.0)) / kPi;
    sum += lobe.value(ct) * 2 * kPi * st * h * frac;
  }
  return sum;
}

// The quadrature itself, on answers known by symmetry: a lobe about the normal lies in the
// hemisphere (Phong: all of it, ∫ = 1), and a lobe about a tangent direction is cut in half by
// the tangent plane (it is symmetric under the mirror through that plane).
TEST(ReferenceGlossy, QuadratureOfTheClippedLobe) {
  const GlossyLobe phong = parseMaterial("phong?exponent=32").lobe;
  const GlossyLobe ggx = parseMaterial("ggx?roughness=0.3").lobe;
  EXPECT_NEAR(clippedLobeIntegral(phong, 1.0), 1.0, 1e-5);
  EXPECT_NEAR(clippedLobeIntegral(phong, 0.0), 0.5, 1e-5);
  EXPECT_NEAR(clippedLobeIntegral(ggx, 0.0), 0.5, 1e-5);
  EXPECT_NEAR(clippedLobeIntegral(ggx, 1.0) + clippedLobeIntegral(ggx, -1.0), 1.0, 1e-5);
  EXPECT_LT(clippedLobeIntegral(ggx, 1.0), 1.0);  // GGX has a tail past 90° from r
}

/// Unit normal, eye far off on a side: vertices of the sphere see r at every angle to n.
const Vec3f kEye{0.6f, 1.2f, 3.0f};

// White furnace: a convex sphere (nothing occludes; vertex normals lie in each vertex's normal
// cone, so no ray above the tangent plane hits the mesh) under radiance 1, kd = 0: e = ks ·
// ∫_{n·ω>0} G(r·ω) dω ≤ ks at every vertex, within 4 standard errors — silhouettes and vertices
// facing away from the eye included, whose lobes the horizon clips. Also the error bars: over the
// 100–130 vertices whose value exceeds 10⁻⁶, the mean of z² = ((e − exact)/se)² is 1 for an
// honest standard error (we accept 0.5..1.6; its own spread, sqrt(2/count), is about ±0.13).
TEST(ReferenceGlossy, WhiteFurnaceMatchesQuadrature) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=3");
  auto occ = makeEmbreeOccluder(mesh);
  const Environment env = envmap::builtinEnvironment("builtin:constant", 64);
  for (const char* spec : {"phong?exponent=32&ks=1&kd=0", "phong?exponent=1&ks=0.7&kd=0",
                           "ggx?roughness=0.3&ks=0.8&kd=0", "ggx?roughness=0.1&ks=1&kd=0"}) {
    for (MisHeuristic heuristic : {MisHeuristic::Power, MisHeuristic::Balance}) {
      SCOPED_TRACE(spec);
      SCOPED_TRACE(heuristic == MisHeuristic::Power ? "power" : "balance");
      ReferenceSettings s;
      s.material = parseMaterial(spec);
      s.eye = kEye;
      s.samples = 512;
      s.heuristic = heuristic;
      for (std::uint32_t v = 0; v < mesh.vertexCount(); v += 5) s.vertices.push_back(v);
      const ReferenceResult r = renderReference(mesh, *occ, env, s);
      const double ks = s.material.specular.x;
      double z2 = 0, minExact = 1;
      int counted = 0;
      for (std::size_t i = 0; i < r.vertices.size(); ++i) {
        const std::uint32_t v = r.vertices[i];
        const Vec3f n = mesh.normals[v], view = normalize(kEye - mesh.positions[v]);
        const double exact =
            ks * clippedLobeIntegral(s.material.lobe, dot(n, reflectView(n, view)));
        ASSERT_LE(exact, ks + 1e-6);
        minExact = std::min(minExact, exact);
        const double se = r.stdError[i].x;
        EXPECT_NEAR(r.radiance[i].x, exact, 4 * se + 1e-6) << "vertex " << v;
        if (exact < 1e-6) continue;  // r so far below the horizon that every sample is ~0
        ASSERT_GT(se, 0.0) << "vertex " << v;
        z2 += (r.radiance[i].x - exact) * (r.radiance[i].x - exact) / (se * se);
        ++counted;
      }
      ASSERT_GT(counted, 100);
      z2 /= counted;
      EXPECT_GT(z2, 0.5);
      EXPECT_LT(z2, 1.6);
      EXPECT_LT(minExact, 0.01 * ks);  // some vertices see their lobe mostly clipped
    }
  }
}

// Where the horizon cuts off most of the lobe (r 31° below it: 0.08% of Phong 32 and 0.04% of
// GGX 0.1 lie above it), the integrand G·[n·ω > 0] peaks at the horizon point nearest r, where
// neither the environment nor the lobe about r puts samples; without the horizon strategy a
// single estimate rests on a few rare samples and its s² understates its spread. Over 400
// independent estimates of N = 512: their mean agrees with the quadrature within 4 standard
// errors of that mean (from the spread of the 400), and the mean of their own z² is near 1.
TEST(ReferenceGlossy, ClippedLobeHasHonestErrorBars) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=3");
  auto occ = makeEmbreeOccluder(mesh);
  const EnvironmentSampler env(envmap::builtinEnvironment("builtin:constant", 64));
  const Vec3f n{0, 1, 0}, r = normalize(Vec3f{1.0f, -0.6f, 0.0f});
  const Vec3f view = n * (2 * dot(n, r)) - r;  // the v with 2(n·v)n − v = r
  for (const char* spec : {"phong?exponent=32&ks=1&kd=0", "ggx?roughness=0.1&ks=1&kd=0"}) {
    SCOPED_TRACE(spec);
    ReferenceSettings s;
    s.material = parseMaterial(spec);
    const double exact = clippedLobeIntegral(s.material.lobe, dot(n, r));
    ASSERT_LT(exact, 0.02);
    const ReferenceIntegrator ref(mesh, *occ, env, s);
    const int runs = 400;
    double sum = 0, sum2 = 0, z2 = 0;
    for (int k = 0; k < runs; ++k) {
      const Estimate e = ref.estimate(n, n, view, Rgb(0.0f), 512, deriveSeed(5, k));
      const double x = e.mean.x;
      sum += x;
      sum2 += x * x;
      z2 += (x - exact) * (x - exact) / (e.stdError.x * e.stdError.x) / runs;
    }
    const double mean = sum / runs, se = std::sqrt((sum2 / runs - mean * mean) / (runs - 1));
    EXPECT_NEAR(mean, exact, 4 * se);
    EXPECT_LT(se, 0.01 * exact);  // each estimate within ~10% (the horizon strategy's doing)
    EXPECT_GT(z2, 0.7);
    EXPECT_LT(z2, 1.4);
  }
}

// With ks = 0 (or a Lambertian material) the glossy machinery changes nothing: kd from the
// material gives what the same kd as mesh albedo gives — bit for bit without bounces, and to
// rounding with them (the mesh's albedo is interpolated at a hit, kd (1−u−v) + kd u + kd v,
// which may differ from kd in the last bit). With both terms the sample is X = kd D + ks S from
// separate streams, so with occlusion but no bounces (which would take kd as their albedo) the
// total is the diffuse-only estimate plus the glossy-only one up to rounding.
TEST(ReferenceGlossy, DiffusePartUnchanged) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?r=0.5&h=0.8&grid=6&subdiv=2");
  auto occ = makeEmbreeOccluder(mesh);
  const Environment env = envmap::builtinEnvironment("builtin:sky", 128);
  ReferenceSettings s;
  s.samples = 64;
  s.eye = kEye;
  for (std::uint32_t v = 0; v < mesh.vertexCount(); v += 7) s.vertices.push_back(v);

  const Rgb kd(0.3f, 0.5f, 0.7f);
  Mesh coloured = mesh;
  coloured.albedo.assign(mesh.vertexCount(), kd);
  for (int bounces : {0, 2}) {
    SCOPED_TRACE(bounces);
    s.mode = bounces ? TransferMode::Interreflected : TransferMode::Shadowed;
    s.bounces = bounces;
    const ReferenceResult base = renderReference(coloured, *occ, env, s);
    for (const char* spec : {"lambert?kd=0.3,0.5,0.7", "phong?ks=0&kd=0.3,0.5,0.7"}) {
      SCOPED_TRACE(spec);
      ReferenceSettings m = s;
      m.material = parseMaterial(spec);
      ASSERT_FALSE(m.material.glossy());
      const ReferenceResult r = renderReference(mesh, *occ, env, m);
      ASSERT_EQ(r.radiance.size(), base.radiance.size());
      const float tol = bounces ? 1e-5f : 0.0f;
      for (std::size_t i = 0; i < r.radiance.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(r.radiance[i][c], base.radiance[i][c], tol * base.radiance[i][c]);
          EXPECT_NEAR(r.stdError[i][c], base.stdError[i][c], tol * base.stdError[i][c]);
        }
      }
      EXPECT_EQ(r.rays, base.rays);
    }
  }

  s.mode = TransferMode::Shadowed;
  s.material = parseMaterial("ggx?roughness=0.2&ks=0.6,0.5,0.4&kd=0.3,0.5,0.7");
  const ReferenceResult both = renderReference(mesh, *occ, env, s);
  s.material.diffuse = Rgb(0.0f);
  const ReferenceResult glossyOnly = renderReference(mesh, *occ, env, s);
  s.material = parseMaterial("lambert?kd=0.3,0.5,0.7");
  const ReferenceResult diffuseOnly = renderReference(mesh, *occ, env, s);
  double glossySum = 0;
  for (std::size_t i = 0; i < both.radiance.size(); ++i) {
    const Vec3d sum = Vec3d(diffuseOnly.radiance[i]) + Vec3d(glossyOnly.radiance[i]);
    EXPECT_LE(length(Vec3d(both.radiance[i]) - sum), 1e-5 * length(sum) + 1e-7);
    glossySum += glossyOnly.radiance[i].x;
  }
  EXPECT_GT(glossySum, 0.0);
}

// Glossy light through glossy bounces: a white furnace. Under the sphere of sphere-plane, under
// radiance 1, with kd + ks = 1 and a normalised lobe, no surface reflects more than it receives
// (a lobe clipped by the horizon reflects less), so L_in ≤ 1 in every direction and the glossy
// term at p can never exceed ks ∫_{n·ω>0} G(r·ω) dω — although the plane hides most of what the
// lobe looks at. The bounces must bring most of that light back: what a glossy bounce loses is
// only the clipped part of the lobe at the hits, a few percent here.
TEST(ReferenceGlossy, WhiteFurnaceWithGlossyBounces) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?r=0.5&h=0.8&grid=8&subdiv=4");
  auto occ = makeEmbreeOccluder(mesh);
  const EnvironmentSampler env(envmap::builtinEnvironment("builtin:constant", 32));
  const Vec3f p{0, 0.3f, 0}, n{0, -1, 0};
  // Two views: r toward the plane, and r 17° below the horizon of n (into the sphere), where the
  // horizon strategy carries the light that bounces in from the plane at grazing angles.
  for (const Vec3f& view :
       {normalize(Vec3f{0.4f, -1.0f, 0.2f}), normalize(Vec3f{1.0f, 0.3f, 0.0f})}) {
    for (const char* spec : {"phong?exponent=8&ks=0.5&kd=0.5", "ggx?roughness=0.5&ks=0.5&kd=0.5"}) {
      SCOPED_TRACE(spec);
      ReferenceSettings s;
      s.material = parseMaterial(spec);
      s.mode = TransferMode::Interreflected;
      s.bounces = 12;
      // kd = 0 at p: the glossy term alone (the bounce surfaces keep kd = ρ = 0.5).
      const Estimate e =
          ReferenceIntegrator(mesh, *occ, env, s).estimate(p, n, view, Rgb(0.0f), 4096, 9);
      const double exact = 0.5 * clippedLobeIntegral(s.material.lobe, dot(n, reflectView(n, view)));
      std::printf("%s: furnace %.4f ± %.4f of at most %.4f\n", spec, e.mean.x, e.stdError.x, exact);
      EXPECT_LT(e.mean.x, exact + 4 * e.stdError.x);
      EXPECT_GT(e.mean.x, 0.85 * exact);
      s.bounces = 0;
      const Estimate direct =
          ReferenceIntegrator(mesh, *occ, env, s).estimate(p, n, view, Rgb(0.0f), 512, 9);
      EXPECT_LT(direct.mean.x, 0.5 * exact);
    }
  }
}

/// A plain estimator of ∫_{n·ω>0} L(ω) G(r·ω) dω for the Phong lobe, written independently of
/// the reference: ω drawn with density G (cos θ = u^{1/(s+1)} about r), weight L(ω)·[n·ω > 0]
/// (G/pdf = 1), no occlusion (a convex sphere), no MIS. Returns the mean and standard error.
std::pair<double, double> plainPhong(const EnvironmentSampler& env, double exponent, const Vec3d& n,
                                     const Vec3d& r, int samples, std::uint64_t seed) {
  // A frame about r: t ⟂ r from the coordinate axis least aligned with r.
  const Vec3d axis = std::abs(r.x) < 0.5 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  const Vec3d t = normalize(cross(r, axis)), b = cross(r, t);
  Pcg32 rng(seed);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < samples; ++i) {
    const double ct = std::pow(double(rng.uniform()), 1.0 / (exponent + 1.0));
    const double st = std::sqrt(std::max(0.0, 1 - ct * ct)), phi = 2 * kPi * rng.uniform();
    const Vec3d w = r * ct + t * (st * std::cos(phi)) + b * (st * std::sin(phi));
    const double x = dot(n, w) > 0 ? env.radiance(Vec3f(w)).x : 0.0;
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / samples;
  return {mean, std::sqrt(std::max(0.0, sum2 / samples - mean * mean) / (samples - 1))};
}

// A sharp lobe (Phong 200, about 4° wide) under a sky with a 0.5° sun: the reference's MIS
// estimate agrees with the plain lobe-sampling estimator, with r aimed at the sun, 2° and 6° off
// it, at the open sky, and grazing the horizon of n.
TEST(ReferenceGlossy, SharpLobeUnderSkyMatchesPlainLobeSampling) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=3");
  auto occ = makeEmbreeOccluder(mesh);
  const Environment skyEnv = envmap::builtinEnvironment("builtin:sky", 512);
  ASSERT_EQ(skyEnv.caps().size(), 1u);
  const Vec3d sun(skyEnv.caps()[0].direction);
  const EnvironmentSampler env(skyEnv);
  ReferenceSettings s;
  s.material = parseMaterial("phong?exponent=200&ks=1&kd=0");
  const ReferenceIntegrator ref(mesh, *occ, env, s);
  const Vec3d up(0, 1, 0), side = normalize(cross(sun, up));
  const auto tilt = [&](double deg) {
    const double a = deg * kPi / 180;
    return sun * std::cos(a) + normalize(cross(side, sun)) * std::sin(a);
  };
  const Vec3d view = normalize(Vec3d(0.2, 0.3, 1.0));
  int k = 0;
  std::vector<double> means;
  for (const Vec3d& r : {sun, tilt(2), tilt(6), normalize(Vec3d(-0.3, 1.0, 0.4))}) {
    SCOPED_TRACE(++k);
    // n is the half vector of r and view, so that r = 2(n·v)n − v.
    const Vec3d n = normalize(r + view);
    const Estimate e = ref.estimate(Vec3f(n), Vec3f(n), Vec3f(view), Rgb(0.0f), 4096, 100 + k);
    const auto [mean, se] = plainPhong(env, 200, n, r, 200000, 200 + k);
    EXPECT_GT(e.stdError.x, 0.0);
    EXPECT_NEAR(e.mean.x, mean, 4 * std::hypot(e.stdError.x, se));
    means.push_back(e.mean.x);
  }
  EXPECT_GT(means[0], 10 * means[3]);  // the sun in the lobe outshines the open sky
  // r on the horizon of n: the lobe is cut in half by the tangent plane.
  {
    const Vec3d r = normalize(Vec3d(-0.3, 1.0, 0.4)), n = normalize(cross(r, Vec3d(1, 0, 0)));
    const Vec3d v = n * (2 * dot(n, r)) - r;  // r = 2(n·v)n − v with n·r = 0: v = −r
    const Estimate e = ref.estimate(Vec3f(n), Vec3f(n), Vec3f(v), Rgb(0.0f), 4096, 7);
    const auto [mean, se] = plainPhong(env, 200, n, r, 200000, 8);
    EXPECT_NEAR(e.mean.x, mean, 4 * std::hypot(e.stdError.x, se));
  }
}

// Where nothing occludes (a convex sphere), unshadowed, shadowed and inter-reflected transport
// are one function, and the estimator draws the same random numbers in each: identical results.
TEST(ReferenceGlossy, ModesAgreeOnAnUnoccludedSphere) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=3");
  auto occ = makeEmbreeOccluder(mesh);
  const Environment env = envmap::builtinEnvironment("builtin:sky", 128);
  ReferenceSettings s;
  s.material = parseMaterial("ggx?roughness=0.2&ks=0.5&kd=0.4");
  s.eye = kEye;
  s.samples = 64;
  for (std::uint32_t v = 0; v < mesh.vertexCount(); v += 3) s.vertices.push_back(v);
  s.mode = TransferMode::Unshadowed;
  const ReferenceResult u = renderReference(mesh, *occ, env, s);
  EXPECT_EQ(u.rays, 0u);
  s.mode = TransferMode::Shadowed;
  const ReferenceResult sh = renderReference(mesh, *occ, env, s);
  s.mode = TransferMode::Interreflected;
  s.bounces = 3;
  const ReferenceResult ir = renderReference(mesh, *occ, env, s);
  EXPECT_GT(sh.rays, 0u);
  for (std::size_t i = 0; i < u.radiance.size(); ++i) {
    EXPECT_EQ(u.radiance[i], sh.radiance[i]) << "vertex " << u.vertices[i];
    EXPECT_EQ(u.radiance[i], ir.radiance[i]) << "vertex " << u.vertices[i];
    EXPECT_EQ(u.stdError[i], sh.stdError[i]);
  }
}

TEST(ReferenceGlossy, GlossyNeedsAnEye) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=1");
  auto occ = makeEmbreeOccluder(mesh);
  const Environment env = envmap::builtinEnvironment("builtin:constant", 16);
  ReferenceSettings s;
  s.samples = 4;
  s.material = parseMaterial("phong");
  EXPECT_THROW(renderReference(mesh, *occ, env, s), Error);
  s.eye = kEye;
  EXPECT_NO_THROW(renderReference(mesh, *occ, env, s));
}

}  // namespace
}  // namespace prt::render
