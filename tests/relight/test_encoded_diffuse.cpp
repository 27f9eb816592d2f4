// Diffuse radiance through an irradiance encoding (relight/encoded_diffuse.hpp): against an
// independent evaluation (the light rotated and multiplied through each matrix by hand, then
// sh::encodeIrradiance and sh::evaluate), against relight()'s own diffuse term for l2, and the
// non-negative encodings non-negative wherever the light arriving has a non-negative mean.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/random_data.hpp"
#include "prt/core/error.hpp"
#include "prt/core/sampling.hpp"
#include "prt/relight/encoded_diffuse.hpp"
#include "prt/relight/relight.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/sh/rotate.hpp"

namespace prt {
namespace {

using sh::IrradianceEncoding;

std::vector<Vec3f> randomNormals(std::size_t n, std::uint64_t seed) {
  Pcg32 rng(seed);
  std::vector<Vec3f> out(n);
  for (Vec3f& v : out) {
    const double z = 2 * rng.uniform() - 1, phi = 2 * kPi * rng.uniform();
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    v = Vec3f(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
  }
  return out;
}

std::vector<Rgb> randomAlbedo(std::size_t n, std::uint64_t seed) {
  Pcg32 rng(seed);
  std::vector<Rgb> out(n);
  for (Rgb& a : out) a = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
  return out;
}

/// L'_p = M_p (R L) by the layout's definition (transfer/shape.hpp: (M_p)_ij,c at
/// (i·B² + j)·C + c), in double.
sh::RgbSh incidentByHand(const Transfer& t, std::size_t r, const sh::RgbSh& rotated) {
  const int B2 = t.coeffs(), C = t.channels();
  sh::RgbSh out(t.bands());
  for (int i = 0; i < B2; ++i) {
    Rgbd acc(0.0);
    for (int j = 0; j < B2; ++j)
      for (int c = 0; c < 3; ++c)
        acc[c] += double(t.row(r)[(i * B2 + j) * C + (C == 1 ? 0 : c)]) * double(rotated.c[j][c]);
    out.c[i] = Rgb(acc);
  }
  return out;
}

double relativeDifference(const Rgb& a, const Rgb& b, double scale) {
  return double(length(a - b)) / scale;
}

TEST(EncodedDiffuse, MatchesAnIndependentEvaluationForEveryEncoding) {
  const std::size_t rows = 40;
  for (const int channels : {1, 3}) {
    const Transfer t = testdata::randomField(TransferLayout::Matrix, 3, channels, rows, 7);
    const sh::RgbSh light = testdata::randomLight(3, 11);
    const std::vector<Vec3f> normals = randomNormals(rows, 13);
    const std::vector<Rgb> albedo = randomAlbedo(rows, 17);
    const relight::Surface surface{{}, normals, albedo};
    const Mat3d rotation = rotationAxisAngle(normalize(Vec3d(1, 2, 3)), 0.7);
    const sh::RgbSh rotated = sh::Rotation(3, rotation).apply(light);
    for (const IrradianceEncoding e : sh::kIrradianceEncodings) {
      SCOPED_TRACE(sh::toString(e));
      const std::vector<Rgb> got =
          relight::encodedDiffuse(t, light, e, Material{}, surface, rotation);
      ASSERT_EQ(got.size(), rows);
      double worst = 0, peak = 0;
      for (std::size_t r = 0; r < rows; ++r) {
        const sh::EncodedIrradiance enc = sh::encodeIrradiance(incidentByHand(t, r, rotated), e);
        const Rgbd irradiance = sh::evaluate(enc, Vec3d(normals[r]));
        const Rgb want = albedo[r] * Rgb(irradiance / kPi);
        peak = std::max(peak, double(length(want)));
        worst = std::max(worst, double(length(got[r] - want)));
      }
      EXPECT_GT(peak, 0.0);
      EXPECT_LT(worst / peak, 2e-5);
    }
  }
}

// l2 is the irradiance of bands 0..2 exactly: at 3 bands the encoded shading is relight()'s own
// diffuse (Lambert) term of the matrices, kd (A_l/π) Y(n)·L'_p; l1 leaves band 2 out and differs.
TEST(EncodedDiffuse, L2AtThreeBandsIsTheDiffuseRelighting) {
  const std::size_t rows = 64;
  const Transfer t = testdata::randomField(TransferLayout::Matrix, 3, 3, rows, 21);
  const sh::RgbSh light = testdata::randomLight(3, 22);
  const std::vector<Vec3f> normals = randomNormals(rows, 23);
  const std::vector<Vec3f> positions(rows, Vec3f(0.0f));
  const std::vector<Rgb> albedo = randomAlbedo(rows, 24);
  const relight::Surface surface{positions, normals, albedo};
  const Mat3d rotation = rotationAxisAngle({0, 1, 0}, 1.1);
  const std::vector<Rgb> prt =
      relight::relight(t, light, Material{}, surface, Vec3f(0, 0, 5), rotation);
  const std::vector<Rgb> l2 =
      relight::encodedDiffuse(t, light, IrradianceEncoding::L2, Material{}, surface, rotation);
  const std::vector<Rgb> l1 =
      relight::encodedDiffuse(t, light, IrradianceEncoding::L1, Material{}, surface, rotation);
  double peak = 0, l2Worst = 0, l1Worst = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    peak = std::max(peak, double(length(prt[r])));
    l2Worst = std::max(l2Worst, double(length(l2[r] - prt[r])));
    l1Worst = std::max(l1Worst, double(length(l1[r] - prt[r])));
  }
  EXPECT_LT(l2Worst / peak, 1e-5);
  EXPECT_GT(l1Worst / peak, 1e-2);

  // A material's kd replaces the albedo, as relight() has it.
  Material grey;
  grey.diffuse = Rgb(0.5f);
  const std::vector<Rgb> g =
      relight::encodedDiffuse(t, light, IrradianceEncoding::L2, grey, surface, rotation);
  const std::vector<Rgb> gPrt = relight::relight(t, light, grey, surface, Vec3f(0, 0, 5), rotation);
  for (std::size_t r = 0; r < rows; ++r)
    EXPECT_LT(relativeDifference(g[r], gPrt[r], peak), 1e-5) << r;
}

// The light arriving unoccluded (M_p = I, L'_p = L) is a sun cut to 3 bands over a dim uniform
// sky: positive mean, but its l1 irradiance E₀ + d·n is negative facing away from the sun. The
// windowed, Geomerics and deringed forms are non-negative at every normal whose light has a
// non-negative mean (their guarantee: sh/irradiance_encoding.hpp); where the mean itself is
// negative no encoding that keeps it can be (prt render --encoding shows such rows black).
TEST(EncodedDiffuse, NonNegativeFormsStayNonNegativeWhereL1Rings) {
  const std::size_t rows = 2000;
  std::vector<float> identity(rows * 81, 0.0f);
  for (std::size_t r = 0; r < rows; ++r)
    for (int i = 0; i < 9; ++i) identity[r * 81 + i * 9 + i] = 1.0f;
  const Transfer t = testdata::denseTransfer(TransferLayout::Matrix, 3, 1, identity);
  sh::RgbSh light(3);
  double y[9];
  sh::eval(3, normalize(Vec3d(0.3, 1, 0.2)), y);
  for (int i = 0; i < 9; ++i) light.c[i] = Rgb(float(y[i]) * Rgb(1.0f, 0.9f, 0.8f));
  light.c[0] += Rgb(0.05f * float(std::sqrt(4 * kPi)));  // a uniform sky of radiance 0.05
  const std::vector<Vec3f> normals = randomNormals(rows, 31);
  const relight::Surface surface{{}, normals, {}};
  ASSERT_GT(light.c[0].z, 0.0f);  // the mean is positive in every channel
  auto negatives = [&](IrradianceEncoding e) {
    const std::vector<Rgb> f = relight::encodedDiffuse(t, light, e, Material{}, surface);
    int n = 0;
    for (const Rgb& v : f) n += v.x < 0 || v.y < 0 || v.z < 0;
    return n;
  };
  EXPECT_GT(negatives(IrradianceEncoding::L1), int(rows / 20));
  EXPECT_EQ(negatives(IrradianceEncoding::L1Windowed), 0);
  EXPECT_EQ(negatives(IrradianceEncoding::L1Geomerics), 0);
  EXPECT_EQ(negatives(IrradianceEncoding::L2Deringed), 0);
}

TEST(EncodedDiffuse, RefusesVectorsGlossyMaterialsAndMissingNormals) {
  const std::vector<Vec3f> normals(4, Vec3f(0, 0, 1));
  const relight::Surface surface{{}, normals, {}};
  const sh::RgbSh light = testdata::randomLight(3, 1);
  const Transfer vectors = testdata::randomField(TransferLayout::Vector, 3, 3, 4, 2);
  EXPECT_THROW(relight::encodedDiffuse(vectors, light, IrradianceEncoding::L1, Material{}, surface),
               Error);
  const Transfer matrices = testdata::randomField(TransferLayout::Matrix, 3, 1, 4, 3);
  const Material phong = parseMaterial("phong?exponent=16&ks=0.3");
  EXPECT_THROW(relight::encodedDiffuse(matrices, light, IrradianceEncoding::L1, phong, surface),
               Error);
  const std::vector<Vec3f> three(3, Vec3f(0, 0, 1));
  EXPECT_THROW(relight::encodedDiffuse(matrices, light, IrradianceEncoding::L1, Material{},
                                       relight::Surface{{}, three, {}}),
               Error);
}

}  // namespace
}  // namespace prt
