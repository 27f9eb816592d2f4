// The Haar bake (transport/bake_haar.cpp): rows hold the occluded part D = U − T, pruned to their
// budget; against analytic answers (nothing occludes a convex sphere; the cosine-weighted
// occluded fraction below a sphere over a plane is (r/h)²), deterministic over threads and
// ranges, and its settings checked.

#include <gtest/gtest.h>

#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/haar/cube_texels.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/relight/relighter.hpp"
#include "prt/transfer/haar_rows.hpp"
#include "prt/transport/bake.hpp"

namespace prt {
namespace {

BakeSettings haarSettings(TransferMode mode, int resolution, int terms, int raysPerTexel = 1) {
  BakeSettings s;
  s.mode = mode;
  s.basis = TransferBasis::Haar;
  s.haar = {resolution, terms};
  s.samples = raysPerTexel;
  s.seed = 77;
  return s;
}

TEST(BakeHaar, UnshadowedAndConvexRowsHoldNoTerms) {
  const Mesh sphere = builtinScene("builtin:sphere?subdiv=2");
  const auto occ = makeEmbreeOccluder(sphere);
  for (TransferMode mode : {TransferMode::Unshadowed, TransferMode::Shadowed}) {
    const Transfer t = bake(sphere, *occ, haarSettings(mode, 8, 16));
    ASSERT_TRUE(t.isHaar());
    EXPECT_EQ(t.stride(), 33u);
    // D = 0: an occluded-part row (kind 0) of padding only.
    for (float x : t.values()) ASSERT_EQ(x, 0.0f) << toString(mode);
  }
}

TEST(BakeHaar, SphereAbovePlaneOccludesRatioSquared) {
  // Under the constant light L = 1 a row relights to U·1 − Σ D̃ L̃ = 1 − (r/h)² at the plane's
  // vertex below the sphere: the end-to-end check of bake, light and relighting.
  const double r = 0.5, h = 1.25;
  const Mesh mesh = builtinScene("builtin:sphere-plane?r=0.5&h=1.25&grid=32&subdiv=4");
  const auto occ = makeEmbreeOccluder(mesh);
  std::size_t below = 0;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    if (length(mesh.positions[v]) < length(mesh.positions[below])) below = v;
  ASSERT_LT(length(mesh.positions[below]), 1e-6f);
  BakeSettings s = haarSettings(TransferMode::Shadowed, 32, 256, 16);
  s.rows = {below, 1};
  BakeStats stats;
  const Transfer t = bake(mesh, *occ, s, &stats);
  const envmap::Environment white =
      envmap::Environment::analytic([](const Vec3f&) { return Rgb(1.0f); }, {});
  const haar::HaarLight light = haar::projectLight(white, 32, 200);
  const std::vector<Vec3f> normal = {mesh.normals[below]};
  const std::vector<Rgb> out = relight::relightHaar(t, light, normal, {});
  EXPECT_GT(stats.stdErrConstMax, 1e-4);  // the estimate is not degenerate
  EXPECT_NEAR(out[0].x, 1.0 - (r / h) * (r / h), 3 * stats.stdErrConstMax + 2e-3);
  // Every kept term is a coefficient of the cube, in ascending order.
  EXPECT_NO_THROW(t.check("haar"));
}

TEST(RelightHaar, BrightTexelsRelightAsTheirExactCosineIntegralsAtEveryNormal) {
  // A row of padding (kind 0, D = 0) relights to U(n)·L; with all of the light in its bright
  // texels (no SH, no terms) that is Σ_b L_b U_b(n), each U_b the texel's clamped-cosine
  // integral (cube_texels.hpp), independently summed here. The normals sweep the sphere finely,
  // so texels lie wholly above, wholly below and across their horizons (relight_haar.cpp takes
  // the first two from a cone's dot product, the last from the clipped polygon).
  const int n = 4;
  const haar::CubeTexels cube(n);
  haar::HaarLight light;
  light.resolution = n;
  light.unshadowed = sh::RgbSh(haar::kUnshadowedBands);
  for (std::uint32_t j : {0u, 5u, 21u, 38u, 47u, 60u, 77u, 95u})
    light.bright.push_back({j, Rgb(1.0f + float(j) / 10, 2.0f, 0.5f)});
  std::vector<Vec3f> normals;
  for (int i = 0; i < 4000; ++i) {
    const double z = 1 - (2 * i + 1) / 4000.0, phi = 2.399963229728653 * i,
                 s = std::sqrt(1 - z * z);
    normals.push_back(Vec3f(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)));
  }
  TransferShape shape;
  shape.basis = TransferBasis::Haar;
  shape.haar = {n, 3};
  shape.rows = {0, normals.size()};
  const std::vector<Rgb> out = relight::relightHaar(Transfer::zeros(shape), light, normals, {});
  int crossing = 0;
  double worst = 0;
  for (std::size_t r = 0; r < normals.size(); ++r) {
    Rgbd want(0.0);
    for (const haar::BrightTexel& b : light.bright) {
      const double u = cube.clampedCosine(b.texel, Vec3d(normals[r]));
      want += Rgbd(b.radiance) * u;
      int above = 0;
      for (const Vec3d& c : cube.corners(b.texel)) above += dot(c, Vec3d(normals[r])) >= 0;
      crossing += above > 0 && above < 4;
    }
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(out[r][c]) - want[c]));
  }
  EXPECT_GT(crossing, 200);  // the horizon crosses texels often enough to test the clipping
  EXPECT_LT(worst, 2e-6);
}

TEST(BakeHaar, EveryRowSeesTheSkyTheShBakeSees) {
  // Under the constant light L = 1 every row relights to its cosine-weighted visible fraction,
  // which the SH bake estimates independently as √(4π) T₀: both kinds of row (the open ones
  // storing their shadow, those facing the plane their window on the sky) must agree with it.
  const Mesh mesh = builtinScene("builtin:sphere-plane?grid=16&subdiv=3");
  const auto occ = makeEmbreeOccluder(mesh);
  const Transfer haarT = bake(mesh, *occ, haarSettings(TransferMode::Shadowed, 16, 1536, 4));
  BakeSettings ss;
  ss.mode = TransferMode::Shadowed;
  ss.bands = 1;
  ss.samples = 4096;
  const Transfer shT = bake(mesh, *occ, ss);
  const envmap::Environment white =
      envmap::Environment::analytic([](const Vec3f&) { return Rgb(1.0f); }, {});
  const std::vector<Rgb> relit =
      relight::relightHaar(haarT, haar::projectLight(white, 16, 1536), mesh.normals, {});
  double sq = 0, worst = 0;
  int visibleRows = 0;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const double sh = shT.row(v)[0] * std::sqrt(4 * kPi), d = relit[v].x - sh;
    sq += d * d;
    worst = std::max(worst, std::abs(d));
    visibleRows += haarT.row(v)[0] == 1.0f;
  }
  EXPECT_GT(visibleRows, 10);
  EXPECT_LT(std::sqrt(sq / double(mesh.vertexCount())), 0.01);
  EXPECT_LT(worst, 0.08);
}

BakeSettings interreflectedSettings(int resolution, int terms, int bounceBands) {
  BakeSettings s = haarSettings(TransferMode::Interreflected, resolution, terms);
  s.bounces = 1;
  s.haar.bounceBands = bounceBands;
  s.material.diffuse = Rgb(0.9f, 0.5f, 0.3f);
  return s;
}

TEST(BakeHaar, InterreflectedRowsAreTheShadowedRowsAndTheShBakesBounce) {
  // The pairs are the shadowed bake's, ray for ray; the bounce after them is what the SH bake
  // of the same bounces (its bands, 1024 directions a row per ray a texel, the same seed and
  // albedo) adds to its direct light — RGB under a coloured albedo.
  const Mesh mesh = builtinScene("builtin:sphere-plane?grid=8&subdiv=2");
  const auto occ = makeEmbreeOccluder(mesh);
  const BakeSettings s = interreflectedSettings(8, 24, 3);
  BakeStats stats;
  const Transfer t = bake(mesh, *occ, s, &stats);
  ASSERT_TRUE(t.isHaar());
  EXPECT_EQ(t.shape().haar.bounceBands, 3);
  ASSERT_EQ(t.channels(), 3);
  ASSERT_EQ(t.stride(), haar::haarRowFloats(24) + 27);
  BakeSettings direct = s;
  direct.mode = TransferMode::Shadowed;
  direct.bounces = 0;
  direct.haar.bounceBands = 0;
  const Transfer d = bake(mesh, *occ, direct);
  BakeSettings sh = s;
  sh.basis = TransferBasis::SphericalHarmonics;
  sh.haar = {};
  sh.bands = 3;
  sh.samples = kHaarBounceSamplesPerTexelRay;
  const Transfer full = bake(mesh, *occ, sh);
  sh.mode = TransferMode::Shadowed;
  sh.bounces = 0;
  const Transfer shDirect = bake(mesh, *occ, sh);
  double largest = 0;
  for (std::size_t r = 0; r < t.rowCount(); ++r) {
    for (std::size_t k = 0; k < d.stride(); ++k) ASSERT_EQ(t.row(r)[k], d.row(r)[k]) << r;
    const float* b = t.row(r) + d.stride();
    for (std::size_t i = 0; i < 9; ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        const double want = full.row(r)[i * 3 + c] - shDirect.row(r)[i];
        ASSERT_NEAR(b[i * 3 + c], want, 1e-6) << r << " " << i << " " << c;
        largest = std::max(largest, std::abs(want));
      }
  }
  EXPECT_GT(largest, 0.02);  // the plane under the sphere sees its bounce
  // The bounce's rays count in the statistics, its noise in the error estimate.
  ASSERT_EQ(stats.raysBounce.size(), 1u);
  EXPECT_GT(stats.raysBounce[0], 0u);
}

TEST(BakeHaar, DeterministicOverThreadsAndRanges) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?grid=8&subdiv=2");
  const auto occ = makeEmbreeOccluder(mesh);
  for (const BakeSettings& s :
       {haarSettings(TransferMode::Shadowed, 8, 24, 2), interreflectedSettings(8, 24, 2)}) {
    SCOPED_TRACE(toString(s.mode));
    const Transfer whole = bake(mesh, *occ, s);
    Transfer oneThread;
    {
      ThreadLimit limit(1);
      oneThread = bake(mesh, *occ, s);
    }
    ASSERT_EQ(whole.values().size(), oneThread.values().size());
    for (std::size_t k = 0; k < whole.values().size(); ++k)
      ASSERT_EQ(whole.values()[k], oneThread.values()[k]);
    BakeSettings part = s;
    part.rows = {30, 41};
    const Transfer piece = bake(mesh, *occ, part);
    for (std::size_t r = 0; r < 41; ++r)
      for (std::size_t k = 0; k < whole.stride(); ++k)
        ASSERT_EQ(piece.row(r)[k], whole.row(30 + r)[k]);
  }
}

TEST(BakeHaar, RejectsWhatItDoesNotMake) {
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=1");
  const auto occ = makeEmbreeOccluder(mesh);
  // An inter-reflected bake's bounce: 1..5 SH bands, and only with bounces.
  BakeSettings s = interreflectedSettings(8, 16, 0);
  EXPECT_THROW(bake(mesh, *occ, s), Error);
  s.haar.bounceBands = 6;
  EXPECT_THROW(bake(mesh, *occ, s), Error);
  s = haarSettings(TransferMode::Shadowed, 8, 16);
  s.haar.bounceBands = 2;
  EXPECT_THROW(bake(mesh, *occ, s), Error);
  s = haarSettings(TransferMode::Shadowed, 8, 16);
  s.layout = TransferLayout::Matrix;
  EXPECT_THROW(bake(mesh, *occ, s), Error);
  EXPECT_THROW(bake(mesh, *occ, haarSettings(TransferMode::Shadowed, 12, 16)), Error);
  EXPECT_THROW(bake(mesh, *occ, haarSettings(TransferMode::Shadowed, 8, 385)), Error);
  EXPECT_THROW(bake(mesh, *occ, haarSettings(TransferMode::Shadowed, 8, 16, 65)), Error);
  EXPECT_NO_THROW(bake(mesh, *occ, haarSettings(TransferMode::Shadowed, 8, 384)));
}

TEST(HaarRows, PruneKeepsTheLargestWeightedTermsInIndexOrder) {
  const int n = 4;
  std::vector<float> c(haar::coefficientCount(n), 0.0f);
  c[5] = 0.5f;    // face 0 at (1, 1): a detail of side 4
  c[17] = -3.0f;  // face 1
  c[40] = 0.25f;
  c[90] = 1.0f;
  std::vector<std::pair<float, std::uint32_t>> order;
  std::vector<float> row(haar::haarRowFloats(3));
  haar::pruneRow(c.data(), n, 3, haar::HaarRowKind::Visible, row.data(), order);
  EXPECT_EQ(row[0], 1.0f);  // the kind
  const float* out = row.data() + 1;
  // Weighted magnitudes |c|·side; the three largest, in ascending index.
  std::vector<std::pair<double, std::uint32_t>> w;
  for (std::uint32_t k : {5u, 17u, 40u, 90u})
    w.push_back({std::abs(c[k]) * haar::supportSide(k, n), k});
  std::sort(w.rbegin(), w.rend());
  std::vector<std::uint32_t> expect = {w[0].second, w[1].second, w[2].second};
  std::sort(expect.begin(), expect.end());
  // The values on the row's 16-bit grid (haar_rows.hpp): within a step of the largest, 3.
  for (int t = 0; t < 3; ++t) {
    EXPECT_EQ(out[std::size_t(2 * t)], float(expect[std::size_t(t)]));
    EXPECT_NEAR(out[std::size_t(2 * t + 1)], c[expect[std::size_t(t)]], 3.0f / 32767);
  }
  EXPECT_NO_THROW(haar::checkRow(row.data(), n, 3, 0, "row"));
  // Fewer non-zeros than the budget: padding (0, 0) after them.
  std::vector<float> wide(haar::haarRowFloats(6));
  haar::pruneRow(c.data(), n, 6, haar::HaarRowKind::Occluded, wide.data(), order);
  EXPECT_EQ(wide[0], 0.0f);
  EXPECT_EQ(wide[9], 0.0f);
  EXPECT_EQ(wide[10], 0.0f);
  EXPECT_NO_THROW(haar::checkRow(wide.data(), n, 6, 0, "row"));
  // Broken rows are named.
  std::vector<float> bad = row;
  bad[3] = bad[1];  // not ascending
  EXPECT_THROW(haar::checkRow(bad.data(), n, 3, 0, "row"), Error);
  bad = row;
  bad[1] = 96.0f;  // past 6·4²
  EXPECT_THROW(haar::checkRow(bad.data(), n, 3, 0, "row"), Error);
  bad = row;
  bad[1] = 1.5f;  // not integral
  EXPECT_THROW(haar::checkRow(bad.data(), n, 3, 0, "row"), Error);
  bad = row;
  bad[0] = 2.0f;  // no such kind
  EXPECT_THROW(haar::checkRow(bad.data(), n, 3, 0, "row"), Error);
  bad = wide;
  bad[9] = 7.0f;  // padding with an index
  EXPECT_THROW(haar::checkRow(bad.data(), n, 6, 0, "row"), Error);
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

TEST(BakeHaar, ShRelightingRefusesHaarTransferByName) {
  // The SH entry points (relight::relight, the Relighter every viewer and RelitView draw
  // through) say what a Haar transfer needs instead of reading its wavelet terms as SH.
  const Mesh mesh = builtinScene("builtin:sphere?subdiv=1");
  const auto occ = makeEmbreeOccluder(mesh);
  const Transfer t = bake(mesh, *occ, haarSettings(TransferMode::Shadowed, 4, 8));
  const relight::Surface surface{mesh.positions, mesh.normals, {}};
  const std::string e = [&] {
    try {
      relight::relight(t, sh::RgbSh(3), Material{}, surface, Vec3f(0.0f));
    } catch (const Error& x) {
      return std::string(x.what());
    }
    return std::string();
  }();
  EXPECT_NE(e.find("relightHaar"), std::string::npos) << e;
  EXPECT_THROW(relight::Relighter(t, surface), Error);
}

}  // namespace
}  // namespace prt
