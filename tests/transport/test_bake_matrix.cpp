// Glossy transfer matrices (TransferLayout::Matrix), each property against an independent
// computation or an exact identity:
//  * unshadowed M(n) equals the hemisphere product ∫_{n·ω>0} Y_i Y_j dω by a plain lat-long
//    quadrature in world coordinates (no rotation, no Gauss rule: independent of the bake's path);
//  * M(n) + M(−n) = I (the two hemispheres make the sphere: orthonormality);
//  * a convex sphere: shadowed equals unshadowed (no ray is blocked);
//  * the diffuse response dᵀM with d = (A_l/π) Y(n) — a lobe "as rough as Lambert" — reproduces
//    the vector bake of the same mode (shadowed and inter-reflected) within Monte Carlo error;
//  * determinism over threads and vertex ranges; the footprint is refused when too large.

#include <gtest/gtest.h>

#include "common/builtin_scene.hpp"
#include "common/random_data.hpp"

#include <cmath>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transport/bake.hpp"

namespace prt {
namespace {

using Scene = testdata::BuiltinScene;

BakeSettings matrixSettings(TransferMode mode, int bands, int samples) {
  BakeSettings s;
  s.mode = mode;
  s.layout = TransferLayout::Matrix;
  s.bands = bands;
  s.samples = samples;
  s.seed = 77;
  return s;
}

/// ∫_{n·ω>0} Y_i Y_j dω by the midpoint rule on a world lat-long grid (double).
std::vector<double> hemisphereQuadrature(int bands, const Vec3d& n, int rows) {
  const int nc = bands * bands, cols = 2 * rows;
  std::vector<double> h(static_cast<std::size_t>(nc * nc), 0.0), y(nc);
  for (int r = 0; r < rows; ++r) {
    const double theta = kPi * (r + 0.5) / rows;
    for (int c = 0; c < cols; ++c) {
      const double phi = 2 * kPi * (c + 0.5) / cols;
      const Vec3d w(std::sin(theta) * std::cos(phi), std::cos(theta),
                    std::sin(theta) * std::sin(phi));
      if (dot(w, n) <= 0) continue;
      const double dw = std::sin(theta) * (kPi / rows) * (2 * kPi / cols);
      sh::eval(bands, w, y.data());
      for (int i = 0; i < nc; ++i)
        for (int j = 0; j < nc; ++j) h[i * nc + j] += dw * y[i] * y[j];
    }
  }
  return h;
}

/// dᵀM: the diffuse response of a matrix row (channel c), to compare with a vector bake.
std::vector<double> diffuseResponse(const Transfer& m, std::size_t v, const Vec3f& n, int c) {
  const int B = m.bands(), nc = B * B;
  std::vector<double> y(nc), out(nc, 0.0);
  sh::eval(B, Vec3d(n), y.data());
  const auto a = sh::clampedCosineKernel(B);
  const float* row = m.row(v);
  for (int l = 0; l < B; ++l)
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) {
      const double di = a[l] / kPi * y[i];
      for (int j = 0; j < nc; ++j) out[j] += di * row[(i * nc + j) * m.channels() + c];
    }
  return out;
}

TEST(BakeMatrix, UnshadowedEqualsHemisphereProductByIndependentQuadrature) {
  Scene scene("builtin:sphere?subdiv=2");
  const int B = 4, nc = 16;
  const Transfer m =
      bake(scene.mesh, *scene.occluder, matrixSettings(TransferMode::Unshadowed, B, 16));
  ASSERT_EQ(m.layout(), TransferLayout::Matrix);
  ASSERT_EQ(m.values().size(), scene.mesh.vertexCount() * nc * nc);
  for (std::size_t v : {std::size_t(0), std::size_t(7), std::size_t(101)}) {
    const Vec3d n(scene.mesh.normals[v]);
    const auto ref = hemisphereQuadrature(B, normalize(n), 600);
    double worst = 0;
    for (int k = 0; k < nc * nc; ++k) worst = std::max(worst, std::abs(m.row(v)[k] - ref[k]));
    // The midpoint rule's error at the hemisphere's edge is O(h) ≈ 1e-3 at 600 rows.
    EXPECT_LT(worst, 3e-3) << "vertex " << v;
  }
}

TEST(BakeMatrix, OppositeHemispheresSumToIdentity) {
  // Two vertices with opposite normals: H(n) + H(−n) = ∫ Y Yᵀ dω over the sphere = I.
  Mesh mesh;
  const Vec3f n = normalize(Vec3f(0.3f, 0.8f, -0.52f));
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals = {n, -n, n};
  mesh.triangles = {{0, 1, 2}};
  auto occ = makeEmbreeOccluder(mesh);
  for (int B : {3, 6, 9}) {
    const Transfer m = bake(mesh, *occ, matrixSettings(TransferMode::Unshadowed, B, 16));
    const int nc = B * B;
    double worst = 0;
    for (int i = 0; i < nc; ++i)
      for (int j = 0; j < nc; ++j) {
        const double sum = m.row(0)[i * nc + j] + m.row(1)[i * nc + j];
        worst = std::max(worst, std::abs(sum - (i == j ? 1.0 : 0.0)));
      }
    EXPECT_LT(worst, 2e-5) << B << " bands";
  }
}

TEST(BakeMatrix, ConvexSphereShadowedEqualsUnshadowed) {
  Scene scene("builtin:sphere?subdiv=3");
  BakeStats stats;
  const Transfer u =
      bake(scene.mesh, *scene.occluder, matrixSettings(TransferMode::Unshadowed, 3, 64));
  const Transfer s =
      bake(scene.mesh, *scene.occluder, matrixSettings(TransferMode::Shadowed, 3, 256), &stats);
  EXPECT_EQ(stats.rays, scene.mesh.vertexCount() * 256);
  EXPECT_EQ(testdata::valuesOf(s),
            testdata::valuesOf(u));  // control variate: no blocked ray, the exact H(n)
}

TEST(BakeMatrix, DiffuseResponseReproducesTheVectorBake) {
  // Sphere above a plane: shadows on the plane. A diffuse lobe applied to M must give the
  // vector transfer; both are Monte Carlo estimates of the same integral (different sample
  // sets), so they agree within a few standard errors.
  Scene scene("builtin:sphere-plane?grid=24&subdiv=2");
  for (TransferMode mode : {TransferMode::Shadowed, TransferMode::Interreflected}) {
    BakeSettings sv = matrixSettings(mode, 3, 1024);
    sv.layout = TransferLayout::Vector;
    sv.bounces = 1;
    BakeSettings sm = sv;
    sm.layout = TransferLayout::Matrix;
    BakeStats stV, stM;
    const Transfer vec = bake(scene.mesh, *scene.occluder, sv, &stV);
    const Transfer mat = bake(scene.mesh, *scene.occluder, sm, &stM);
    ASSERT_EQ(mat.channels(), vec.channels());
    double sumErr = 0, worst = 0;
    for (std::size_t v = 0; v < vec.rowCount(); ++v) {
      const auto r = diffuseResponse(mat, v, scene.mesh.normals[v], 0);
      for (int i = 0; i < 9; ++i) {
        const double e = std::abs(r[i] - vec.row(v)[i * vec.channels()]);
        sumErr += e;
        worst = std::max(worst, e);
      }
    }
    const double meanErr = sumErr / (9.0 * vec.rowCount());
    // Standard errors of T00 are ~1e-3 at 1024 samples; allow 4σ on the mean and 10σ worst.
    const double sigma = std::max(stV.stdErrT0Mean, stM.stdErrT0Mean) + 1e-4;
    EXPECT_LT(meanErr, 4 * sigma) << toString(mode);
    EXPECT_LT(worst, 10 * std::max(stV.stdErrT0Max, stM.stdErrT0Max) + 1e-3) << toString(mode);
    // And the vector bake is not trivially equal to zero response.
    EXPECT_GT(std::abs(vec.row(0)[0]), 0.05);
  }
}

TEST(BakeMatrix, ColouredBouncesGiveRgbMatrices) {
  Scene scene("builtin:cornell?grid=6");
  BakeSettings s = matrixSettings(TransferMode::Interreflected, 3, 256);
  s.bounces = 1;
  const Transfer m = bake(scene.mesh, *scene.occluder, s);
  EXPECT_EQ(m.channels(), 3);  // the red and green walls
  EXPECT_EQ(bakeFootprint(scene.mesh, s).channels, 3);
  m.check("cornell");
}

TEST(BakeMatrix, IdenticalForAnyThreadCountAndRange) {
  Scene scene("builtin:sphere-plane?grid=16&subdiv=1");
  for (const char* material : {"lambert", "phong?exponent=4&ks=0.5&kd=0.5"}) {
    SCOPED_TRACE(material);
    BakeSettings s = matrixSettings(TransferMode::Interreflected, 3, 128);
    s.bounces = 2;
    s.material = parseMaterial(material);
    Transfer one, two;
    {
      ThreadLimit limit(1);
      one = bake(scene.mesh, *scene.occluder, s);
    }
    {
      ThreadLimit limit(2);
      two = bake(scene.mesh, *scene.occluder, s);
    }
    EXPECT_EQ(testdata::valuesOf(one), testdata::valuesOf(two));
    BakeSettings r = s;
    r.rows = {50, 40};
    const Transfer part = bake(scene.mesh, *scene.occluder, r);
    ASSERT_EQ(part.rowCount(), 40u);
    for (std::size_t v = 0; v < 40; ++v)
      for (std::size_t k = 0; k < part.stride(); ++k) ASSERT_EQ(part.row(v)[k], one.row(50 + v)[k]);
  }
}

/// ‖M_a − M_b‖_F over all rows and channels.
double frobeniusDistance(const Transfer& a, const Transfer& b) {
  double sum = 0;
  for (std::size_t k = 0; k < a.values().size(); ++k)
    sum += std::pow(double(a.values()[k]) - b.values()[k], 2);
  return std::sqrt(sum);
}

// Glossy bounce surfaces send M^{K−1}(h)ᵀ (ρ d + ks g) toward p; with a vanishing ks that is the
// diffuse response of the matrices at the hit, M^{K−1}(h)ᵀ d(n_h) ρ, which must reproduce the
// diffuse bounces (ρ T^{K−1}(h), from vector transfer: another estimator, another code path).
// The direct parts of the two bakes are the same samples, so the comparison is of the bounced
// light alone; it must be far closer than the bounce is large.
TEST(BakeMatrix, AVanishingLobeBouncesLikeADiffuseSurface) {
  Scene scene("builtin:sphere-plane?h=0.6&grid=20&subdiv=2");
  for (int bounces : {1, 2}) {
    BakeSettings sd = matrixSettings(TransferMode::Interreflected, 3, 512);
    sd.bounces = bounces;
    sd.material = parseMaterial("lambert?kd=0.8");
    BakeSettings sg = sd;
    sg.material = parseMaterial("phong?exponent=4&ks=1e-6&kd=0.8");
    BakeSettings sh = sd;
    sh.mode = TransferMode::Shadowed;
    const Transfer diffuse = bake(scene.mesh, *scene.occluder, sd);
    const Transfer glossy = bake(scene.mesh, *scene.occluder, sg);
    const Transfer direct = bake(scene.mesh, *scene.occluder, sh);
    const double bounce = frobeniusDistance(diffuse, direct);
    const double gap = frobeniusDistance(glossy, diffuse);
    std::printf("%d bounce(s): bounced light %.4f, glossy vs diffuse bounce surfaces %.4f\n",
                bounces, bounce, gap);
    EXPECT_GT(bounce, 1.0);
    EXPECT_LT(gap, 0.1 * bounce);
  }
}

// ks enters the bounced light once and linearly: with kd = 0 the bounce of one order is
// ks M⁰(h)ᵀ g, so doubling ks doubles M − M⁰ (same samples: to float rounding); the RGB ks
// (0.2, 0.4, 0.8) gives three channels in that ratio.
TEST(BakeMatrix, GlossyBounceIsLinearInKsPerChannel) {
  Scene scene("builtin:sphere-plane?h=0.6&grid=12&subdiv=1");
  BakeSettings s = matrixSettings(TransferMode::Interreflected, 3, 256);
  s.bounces = 1;
  s.material = parseMaterial("phong?exponent=8&ks=0.2,0.4,0.8&kd=0");
  BakeSettings sh = s;
  sh.mode = TransferMode::Shadowed;
  const Transfer m = bake(scene.mesh, *scene.occluder, s);
  const Transfer m0 = bake(scene.mesh, *scene.occluder, sh);
  ASSERT_EQ(m.channels(), 3);
  ASSERT_EQ(m0.channels(), 1);
  double sum1 = 0, worst = 0;
  for (std::size_t v = 0; v < m.rowCount(); ++v)
    for (std::size_t k = 0; k < m0.stride(); ++k) {
      const double b0 = m.row(v)[3 * k] - m0.row(v)[k];
      const double b1 = m.row(v)[3 * k + 1] - m0.row(v)[k];
      const double b2 = m.row(v)[3 * k + 2] - m0.row(v)[k];
      sum1 += std::abs(b1);
      worst = std::max({worst, std::abs(b1 - 2 * b0), std::abs(b2 - 2 * b1)});
    }
  EXPECT_GT(sum1, 1.0);  // there is a bounce to compare
  EXPECT_LT(worst, 1e-5);
}

// The reported standard error of M_00 covers the bounce: two seeds' inter-reflected matrices
// differ (rms over the vertices, over √2 for the difference of two estimates) by no more than
// the reported error — which for scrambled Sobol' points is conservative — and by more than
// nothing. Diffuse and glossy bounce surfaces.
TEST(BakeMatrix, ReportedErrorCoversTheSeedToSeedSpread) {
  Scene scene("builtin:sphere-plane?h=0.6&grid=16&subdiv=2");
  for (const char* material : {"lambert?kd=0.8", "phong?exponent=4&ks=0.6&kd=0.3"}) {
    SCOPED_TRACE(material);
    BakeSettings s = matrixSettings(TransferMode::Interreflected, 3, 64);
    s.bounces = 1;
    s.material = parseMaterial(material);
    BakeStats st;
    const Transfer a = bake(scene.mesh, *scene.occluder, s, &st);
    s.seed = 78;
    const Transfer b = bake(scene.mesh, *scene.occluder, s);
    double sum = 0;
    for (std::size_t v = 0; v < a.rowCount(); ++v)
      sum += std::pow(double(a.row(v)[0]) - b.row(v)[0], 2);
    const double spread = std::sqrt(sum / double(a.rowCount()) / 2);
    std::printf("M00 seed-to-seed spread %.5f, reported mean standard error %.5f\n", spread,
                st.stdErrT0Mean);
    EXPECT_GT(spread, 0.0);
    EXPECT_GT(st.stdErrT0Mean, 0.0);
    EXPECT_LT(spread, 1.5 * st.stdErrT0Mean);
  }
}

TEST(BakeMatrix, TruncationKeepsTheLeadingBlock) {
  Scene scene("builtin:sphere?subdiv=1");
  const Transfer m5 =
      bake(scene.mesh, *scene.occluder, matrixSettings(TransferMode::Unshadowed, 5, 16));
  const Transfer m3 =
      bake(scene.mesh, *scene.occluder, matrixSettings(TransferMode::Unshadowed, 3, 16));
  const Transfer cut = m5.cut(3);
  ASSERT_EQ(cut.values().size(), m3.values().size());
  for (std::size_t k = 0; k < cut.values().size(); ++k)
    ASSERT_NEAR(cut.values()[k], m3.values()[k], 1e-6);
}

TEST(BakeMatrix, RefusesAFootprintBeyondMemoryWithTheFigure) {
  Scene scene("builtin:sphere?subdiv=1");
  BakeSettings s = matrixSettings(TransferMode::Shadowed, 16, 16);  // 256 KiB per vertex
  const BakeFootprint f = bakeFootprint(scene.mesh, s);
  EXPECT_EQ(f.bytesPerRow, std::size_t(16 * 16) * 16 * 16 * 4);
  Mesh big = scene.mesh;
  // 1e6 vertices × 256 KiB = 262 GB: refused before anything is allocated, with the figure.
  big.positions.resize(1000000, Vec3f(0.0f));
  big.normals.resize(1000000, Vec3f(0, 1, 0));
  big.albedo.clear();
  try {
    bake(big, *scene.occluder, s);
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("per vertex"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("GB"), std::string::npos) << e.what();
  }
  // More bands than a bake takes: refused by the one band limit.
  s.bands = 17;
  try {
    bake(scene.mesh, *scene.occluder, s);
    FAIL() << "17 bands were baked";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("1..16"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace prt
