// Tests of validate (render/validate.hpp): a real bake against the reference on a builtin scene,
// the truncation floor on cases with known answers, band reconciliation and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "prt/core/error.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/render/validate.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transport/bake.hpp"

namespace prt::render {
namespace {

using envmap::Cap;
using envmap::Environment;

/// A smooth, low-frequency environment: a sky gradient and a broad warm disc (30°).
Environment smoothEnv() {
  return Environment::analytic(
      [](const Vec3f& d) {
        const float t = 0.5f * (d.y + 1.0f);
        return Rgb(0.3f + 0.5f * t, 0.35f + 0.55f * t, 0.4f + 0.8f * t);
      },
      {Cap{normalize(Vec3f{0.5f, 0.7f, 0.3f}), 30.0 * kPi / 180, Rgb(1.5f, 1.2f, 0.8f)}}, 256);
}

struct Scene {
  Mesh mesh;
  std::unique_ptr<Occluder> occ;
  Transfer transfer;
  BakeSettings bake;
};

Scene bakeScene(const std::string& name, TransferMode mode, int bands, int bounces) {
  Scene s;
  s.mesh = builtinScene(name);
  s.occ = makeEmbreeOccluder(s.mesh);
  s.bake.mode = mode;
  s.bake.bands = bands;
  s.bake.samples = 1024;
  s.bake.bounces = bounces;
  s.transfer = bake(s.mesh, *s.occ, s.bake);
  return s;
}

// The acceptance case: shadowed diffuse PRT at 5 bands on sphere-plane under a smooth
// environment is within 3% relative RMSE of the reference; fewer bands are worse, and the
// floor (band-limited irradiance vs. exact) falls with the band count.
TEST(Validate, ShadowedSpherePlaneUnderSmoothLight) {
  const Scene s = bakeScene("builtin:sphere-plane?grid=24&subdiv=3", TransferMode::Shadowed, 5, 0);
  const Environment env = smoothEnv();
  const sh::RgbSh light = envmap::projectEnvironment(env, 5);
  ValidateSettings vs;
  vs.reference.samples = 1024;
  vs.maxVertices = 250;
  const ValidationReport rep = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs);
  ASSERT_EQ(rep.rows.size(), 5u);
  EXPECT_TRUE(rep.warnings.empty());
  EXPECT_EQ(rep.reference.vertices.size(), 250u);
  const BandRow& r5 = rep.rows[4];
  EXPECT_EQ(r5.bands, 5);
  EXPECT_LT(r5.relRmse, 0.03);
  EXPECT_LE(r5.meanRel, r5.maxRel);
  EXPECT_GT(rep.rows[0].relRmse, 2 * r5.relRmse);  // one band misses the shadows and the disc
  EXPECT_GT(rep.rows[0].floor, rep.rows[2].floor);
  EXPECT_GT(r5.refStdErr, 0.0);
  EXPECT_LT(r5.refStdErr, 0.03);
  ASSERT_EQ(rep.vertexError.size(), 250u);
  EXPECT_NEAR(*std::max_element(rep.vertexError.begin(), rep.vertexError.end()), r5.maxRel, 1e-6);
  // The JSON names every column.
  const std::string json = reportJson(rep);
  for (const char* key : {"relRmse", "meanRelErr", "maxRelErr", "truncationFloor", "refStdErr"})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

// Glossy acceptance: a shadowed matrix bake at 6 bands with a Phong lobe that 6 bands hold (its
// energy beyond 6 bands is under 2%), under the smooth environment, against the glossy
// brute-force reference seen from the same eye: within 5% relative RMSE, within the truncation
// floor plus noise, and the error falls with bands.
TEST(Validate, GlossyMatrixAtSixBandsAgreesWithTheGlossyReference) {
  Scene s;
  s.mesh = builtinScene("builtin:sphere-plane?grid=20&subdiv=3");
  s.occ = makeEmbreeOccluder(s.mesh);
  s.bake.mode = TransferMode::Shadowed;
  s.bake.layout = TransferLayout::Matrix;
  s.bake.bands = 6;
  s.bake.samples = 1024;
  s.bake.material = parseMaterial("phong?exponent=6&ks=0.6&kd=0.4");
  ASSERT_LT(s.bake.material.lobe.energyBeyond(6), 0.02);
  s.transfer = bake(s.mesh, *s.occ, s.bake);
  const Environment env = smoothEnv();
  const sh::RgbSh light = envmap::projectEnvironment(env, 6);
  ValidateSettings vs;
  vs.reference.samples = 1024;
  vs.reference.eye = Vec3f(0.5f, 2.5f, 4.0f);
  vs.maxVertices = 200;
  vs.floorVertices = 200;
  const ValidationReport rep = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs);
  ASSERT_EQ(rep.rows.size(), 6u);
  const BandRow& r6 = rep.rows[5];
  std::printf("glossy 6 bands: rel RMSE %.4f floor %.4f ref noise %.4f lobe beyond %.4f\n",
              r6.relRmse, r6.floor, r6.refStdErr, r6.lobeEnergyBeyond);
  EXPECT_LT(r6.relRmse, 0.05);
  EXPECT_LT(r6.relRmse, r6.floor + 3 * r6.refStdErr + 0.01);
  EXPECT_GT(rep.rows[1].relRmse, 1.5 * r6.relRmse);
  EXPECT_GT(rep.rows[0].lobeEnergyBeyond, r6.lobeEnergyBeyond);
  // Without the eye, glossy validation is refused (PRT and reference must share the view).
  vs.reference.eye.reset();
  EXPECT_THROW(validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs), Error);
}

// Under a constant environment one band is exact (L = c Y00 √4π), so the floor vanishes and the
// inter-reflected bake must agree with the path-traced reference to within noise and the bake's
// interpolation of transfer across triangles. Sphere-plane: the underside of the sphere is lit
// mostly by the plane's first bounce.
TEST(Validate, InterreflectedSpherePlaneUnderConstantLight) {
  const Scene s =
      bakeScene("builtin:sphere-plane?h=0.7&grid=32&subdiv=3", TransferMode::Interreflected, 2, 1);
  const Environment env = Environment::analytic([](const Vec3f&) { return Rgb(1.0f); }, {}, 64);
  const sh::RgbSh light = envmap::projectEnvironment(env, 2);
  ValidateSettings vs;
  vs.reference.samples = 1024;
  vs.maxVertices = 200;
  vs.bandsList = {1};
  const ValidationReport rep = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs);
  ASSERT_EQ(rep.rows.size(), 1u);
  EXPECT_EQ(rep.bounces, 1);
  EXPECT_LT(rep.rows[0].floor, 1e-3);
  EXPECT_LT(rep.rows[0].relRmse, 0.03);
  // Dropping the bounce in the reference would be visible: the sphere's underside gets most of
  // its light from the plane.
  BakeSettings noBounce = s.bake;
  noBounce.bounces = 0;
  const ValidationReport wrong = validate(s.mesh, *s.occ, s.transfer, noBounce, env, light, vs);
  EXPECT_GT(wrong.rows[0].relRmse, 2 * rep.rows[0].relRmse);
}

// Glossy inter-reflection: a mostly glossy sphere-plane (kd 0.2, ks 0.8, a Phong lobe 6 bands
// hold), one bounce, 6 bands, under the smooth environment. The plane mirrors sky and sphere
// into each other, so what the bounce surfaces send depends on the direction they send it in.
// PRT with glossy bounces agrees with the reference (whose bounces follow the same lobe, with no
// SH) within the floor and its noise; the same matrices baked with diffuse bounce surfaces (the
// physics without the glossy bounce) and relit with the same lobe miss by far more.
TEST(Validate, GlossyBouncesAgreeWithTheGlossyReference) {
  Scene s;
  s.mesh = builtinScene("builtin:sphere-plane?h=0.6&grid=20&subdiv=3");
  s.occ = makeEmbreeOccluder(s.mesh);
  s.bake.mode = TransferMode::Interreflected;
  s.bake.layout = TransferLayout::Matrix;
  s.bake.bands = 6;
  s.bake.samples = 512;
  s.bake.bounces = 1;
  s.bake.material = parseMaterial("phong?exponent=3&ks=0.8&kd=0.2");
  ASSERT_LT(s.bake.material.lobe.energyBeyond(6), 0.01);
  s.transfer = bake(s.mesh, *s.occ, s.bake);
  BakeSettings diffuseBounces = s.bake;
  diffuseBounces.material = parseMaterial("lambert?kd=0.2");
  const Transfer old = bake(s.mesh, *s.occ, diffuseBounces);

  const Environment env = smoothEnv();
  const sh::RgbSh light = envmap::projectEnvironment(env, 6);
  ValidateSettings vs;
  vs.reference.samples = 1024;
  vs.reference.eye = Vec3f(0.5f, 2.5f, 4.0f);
  vs.maxVertices = 200;
  vs.floorVertices = 100;
  vs.bandsList = {6};
  const ValidationReport rep = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs);
  const ValidationReport without = validate(s.mesh, *s.occ, old, s.bake, env, light, vs);
  ASSERT_EQ(rep.rows.size(), 1u);
  const BandRow& r = rep.rows[0];
  std::printf(
      "glossy bounces 6 bands: rel RMSE %.4f (diffuse bounce surfaces %.4f) floor %.4f "
      "ref noise %.4f\n",
      r.relRmse, without.rows[0].relRmse, r.floor, r.refStdErr);
  EXPECT_LT(r.relRmse, 0.05);
  EXPECT_LT(r.relRmse, r.floor + 3 * r.refStdErr + 0.01);
  EXPECT_GT(without.rows[0].relRmse, 2 * r.relRmse);
}

// The floor of shadowed transfer is the reference run with the residual light L − L_b, so it
// covers visibility: it is what a perfect b-band transfer would still miss. Where truncation
// dominates (few bands) the bake's error sits on it; it is never far below the error; and it is
// larger than the unshadowed floor of the same scene (shadows need more bands than irradiance).
TEST(Validate, ShadowedFloorIsTheErrorOfAPerfectTransfer) {
  const Scene s = bakeScene("builtin:sphere-plane?grid=24&subdiv=3", TransferMode::Shadowed, 5, 0);
  const Environment env = smoothEnv();
  const sh::RgbSh light = envmap::projectEnvironment(env, 5);
  ValidateSettings vs;
  vs.reference.samples = 1024;
  vs.maxVertices = 250;
  const ValidationReport rep = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs);
  ASSERT_EQ(rep.rows.size(), 5u);
  EXPECT_EQ(rep.floorMethod, "residual reference");
  EXPECT_EQ(rep.floorVertices, 250u);
  EXPECT_GT(rep.floorRays, 0u);
  for (const BandRow& r : rep.rows) {
    SCOPED_TRACE(r.bands);
    // error² ≈ floor² + noise²: the floor is never above the error by more than noise.
    EXPECT_LT(r.floor, r.relRmse + 2 * r.refStdErr);
  }
  for (int b : {1, 2})  // truncation dominates: the error is the floor
    EXPECT_NEAR(rep.rows[b - 1].relRmse, rep.rows[b - 1].floor, 0.15 * rep.rows[b - 1].relRmse)
        << b << " bands";
  EXPECT_GT(rep.rows[0].floor, rep.rows[4].floor);

  Scene u = bakeScene("builtin:sphere-plane?grid=24&subdiv=3", TransferMode::Unshadowed, 5, 0);
  const ValidationReport unshadowed = validate(u.mesh, *u.occ, u.transfer, u.bake, env, light, vs);
  EXPECT_EQ(unshadowed.floorMethod, "irradiance quadrature");
  EXPECT_EQ(unshadowed.floorRays, 0u);
  EXPECT_LT(unshadowed.rows[2].floor, 0.03);  // irradiance is nearly 3-band (R&H 2001)
  EXPECT_GT(rep.rows[2].floor, 1.5 * unshadowed.rows[2].floor);
  for (std::size_t k = 0; k < rep.rows.size(); ++k)
    std::printf(
        "bands %d: shadowed rel RMSE %.4f floor %.4f (ref std err %.4f); unshadowed "
        "rel RMSE %.4f floor %.4f\n",
        rep.rows[k].bands, rep.rows[k].relRmse, rep.rows[k].floor, rep.rows[k].refStdErr,
        unshadowed.rows[k].relRmse, unshadowed.rows[k].floor);
}

// The energy-weighted error is ‖R_b − R_ref‖ / ‖R_ref‖: a transfer that doubles every radiance
// is off by exactly its own energy, 100%; the exact one (unshadowed, constant light, one band)
// by the reference noise only.
TEST(Validate, EnergyWeightedErrorOfADoubledTransfer) {
  Scene s = bakeScene("builtin:sphere?subdiv=2", TransferMode::Unshadowed, 2, 0);
  const Environment env = Environment::analytic([](const Vec3f&) { return Rgb(0.7f); }, {}, 64);
  const sh::RgbSh light = envmap::projectEnvironment(env, 2);
  ValidateSettings vs;
  vs.reference.samples = 256;
  vs.bandsList = {1};
  const ValidationReport exact = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs);
  // Only the reference's noise (and the bake's, far smaller) separates them.
  EXPECT_LT(exact.rows[0].energyRel, 2 * exact.rows[0].refStdErr + 0.002);
  float* x = s.transfer.mutableValues();
  for (std::size_t i = 0; i < s.transfer.values().size(); ++i) x[i] *= 2;
  const ValidationReport twice = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs);
  EXPECT_NEAR(twice.rows[0].energyRel, 1.0, 0.03);
  EXPECT_NE(reportJson(twice).find("\"energyWeightedRelErr\""), std::string::npos);
  EXPECT_NE(formatTable(twice).find("energy-weighted"), std::string::npos);
}

TEST(Validate, BandReconciliationAndBadInput) {
  const Scene s = bakeScene("builtin:sphere?subdiv=1", TransferMode::Shadowed, 3, 0);
  const Environment env = smoothEnv();
  ValidateSettings vs;
  vs.reference.samples = 16;
  // A light with fewer bands than the transfer: validate up to the smaller, and warn.
  const ValidationReport rep =
      validate(s.mesh, *s.occ, s.transfer, s.bake, env, envmap::projectEnvironment(env, 2), vs);
  EXPECT_EQ(rep.bands, 2);
  EXPECT_EQ(rep.rows.size(), 2u);
  EXPECT_FALSE(rep.warnings.empty());
  // Band counts beyond what is available are skipped with a warning; none left is an error.
  const sh::RgbSh light3 = envmap::projectEnvironment(env, 3);
  vs.bandsList = {2, 7};
  const ValidationReport r2 = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light3, vs);
  ASSERT_EQ(r2.rows.size(), 1u);
  EXPECT_EQ(r2.rows[0].bands, 2);
  EXPECT_EQ(r2.warnings.size(), 1u);
  vs.bandsList = {9};
  EXPECT_THROW(validate(s.mesh, *s.occ, s.transfer, s.bake, env, light3, vs), Error);
  vs.bandsList = {0};
  EXPECT_THROW(validate(s.mesh, *s.occ, s.transfer, s.bake, env, light3, vs), Error);
  vs.bandsList.clear();
  vs.reference.samples = 0;
  EXPECT_THROW(validate(s.mesh, *s.occ, s.transfer, s.bake, env, light3, vs), Error);
  // A transfer for another mesh.
  vs.reference.samples = 16;
  TransferShape shorter = s.transfer.shape();
  shorter.rows.count -= 1;
  EXPECT_THROW(validate(s.mesh, *s.occ, Transfer::zeros(shorter), s.bake, env, light3, vs), Error);
}

TEST(Validate, VertexSubsetIsDeterministicSortedAndUnique) {
  const auto a = vertexSubset(1000, 100, 5), b = vertexSubset(1000, 100, 5);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
  EXPECT_EQ(std::set<std::uint32_t>(a.begin(), a.end()).size(), 100u);
  EXPECT_LT(a.back(), 1000u);
  EXPECT_NE(a, vertexSubset(1000, 100, 6));
  EXPECT_EQ(vertexSubset(10, 0, 1).size(), 10u);
  EXPECT_EQ(vertexSubset(10, 50, 1).size(), 10u);
}

}  // namespace
}  // namespace prt::render
