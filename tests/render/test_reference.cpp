// Tests of the Monte Carlo reference (render/reference.hpp) against closed forms: the cosine-
// weighted unoccluded fraction under a sphere, the white furnace with bounces, a small bright cap
// (MIS), and the consistency of the environment's sampling density with its lookup.

#include <gtest/gtest.h>

#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/render/reference.hpp"

namespace prt::render {
namespace {

using envmap::Cap;
using envmap::Environment;

Environment constantEnv(float value, int width = 64) {
  return Environment::analytic([value](const Vec3f&) { return Rgb(value); }, {}, width);
}

/// A coloured, non-uniform lat-long image with one bright texel block.
Environment gradientLatLong(int w) {
  image::Image img(w, w / 2);
  for (int y = 0; y < w / 2; ++y)
    for (int x = 0; x < w; ++x) img.at(x, y) = Rgb(0.2f + float(x) / w, 0.1f + float(y) / w, 0.5f);
  img.at(w / 3, w / 8) = Rgb(200.0f, 150.0f, 100.0f);
  return Environment::latLong(std::move(img));
}

Environment gradientCube(int n) {
  std::array<image::Image, 6> faces;
  for (int f = 0; f < 6; ++f) {
    faces[f] = image::Image(n, n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        faces[f].at(x, y) = Rgb(0.1f + f * 0.3f + float(x) / n, 0.2f + float(y) / n, 1.0f);
  }
  faces[2].at(1, 2) = Rgb(50.0f);
  return Environment::cube(std::move(faces));
}

Environment gradientProbe(int n) {
  image::Image img(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) img.at(x, y) = Rgb(0.3f + float(x) / n, 1.0f, 0.2f + float(y) / n);
  img.at(n / 2, n / 4) = Rgb(80.0f);
  return Environment::probe(std::move(img));
}

// The sampling density integrates to one (checked by uniform-sphere Monte Carlo: E[4π p] = 1),
// sample() reports the density and radiance that pdf() and radiance() give at its direction,
// and the importance-sampled estimate of ∫ L dω agrees with the texel sum Σ L_k ΔΩ_k.
void checkSampler(const Environment& env, const char* what) {
  SCOPED_TRACE(what);
  const EnvironmentSampler s(env);
  ASSERT_TRUE(s.canSample());
  Pcg32 rng(7);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double v = 4 * kPi * s.pdf(uniformSphere(rng.uniform(), rng.uniform()));
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, 1.0, 4 * se + 1e-3);

  double exactR = 0;
  for (std::size_t k = 0; k < env.texelCount(); ++k)
    exactR += double(env.texel(k).radiance.x) * env.texelSolidAngle(k);
  double est = 0, est2 = 0;
  int m = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec3f d;
    double pdf;
    Rgb l;
    double x = 0;
    if (s.sample(double(rng.uniform()), rng.uniform(), rng.uniform(), d, pdf, l)) {
      ASSERT_NEAR(pdf, s.pdf(d), 1e-6 * pdf);
      ASSERT_EQ(l.x, s.radiance(d).x);
      x = l.x / pdf;
      ++m;
    }
    est += x;
    est2 += x * x;
  }
  const double em = est / 20000, ese = std::sqrt((est2 / 20000 - em * em) / 20000);
  EXPECT_GT(m, 19000);
  EXPECT_NEAR(em, exactR, 4 * ese + 1e-4 * exactR);
}

TEST(EnvironmentSampler, DensityAndLookupAreOneFunctionLatLong) {
  checkSampler(gradientLatLong(64), "latlong");
}
TEST(EnvironmentSampler, DensityAndLookupAreOneFunctionCube) {
  checkSampler(gradientCube(8), "cube");
}
TEST(EnvironmentSampler, DensityAndLookupAreOneFunctionProbe) {
  checkSampler(gradientProbe(32), "probe");
}

// Plane point straight below a sphere of radius r centred at height h: the sphere hides the cap
// of half-angle α, sin α = r/h, about the normal, whose cosine-weighted fraction is sin² α, so
// R = ρ (1 − (r/h)²) c under a constant environment c.
TEST(Reference, SpherePlaneClosedForm) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?r=0.5&h=1&grid=4&subdiv=6");
  auto occ = makeEmbreeOccluder(mesh);
  const EnvironmentSampler env(constantEnv(2.0f));
  for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
    ReferenceSettings s;
    s.heuristic = h;
    const ReferenceIntegrator ref(mesh, *occ, env, s);
    const Estimate e = ref.estimate({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, Rgb(0.8f), 4096, 42);
    const double expected = 0.8 * (1 - 0.25) * 2.0;
    // The icosphere (subdiv 6) is inscribed in the sphere: its silhouette is smaller by < 0.05%.
    EXPECT_NEAR(e.mean.x, expected, 4 * e.stdError.x + 1e-3 * expected);
    EXPECT_LT(e.stdError.x, 0.01 * expected);
    EXPECT_GT(e.stdError.x, 0.0);
    // Unshadowed: the whole hemisphere, R = ρ c.
    s.mode = TransferMode::Unshadowed;
    const ReferenceIntegrator un(mesh, *occ, env, s);
    const Estimate u = un.estimate({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, Rgb(0.8f), 1024, 42);
    EXPECT_NEAR(u.mean.x, 1.6, 4 * u.stdError.x + 1e-4);
  }
}

// White furnace with bounces: albedo 1 everywhere under a constant environment 1. At the bottom
// of the sphere the plane fills most of the view, so the direct term alone is small, and every
// bounce adds what escapes next; with enough bounces the radiance approaches 1 (each path either
// escapes, seeing 1, or keeps reflecting all of its energy).
TEST(Reference, WhiteFurnaceWithBounces) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?r=0.5&h=0.8&grid=8&subdiv=4");
  auto occ = makeEmbreeOccluder(mesh);
  const EnvironmentSampler env(constantEnv(1.0f));
  const Vec3f p{0, 0.3f, 0}, n{0, -1, 0};
  std::vector<double> r;
  for (int k : {0, 1, 2, 12}) {
    ReferenceSettings s;
    s.mode = TransferMode::Interreflected;
    s.bounces = k;
    s.material.diffuse = Rgb(1.0f);
    const ReferenceIntegrator ref(mesh, *occ, env, s);
    const Estimate e = ref.estimate(p, n, n, Rgb(1.0f), 2048, 3);
    r.push_back(e.mean.x);
    if (k == 12) {
      EXPECT_NEAR(e.mean.x, 1.0, 4 * e.stdError.x + 5e-3);
    }
  }
  EXPECT_LT(r[0], 0.1);         // the plane (size 4 at distance 0.3) hides most of the sky
  EXPECT_GT(r[1], r[0] + 0.5);  // one bounce off the bright plane
  EXPECT_GT(r[2], r[1]);
}

// MIS with a small bright cap (the sun) on a convex sphere: the exact clamped-cosine integral of
// a cap of half-angle α fully above the horizon, at angle β from the normal, is
// E = L π sin² α cos β. Cosine sampling alone would hit the cap with probability ~ sin² α cos β
// (0.2%) and have a relative error of ~20% at 1024 samples; light sampling makes it ≪ 1%.
TEST(Reference, SmallCapMatchesAnalyticIrradiance) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=3");
  auto occ = makeEmbreeOccluder(mesh);
  const double alpha = 3.0 * kPi / 180;
  const Vec3f sun = normalize(Vec3f{0.3f, 0.8f, 0.5f});
  const Environment envA = Environment::analytic([](const Vec3f&) { return Rgb(0.0f); },
                                                 {Cap{sun, alpha, Rgb(1000.0f)}}, 1024);
  const EnvironmentSampler env(envA);
  const Vec3f n = normalize(Vec3f{0.0f, 1.0f, 0.2f});
  const double cosBeta = dot(n, sun);
  const double exactE = 1000.0 * kPi * std::sin(alpha) * std::sin(alpha) * cosBeta;
  // The texelised environment carries the cap by covered fraction: its own quadrature agrees.
  EXPECT_NEAR(env.irradianceQuadrature(n).x, exactE, 0.01 * exactE);

  for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
    ReferenceSettings s;
    s.heuristic = h;
    const ReferenceIntegrator ref(mesh, *occ, env, s);
    const Estimate e = ref.estimate(n * 1.0f, n, n, Rgb(0.5f), 1024, 11);
    const double expected = 0.5 / kPi * exactE;
    EXPECT_NEAR(e.mean.x, expected, 4 * e.stdError.x + 0.01 * expected);
    EXPECT_LT(e.stdError.x, 0.01 * expected);
  }
}

// Rotating the environment by R and evaluating at R n equals the unrotated environment at n.
TEST(Reference, RotationMovesTheEnvironment) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=2");
  auto occ = makeEmbreeOccluder(mesh);
  const Vec3f sun = normalize(Vec3f{0.0f, 1.0f, 0.0f});
  const EnvironmentSampler env(Environment::analytic([](const Vec3f&) { return Rgb(0.05f); },
                                                     {Cap{sun, 0.2, Rgb(50.0f)}}, 256));
  const Mat3d rot = rotationEulerXYZ(70, 20, 0);
  const Vec3f n{0, 1, 0}, rn = Vec3f(rot * Vec3d(n));
  ReferenceSettings s0, s1;
  s1.rotation = rot;
  const Estimate a = ReferenceIntegrator(mesh, *occ, env, s0).estimate(n, n, n, Rgb(1.0f), 2048, 5);
  const Estimate b =
      ReferenceIntegrator(mesh, *occ, env, s1).estimate(rn, rn, rn, Rgb(1.0f), 2048, 6);
  const double se = std::hypot(a.stdError.x, b.stdError.x);
  EXPECT_NEAR(a.mean.x, b.mean.x, 4 * se + 1e-3 * a.mean.x);
  // And a normal facing away from the rotated sun sees only the dim sky.
  const Estimate c =
      ReferenceIntegrator(mesh, *occ, env, s1).estimate(-rn, -rn, -rn, Rgb(1.0f), 512, 7);
  EXPECT_LT(c.mean.x, 0.1);
}

TEST(Reference, DeterministicAcrossThreadCounts) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?grid=6&subdiv=1");
  auto occ = makeEmbreeOccluder(mesh);
  const Environment env = envmap::builtinEnvironment("builtin:sky", 64);
  ReferenceSettings s;
  s.samples = 64;
  s.mode = TransferMode::Interreflected;
  s.bounces = 2;
  ReferenceResult a, b;
  {
    ThreadLimit one(1);
    a = renderReference(mesh, *occ, env, s);
  }
  b = renderReference(mesh, *occ, env, s);
  ASSERT_EQ(a.radiance.size(), mesh.vertexCount());
  for (std::size_t i = 0; i < a.radiance.size(); ++i) {
    EXPECT_EQ(a.radiance[i], b.radiance[i]);
    EXPECT_EQ(a.stdError[i], b.stdError[i]);
  }
  EXPECT_EQ(a.rays, b.rays);
  EXPECT_GT(a.rays, 0u);
  // A subset estimates the same vertices identically (seed per vertex, not per position).
  s.vertices = {3, 17};
  const ReferenceResult c = renderReference(mesh, *occ, env, s);
  EXPECT_EQ(c.radiance[0], a.radiance[3]);
  EXPECT_EQ(c.radiance[1], a.radiance[17]);
}

TEST(Reference, BadSettingsThrow) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=1");
  auto occ = makeEmbreeOccluder(mesh);
  const Environment env = constantEnv(1.0f, 16);
  ReferenceSettings s;
  s.samples = 0;
  EXPECT_THROW(renderReference(mesh, *occ, env, s), Error);
  s.samples = 4;
  s.bounces = 17;
  EXPECT_THROW(renderReference(mesh, *occ, env, s), Error);
  s.bounces = 0;
  s.vertices = {static_cast<std::uint32_t>(mesh.vertexCount())};
  EXPECT_THROW(renderReference(mesh, *occ, env, s), Error);
  // Cancellation through the progress callback.
  s.vertices.clear();
  EXPECT_THROW(renderReference(mesh, *occ, env, s, [](double) { return false; }), Cancelled);
}

}  // namespace
}  // namespace prt::render
