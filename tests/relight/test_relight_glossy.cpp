// Glossy relighting (prt/relight/relight.hpp, view_transfer.hpp, relighter.hpp) and the material's
// lobes (prt/transfer/material.hpp):
//  * Phong zonal factors against their closed forms; Λ_0 = 1 for every lobe; energy beyond B
//    falls with B and with roughness;
//  * the kernel equals a naive double-precision evaluation of kd (dᵀ M L) + ks (gᵀ M L), scalar
//    and RGB transfer, with light of as many and of fewer bands than the transfer;
//  * white furnace: a convex sphere under L = 1 never reflects more than ks + kd;
//  * turning the light by R equals turning the scene (and the eye) by R⁻¹;
//  * material specs round-trip and bad ones are refused with one line.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/random_data.hpp"
#include "prt/core/cpu.hpp"
#include "prt/core/error.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/relighter.hpp"
#include "prt/relight/view_transfer.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transport/bake.hpp"

namespace prt {
namespace {

TEST(Material, PhongZonalFactorsMatchClosedForms) {
  for (double s : {0.0, 1.0, 8.0, 64.0}) {
    const Material m = parseMaterial("phong?exponent=" + std::to_string(s));
    const auto z = m.lobe.zonal(4);
    EXPECT_NEAR(z[0], 1.0, 1e-9);
    EXPECT_NEAR(z[1], (s + 1) / (s + 2), 2e-6) << s;
    EXPECT_NEAR(z[2], (s + 1) / 2 * (3 / (s + 3) - 1 / (s + 1)), 2e-6) << s;
  }
}

TEST(Material, GgxLobeIsNormalisedAndSharpensWithLowerRoughness) {
  const Material rough = parseMaterial("ggx?roughness=0.9");
  const Material sharp = parseMaterial("ggx?roughness=0.2");
  EXPECT_NEAR(rough.lobe.zonal(3)[0], 1.0, 1e-9);
  EXPECT_GT(sharp.lobe.zonal(6)[5], rough.lobe.zonal(6)[5]);
  EXPECT_GT(sharp.lobe.energyBeyond(6), rough.lobe.energyBeyond(6));
  double previous = 1.0;
  for (int b = 1; b <= 12; ++b) {
    const double e = sharp.lobe.energyBeyond(b);
    EXPECT_LE(e, previous + 1e-12);
    previous = e;
  }
  EXPECT_LT(previous, sharp.lobe.energyBeyond(1));
  EXPECT_LT(rough.lobe.energyBeyond(6), 0.1);  // a rough lobe fits in a few bands
}

TEST(Material, SpecsRoundTripAndBadOnesAreRefused) {
  for (const char* spec : {"lambert", "phong?exponent=32&ks=0.5", "ggx?roughness=0.3&ks=0.04",
                           "phong?exponent=4&ks=0.2,0.3,0.4&kd=0.5"}) {
    const Material m = parseMaterial(spec);
    EXPECT_EQ(parseMaterial(m.spec()), m) << spec;
  }
  EXPECT_TRUE(parseMaterial("phong").glossy());
  EXPECT_FALSE(parseMaterial("lambert?kd=0.5").glossy());
  for (const char* bad : {"plastic", "phong?exponent=-1", "ggx?roughness=0", "phong?ks=2",
                          "phong?shininess=3", "phong?kd=1,2", "ggx?roughness=abc"})
    EXPECT_THROW(parseMaterial(bad), Error) << bad;
}

/// A small scene with an unshadowed matrix bake.
struct Baked {
  Mesh mesh;
  Transfer m;
  explicit Baked(const std::string& scene, int bands) : mesh(builtinScene(scene)) {
    auto occ = makeEmbreeOccluder(mesh);
    BakeSettings s;
    s.mode = TransferMode::Unshadowed;
    s.layout = TransferLayout::Matrix;
    s.bands = bands;
    m = bake(mesh, *occ, s);
  }
};

/// Glossy relighting through the one entry point.
std::vector<Rgb> glossy(const Transfer& t, const sh::RgbSh& light, const Material& mat,
                        const Mesh& mesh, const Vec3f& eye, std::span<const Rgb> albedo,
                        const Mat3d& rotation = Mat3d::identity(),
                        relight::RelightInfo* info = nullptr) {
  return relight::relight(t, light, mat, {mesh.positions, mesh.normals, albedo}, eye, rotation,
                          info);
}

/// The scalar matrices as RGB ones, channel c scaled by 0.5 + 0.25 c.
Transfer rgbOf(const Transfer& m) {
  TransferShape shape = m.shape();
  shape.channels = 3;
  Transfer rgb = Transfer::zeros(shape);
  float* x = rgb.mutableValues();
  for (std::size_t k = 0; k < m.values().size(); ++k)
    for (int c = 0; c < 3; ++c) x[3 * k + c] = m.values()[k] * (0.5f + 0.25f * c);
  return rgb;
}

sh::RgbSh someLight(int bands) {
  return envmap::projectEnvironment(envmap::builtinEnvironment("builtin:sky?elevation=35"), bands);
}

/// e = kd (dᵀ M L) + ks (gᵀ M L) in double, written plainly.
Rgb naive(const Transfer& t, std::size_t v, const sh::RgbSh& light, const Material& mat,
          const Vec3f& p, const Vec3f& n, const Vec3f& eye, const Rgb& albedo) {
  const int B = t.bands(), nc = B * B, nl = std::min(light.bands, B) * std::min(light.bands, B);
  std::vector<double> yn(nc), yr(nc);
  sh::eval(B, Vec3d(n), yn.data());
  const Vec3d vd = normalize(Vec3d(eye - p));
  const Vec3d nd(n);
  const Vec3d r = nd * (2 * dot(nd, vd)) - vd;
  sh::eval(B, r, yr.data());
  const auto a = sh::clampedCosineKernel(B);
  const auto z = mat.lobe.zonal(B);
  Rgb out(0.0f);
  for (int c = 0; c < 3; ++c) {
    double diff = 0, spec = 0;
    for (int i = 0; i < nc; ++i) {
      const int l = static_cast<int>(std::sqrt(double(i)));
      double li = 0;  // (M L_c)_i
      for (int j = 0; j < nl; ++j)
        li += double(t.row(v)[(i * nc + j) * t.channels() + (t.channels() == 1 ? 0 : c)]) *
              light.c[j][c];
      diff += a[l] / kPi * yn[i] * li;
      if (mat.glossy()) spec += z[l] * yr[i] * li;
    }
    const double kd = mat.diffuse ? (*mat.diffuse)[c] : albedo[c];
    out[c] = static_cast<float>(kd * diff + mat.specular[c] * spec);
  }
  return out;
}

TEST(RelightGlossy, KernelEqualsNaiveEvaluation) {
  Baked scene("builtin:sphere?subdiv=1", 4);
  const Vec3f eye(0.5f, 2.0f, 3.0f);
  const Material mat = parseMaterial("phong?exponent=12&ks=0.3,0.4,0.5");
  for (Simd simd : {Simd::Auto, Simd::Portable})
    for (int lightBands : {4, 3, 6}) {
      const ScopedSimd policy(simd);
      const sh::RgbSh light = someLight(lightBands);
      relight::RelightInfo info;
      const std::vector<Rgb> out =
          glossy(scene.m, light, mat, scene.mesh, eye, scene.mesh.albedo, Mat3d::identity(), &info);
      EXPECT_EQ(info.bands, std::min(4, lightBands));
      for (std::size_t v = 0; v < out.size(); ++v) {
        const Rgb want = naive(scene.m, v, light, mat, scene.mesh.positions[v],
                               scene.mesh.normals[v], eye, scene.mesh.albedo[v]);
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(out[v][c], want[c], 1e-4 * (1 + std::abs(want[c])))
              << "vertex " << v << " light bands " << lightBands;
      }
    }
  // RGB transfer: three different channels (the scalar field scaled per channel).
  const Transfer rgb = rgbOf(scene.m);
  const sh::RgbSh light = someLight(4);
  const std::vector<Rgb> out = glossy(rgb, light, mat, scene.mesh, eye, {});
  for (std::size_t v = 0; v < out.size(); ++v) {
    const Rgb want =
        naive(rgb, v, light, mat, scene.mesh.positions[v], scene.mesh.normals[v], eye, Rgb(1.0f));
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(out[v][c], want[c], 1e-4 * (1 + std::abs(want[c])));
  }
}

// The view-collapsed vector transfer relights like the matrices themselves for any light: band
// counts below, at and above the transfer's, turned lights, scalar and RGB matrices, per-vertex
// albedo and a material kd — compared against the naive double evaluation of the matrices.
TEST(RelightGlossy, ViewTransferRelightsLikeTheMatrices) {
  Baked scene("builtin:sphere?subdiv=1", 4);
  const Vec3f eye(0.5f, 2.0f, 3.0f);
  const Transfer rgb = rgbOf(scene.m);
  const relight::Surface surface{scene.mesh.positions, scene.mesh.normals, scene.mesh.albedo};
  for (const char* spec :
       {"phong?exponent=12&ks=0.3,0.4,0.5", "ggx?roughness=0.4&ks=0.2&kd=0.6", "lambert"}) {
    SCOPED_TRACE(spec);
    const Material mat = parseMaterial(spec);
    for (const Transfer* m : {static_cast<const Transfer*>(&scene.m), &rgb}) {
      const Transfer t = relight::viewTransfer(*m, prepareMaterial(mat, 4), surface, eye);
      ASSERT_EQ(t.layout(), TransferLayout::Vector);
      ASSERT_EQ(t.channels(), 3);
      for (int lightBands : {4, 3, 6}) {
        const sh::RgbSh light = someLight(lightBands);
        const Mat3d turn = rotationEulerXYZ(10, 40 * lightBands, 0);
        const std::vector<Rgb> out = relight::relight(t, light, Material{}, {}, Vec3f(0.0f), turn);
        const sh::RgbSh turned = sh::Rotation(lightBands, turn).apply(light);
        for (std::size_t v = 0; v < out.size(); ++v) {
          const Rgb want = naive(*m, v, turned, mat, scene.mesh.positions[v], scene.mesh.normals[v],
                                 eye, scene.mesh.albedo[v]);
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(out[v][c], want[c], 1e-4 * (1 + std::abs(want[c])))
                << "vertex " << v << " light bands " << lightBands;
        }
      }
    }
  }
}

TEST(RelightGlossy, WhiteFurnaceNeverExceedsTheLight) {
  // L = 1 on a convex sphere, energy-conserving lobes, kd + ks ≤ 1: exit radiance ≤ 1 (up to the
  // SH ringing of the hemisphere edge, which the lobe's own smoothing keeps below 2%).
  Baked scene("builtin:sphere?subdiv=3", 6);
  sh::RgbSh white(6);
  white.c[0] = Rgb(static_cast<float>(std::sqrt(4 * kPi)));
  for (const char* spec : {"phong?exponent=4&ks=0.6&kd=0.4", "ggx?roughness=0.5&ks=0.7&kd=0.3",
                           "phong?exponent=1&ks=1&kd=0"}) {
    const Material mat = parseMaterial(spec);
    const std::vector<Rgb> out =
        glossy(scene.m, white, mat, scene.mesh, Vec3f(0.3f, 1.0f, 4.0f), {});
    float hi = 0, lo = 1e9f;
    for (const Rgb& e : out) {
      hi = std::max(hi, e.x);
      lo = std::min(lo, e.x);
    }
    EXPECT_LE(hi, 1.02f) << spec;
    EXPECT_GT(hi, 0.5f) << spec;  // and it is not trivially dark
    EXPECT_GE(lo, -0.02f) << spec;
  }
}

// The same furnace with glossy inter-reflection: sphere-plane, kd + ks = 1, two bounces off
// surfaces of the same material. No surface reflects more than it receives, so under L = 1 no
// vertex exceeds 1 (up to ringing and the bake's noise); and the bounces do add light where the
// sphere and the plane face each other.
TEST(RelightGlossy, WhiteFurnaceWithGlossyBouncesNeverExceedsTheLight) {
  const Mesh mesh = builtinScene("builtin:sphere-plane?h=0.6&grid=16&subdiv=2");
  auto occ = makeEmbreeOccluder(mesh);
  sh::RgbSh white(5);
  white.c[0] = Rgb(static_cast<float>(std::sqrt(4 * kPi)));
  const Vec3f eye(0.3f, 2.0f, 4.0f);
  for (const char* spec : {"phong?exponent=4&ks=0.6&kd=0.4", "ggx?roughness=0.5&ks=0.7&kd=0.3"}) {
    SCOPED_TRACE(spec);
    BakeSettings s;
    s.layout = TransferLayout::Matrix;
    s.mode = TransferMode::Interreflected;
    s.bounces = 2;
    s.bands = 5;
    s.samples = 1024;
    s.material = parseMaterial(spec);
    const Transfer inter = bake(mesh, *occ, s);
    s.mode = TransferMode::Shadowed;
    const Transfer direct = bake(mesh, *occ, s);
    const std::vector<Rgb> e = glossy(inter, white, s.material, mesh, eye, {});
    const std::vector<Rgb> e0 = glossy(direct, white, s.material, mesh, eye, {});
    float hi = 0, gain = 0;
    for (std::size_t v = 0; v < e.size(); ++v) {
      hi = std::max(hi, e[v].x);
      gain = std::max(gain, e[v].x - e0[v].x);
    }
    std::printf("%s: brightest vertex %.4f, largest gain from the bounces %.4f\n", spec, hi, gain);
    EXPECT_LE(hi, 1.03f);
    EXPECT_GT(gain, 0.2f);
  }
}

TEST(RelightGlossy, TurningTheLightEqualsTurningTheSceneBack) {
  const Mat3d rot = rotationEulerXYZ(20, 75, -10);
  const Mat3d inv = rot.transposed();
  Baked scene("builtin:sphere?subdiv=2", 5);
  // The scene turned by R⁻¹ (positions, normals), baked again.
  Mesh turned = scene.mesh;
  for (auto& p : turned.positions) p = Vec3f(inv * Vec3d(p));
  for (auto& n : turned.normals) n = normalize(Vec3f(inv * Vec3d(n)));
  auto occ = makeEmbreeOccluder(turned);
  BakeSettings s;
  s.mode = TransferMode::Unshadowed;
  s.layout = TransferLayout::Matrix;
  s.bands = 5;
  const Transfer mTurned = bake(turned, *occ, s);
  const Material mat = parseMaterial("ggx?roughness=0.4&ks=0.5&kd=0.5");
  const sh::RgbSh light = someLight(5);
  const Vec3f eye(0.2f, 1.5f, 3.0f);
  const std::vector<Rgb> a = glossy(scene.m, light, mat, scene.mesh, eye, {}, rot);
  const std::vector<Rgb> b = glossy(mTurned, light, mat, turned, Vec3f(inv * Vec3d(eye)), {});
  for (std::size_t v = 0; v < a.size(); ++v)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[v][c], b[v][c], 2e-3 * (1 + std::abs(b[v][c])));
}

TEST(RelightGlossy, MatricesNeedAPositionAndNormalPerRow) {
  Baked scene("builtin:sphere?subdiv=0", 3);
  std::vector<Rgb> out(scene.mesh.vertexCount());
  EXPECT_THROW(relight::relight(scene.m, someLight(3), Material{}, {}, Vec3f(0.0f), out), Error);
}

// The frame loop: frames in which only the light turns are relit from the matrices collapsed
// for the eye (after one full frame and the one that collapses them), and every frame equals the
// matrices relit through the entry point; a new eye, band count or material relights the
// matrices again; a frame with nothing changed returns the last radiance.
TEST(RelightGlossy, RelighterServesLightOnlyFramesFromTheCollapsedTransfer) {
  Baked scene("builtin:sphere?subdiv=1", 4);
  const Material mat = parseMaterial("phong?exponent=10&ks=0.4&kd=0.6");
  relight::Relighter r(scene.m, {scene.mesh.positions, scene.mesh.normals, scene.mesh.albedo});
  r.setMaterial(mat);
  const sh::RgbSh light = someLight(4);
  const auto frame = [&](double degrees, const Vec3f& eye) {
    const Mat3d turn = rotationEulerXYZ(0, degrees, 0);
    const std::span<const Rgb> got = r.relight(light, turn, eye);
    const std::vector<Rgb> want =
        glossy(scene.m.cut(r.bands()), light, mat, scene.mesh, eye, scene.mesh.albedo, turn);
    for (std::size_t v = 0; v < want.size(); ++v)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[v][c], want[v][c], 1e-4 * (1 + std::abs(want[v][c]))) << "vertex " << v;
  };
  const Vec3f eye(0.5f, 2.0f, 3.0f);
  frame(0, eye);
  EXPECT_EQ(r.lightOnlyFrames(), 0);
  frame(20, eye);
  frame(40, eye);
  EXPECT_EQ(r.frames(), 3);
  EXPECT_EQ(r.lightOnlyFrames(), 2);
  frame(40, eye);  // nothing changed: the same radiance, no relighting
  EXPECT_EQ(r.frames(), 3);
  frame(40, Vec3f(1.0f, 2.0f, 3.0f));  // the eye moved: the matrices again
  EXPECT_EQ(r.lightOnlyFrames(), 2);
  r.setBands(3);
  frame(60, Vec3f(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(r.lightOnlyFrames(), 2);
  frame(80, Vec3f(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(r.lightOnlyFrames(), 3);
  EXPECT_THROW(r.setBands(5), Error);
}

}  // namespace
}  // namespace prt
