// Per-texel Haar transfer (transport/bake_haar.cpp over the lightmap domain) against answers it
// cannot fake:
//   * a texel's row is the per-vertex kernel's at the texel's sample point: the plane under a
//     ball baked per texel relights, under the constant sky, as the same plane tessellated with
//     a vertex at every texel centre, baked per vertex at the same seed;
//   * under the constant sky every texel relights to its cosine-weighted visible fraction,
//     which the SH bake per texel estimates independently as √(4π) T₀;
//   * the gutter copies whole rows (transfer/row_dilation.hpp): every row is a valid Haar row,
//     and each dilated one is a neighbour's, relit at that neighbour's normal
//     (render::texelRelight) — a mean of sparse (index, value) pairs would be neither;
//   * the same rows for any thread count and any texel range.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/texel_planes.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/load.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/transfer/haar_rows.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"
#include "prt/transport/passes.hpp"
#include "prt/unwrap/unwrap.hpp"

namespace prt {
namespace {

using testing::coarsePlane;
using testing::texelCentrePlane;

BakeSettings haarSettings(int resolution, int terms, int raysPerTexel) {
  BakeSettings s;
  s.mode = TransferMode::Shadowed;
  s.basis = TransferBasis::Haar;
  s.haar = {resolution, terms};
  s.samples = raysPerTexel;
  s.seed = 77;
  return s;
}

/// The builtin scene with the lightmap UVs prt bake --domain texels gives it (prt unwrap's atlas
/// for an N² lightmap).
Mesh unwrapped(const std::string& name, int n) {
  UnwrapSettings us;
  us.resolution = n;
  us.padding = 2;
  return unwrap(loadMesh(name), us).mesh;
}

haar::HaarLight whiteLight(int resolution) {
  const envmap::Environment white =
      envmap::Environment::analytic([](const Vec3f&) { return Rgb(1.0f); }, {});
  return haar::projectLight(white, resolution, haar::coefficientCount(resolution));
}

TEST(BakeHaarTexels, ATexelIsTheVertexKernelAtItsSamplePoint) {
  constexpr int N = 16;
  const Mesh coarse = coarsePlane(true);
  const Mesh fine = texelCentrePlane(coarse, N);
  const auto occCoarse = makeEmbreeOccluder(coarse), occFine = makeEmbreeOccluder(fine);
  const BakeSettings s = haarSettings(16, 128, 2);
  const TexelBake texels = bakeTexels(coarse, *occCoarse, s, coarse.lightmapUvs, N, N, 2);
  ASSERT_TRUE(texels.transfer.isHaar());
  ASSERT_EQ(texels.transfer.domain(), TransferDomain::Texels);
  ASSERT_EQ(texels.transfer.rowCount(), std::size_t(N * N));
  EXPECT_NO_THROW(texels.transfer.check("texels"));
  // Texel j·N + i and vertex j·N + i share their point (to float rounding of the interpolated
  // point), normal and seed index: the same rays, the same row.
  const Transfer vertices = bake(fine, *occFine, s);
  const haar::HaarLight white = whiteLight(16);
  const std::vector<Vec3f> up(std::size_t(N * N), Vec3f(0, 1, 0));
  const std::vector<Rgb> a = relight::relightHaar(texels.transfer, white, up, {});
  const std::vector<Rgb> b = relight::relightHaar(vertices, white, fine.normals, {});
  int identical = 0, shadowed = 0;
  for (std::size_t r = 0; r < std::size_t(N * N); ++r) {
    EXPECT_NEAR(a[r].x, b[r].x, 1e-3) << "texel " << r;
    identical += std::equal(texels.transfer.row(r), texels.transfer.row(r) + vertices.stride(),
                            vertices.row(r));
    shadowed += a[r].x < 0.8f;
  }
  EXPECT_GT(identical, N * N * 9 / 10);
  EXPECT_GT(shadowed, 5) << "the ball's shadow must fall on the plane";
}

TEST(BakeHaarTexels, EveryTexelSeesTheSkyTheShBakeSees) {
  const Mesh mesh = unwrapped("builtin:sphere-plane?grid=8&subdiv=2", 32);
  ASSERT_EQ(mesh.lightmapUvs.size(), mesh.vertexCount());
  const auto occ = makeEmbreeOccluder(mesh);
  constexpr int N = 32;
  const TexelBake haarT =
      bakeTexels(mesh, *occ, haarSettings(16, 1536, 4), mesh.lightmapUvs, N, N, 2);
  BakeSettings ss;
  ss.mode = TransferMode::Shadowed;
  ss.bands = 1;
  ss.samples = 4096;
  ss.seed = 5;
  const TexelBake shT = bakeTexels(mesh, *occ, ss, mesh.lightmapUvs, N, N, 2);
  const render::TexelRelight points = render::texelRelight(mesh, *occ, haarT.transfer, Material{});
  ASSERT_EQ(points.points.normals.size(), std::size_t(N * N));
  const std::vector<Rgb> relit =
      relight::relightHaar(haarT.transfer, whiteLight(16), points.points.normals, {});
  double sq = 0;
  std::size_t counted = 0;
  for (const TexelSample& t : haarT.samples.samples) {
    const double d = relit[t.texel].x - shT.transfer.row(t.texel)[0] * std::sqrt(4 * kPi);
    sq += d * d;
    ++counted;
  }
  ASSERT_GT(counted, 100u);
  EXPECT_LT(std::sqrt(sq / double(counted)), 0.015);
}

TEST(BakeHaarTexels, TheGutterCopiesANeighboursRowAndItsNormal) {
  const Mesh mesh = unwrapped("builtin:sphere?subdiv=2", 32);
  ASSERT_EQ(mesh.lightmapUvs.size(), mesh.vertexCount());
  const auto occ = makeEmbreeOccluder(mesh);
  constexpr int N = 32;
  const TexelBake b = bakeTexels(mesh, *occ, haarSettings(8, 24, 1), mesh.lightmapUvs, N, N, 2);
  const Transfer& t = b.transfer;
  // Every row, the gutter's included, is a valid Haar row (a mean of two rows' pairs is not:
  // its indices are not integral, or not ascending).
  EXPECT_NO_THROW(t.check("gutter"));
  const render::TexelRelight points = render::texelRelight(mesh, *occ, t, Material{});
  const auto& own = b.samples.sampleOfTexel;
  int gutter = 0;
  for (int y = 0; y < N; ++y)
    for (int x = 0; x < N; ++x) {
      const std::size_t texel = std::size_t(y) * N + std::size_t(x);
      if (own[texel] >= 0 || !b.filled[texel]) continue;
      ++gutter;
      // The first filled neighbour that holds the same row has the same normal: the texel is
      // relit where its transfer came from.
      bool found = false;
      for (int dy = -1; dy <= 1 && !found; ++dy)
        for (int dx = -1; dx <= 1 && !found; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= N || ny >= N) continue;
          const std::size_t o = std::size_t(ny) * N + std::size_t(nx);
          if (!b.filled[o]) continue;
          found = std::equal(t.row(texel), t.row(texel) + t.stride(), t.row(o)) &&
                  points.points.normals[texel] == points.points.normals[o];
        }
      EXPECT_TRUE(found) << "gutter texel " << x << "," << y;
    }
  EXPECT_GT(gutter, 50);
}

TEST(BakeHaarTexels, TheSameForAnyThreadCountAndRange) {
  const Mesh mesh = unwrapped("builtin:sphere-plane?grid=8&subdiv=2", 32);
  const auto occ = makeEmbreeOccluder(mesh);
  BakeSettings shadowed = haarSettings(8, 24, 2);
  shadowed.domain = TransferDomain::Texels;
  shadowed.lightmap = {16, 16, 2};
  // Inter-reflected: the bounce's SH passes over the whole lightmap, then each row reads its own
  // texel of their sum.
  BakeSettings interreflected = shadowed;
  interreflected.mode = TransferMode::Interreflected;
  interreflected.bounces = 2;
  interreflected.haar.bounceBands = 2;
  for (BakeSettings s : {shadowed, interreflected}) {
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
    s.rows = {70, 90};
    const Transfer piece = bake(mesh, *occ, s);
    ASSERT_EQ(piece.rowCount(), 90u);
    for (std::size_t r = 0; r < 90; ++r)
      for (std::size_t k = 0; k < whole.stride(); ++k)
        ASSERT_EQ(piece.row(r)[k], whole.row(70 + r)[k]) << "texel " << 70 + r;
  }
}

TEST(BakeHaarTexels, AnInterreflectedTexelHoldsTheShBakesBounceAtIt) {
  // Each covered texel's bounce is the per-texel SH bake's bounce at that texel (the same
  // passes: bands, 1024 directions per ray a texel, seed), and its pairs the shadowed rows'.
  const Mesh mesh = unwrapped("builtin:sphere-plane?grid=8&subdiv=2", 32);
  const auto occ = makeEmbreeOccluder(mesh);
  BakeSettings s = haarSettings(8, 24, 1);
  s.domain = TransferDomain::Texels;
  s.lightmap = {16, 16, 0};
  const Transfer direct = bake(mesh, *occ, s);
  s.mode = TransferMode::Interreflected;
  s.bounces = 1;
  s.haar.bounceBands = 2;
  TexelBakeInfo info;
  ThreadExecutor threads;
  const Transfer t = bake(mesh, *occ, s, threads, nullptr, {}, &info);
  BakeSettings sh = s;
  sh.basis = TransferBasis::SphericalHarmonics;
  sh.haar = {};
  sh.bands = 2;
  sh.samples = kHaarBounceSamplesPerTexelRay;
  const Transfer full = bake(mesh, *occ, sh);
  sh.mode = TransferMode::Shadowed;
  sh.bounces = 0;
  const Transfer shDirect = bake(mesh, *occ, sh);
  ASSERT_EQ(t.stride(), direct.stride() + 4);
  std::size_t covered = 0;
  double largest = 0;
  for (const TexelSample& q : info.samples.samples) {
    const std::size_t r = q.texel;
    // A texel inside geometry is refilled: Haar copies a neighbour's row, SH takes a mean.
    if (std::binary_search(info.inside.begin(), info.inside.end(), std::uint32_t(r))) continue;
    ++covered;
    for (std::size_t k = 0; k < direct.stride(); ++k) ASSERT_EQ(t.row(r)[k], direct.row(r)[k]);
    for (std::size_t i = 0; i < 4; ++i) {
      const double want = full.row(r)[i] - shDirect.row(r)[i];
      ASSERT_NEAR(t.row(r)[direct.stride() + i], want, 1e-6) << "texel " << r;
      largest = std::max(largest, std::abs(want));
    }
  }
  EXPECT_GT(covered, 50u);
  EXPECT_GT(largest, 0.01);
}

}  // namespace
}  // namespace prt
