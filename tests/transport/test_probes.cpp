// Probe grids (the probe domain, prt/transfer/probe_grid.hpp; issue 32) against answers the bake
// cannot fake:
//   * a probe just above a very large plane, shadowed: M is ∫_{y>0} Y Yᵀ dω, the upper
//     hemisphere's product matrix, computed here by a midpoint rule of its own;
//   * the same with one bounce off the plane (albedo ρ): under the constant sky the probe sees 1
//     above and ρ below, so M's first column is ρ e_0 + (1 − ρ) ∫_{y>0} Y Y_0 dω;
//   * a probe in a closed room (walls facing in) sees nothing of the sky, bounces included;
//   * a probe inside a solid is found and refilled with its neighbours' mean;
//   * any probe range gives the whole bake's rows bit for bit; the same for any thread count;
//   * relighting: the trilinear blend is exact for a linear field, and shading under a uniform
//     sky of radiance 1 gives the albedo.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/error_text.hpp"
#include "prt/core/parallel.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/passes.hpp"

namespace prt {
namespace {

/// A square [-s, s]² at height y facing +Y (or −Y).
void addQuad(Mesh& m, float s, float y, bool up, Rgb albedo) {
  const auto base = std::uint32_t(m.positions.size());
  for (const auto& [x, z] : std::vector<std::pair<float, float>>{{-s, -s}, {s, -s}, {s, s}, {-s, s}}) {
    m.positions.push_back({x, y, z});
    m.normals.push_back({0, up ? 1.0f : -1.0f, 0});
    m.albedo.push_back(albedo);
  }
  if (up)
    m.triangles.insert(m.triangles.end(), {{base, base + 3, base + 2}, {base, base + 2, base + 1}});
  else
    m.triangles.insert(m.triangles.end(), {{base, base + 1, base + 2}, {base, base + 2, base + 3}});
}

/// An axis-aligned box [lo, hi]³, its faces facing in (a room) or out (a solid); 4 vertices a face.
Mesh box(float lo, float hi, bool inward, Rgb albedo) {
  Mesh m;
  m.source = inward ? "room" : "solid";
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const float c = side ? hi : lo;
      // Outward normal of this face: +axis on the high side.
      Vec3f n(0.0f);
      n[axis] = side ? 1.0f : -1.0f;
      if (inward) n = -n;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto base = std::uint32_t(m.positions.size());
      for (const auto& [a, b] :
           std::vector<std::pair<float, float>>{{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}}) {
        Vec3f p(0.0f);
        p[axis] = c, p[u] = a, p[v] = b;
        m.positions.push_back(p);
        m.normals.push_back(n);
        m.albedo.push_back(albedo);
      }
      // Counter-clockwise about n (u × v = +axis).
      const bool ccwAboutAxis = dot(n, Vec3f(axis == 0, axis == 1, axis == 2)) > 0;
      if (ccwAboutAxis)
        m.triangles.insert(m.triangles.end(),
                           {{base, base + 1, base + 2}, {base, base + 2, base + 3}});
      else
        m.triangles.insert(m.triangles.end(),
                           {{base, base + 2, base + 1}, {base, base + 3, base + 2}});
    }
  return m;
}

BakeSettings probeSettings(TransferMode mode, int bands, int samples, ProbeGrid grid) {
  BakeSettings s;
  s.mode = mode;
  s.layout = TransferLayout::Matrix;
  s.domain = TransferDomain::Probes;
  s.probes = grid;
  s.bands = bands;
  s.samples = samples;
  s.bounces = mode == TransferMode::Interreflected ? 1 : 0;
  s.seed = 11;
  return s;
}

ProbeGrid singleProbe(Vec3f at) {
  ProbeGrid g;
  g.origin = at;
  g.spacing = Vec3f(1.0f);
  g.count = {1, 1, 1};
  return g;
}

/// ∫_{y>0} Y_i Y_j dω by a midpoint rule in (θ, φ) about +Y, independent of the bake's quadrature.
std::vector<double> upperHemisphereProduct(int bands) {
  const int nc = bands * bands, nt = 400, np = 800;
  std::vector<double> h(std::size_t(nc) * nc, 0.0), y(nc);
  for (int a = 0; a < nt; ++a) {
    const double th = (a + 0.5) * (kPi / 2) / nt;
    for (int b = 0; b < np; ++b) {
      const double ph = (b + 0.5) * 2 * kPi / np;
      sh::eval(bands, Vec3d(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)),
               y.data());
      const double w = std::sin(th) * (kPi / 2 / nt) * (2 * kPi / np);
      for (int i = 0; i < nc; ++i)
        for (int j = 0; j < nc; ++j) h[std::size_t(i) * nc + j] += w * y[i] * y[j];
    }
  }
  return h;
}

TEST(Probes, AboveALargePlaneTheShadowedMatrixIsTheUpperHemisphere) {
  Mesh plane;
  plane.source = "plane";
  addQuad(plane, 2000.0f, 0.0f, true, Rgb(0.5f));
  const auto occ = makeEmbreeOccluder(plane);
  const int B = 3, nc = B * B;
  BakeStats stats;
  ThreadExecutor threads;
  // 65,536 directions: the randomly turned Sobol' set's worst element over 20 seeds was
  // 0.6e-3 on average, 1.1e-3 at most (its error falls as ~N^-0.6 here; a plane through the
  // probe's axes is no easier for it than any other).
  const Transfer t = bake(plane, *occ,
                          probeSettings(TransferMode::Shadowed, B, 65536, singleProbe({0, 1, 0})),
                          threads, &stats);
  ASSERT_EQ(t.domain(), TransferDomain::Probes);
  ASSERT_EQ(t.rowCount(), 1u);
  const std::vector<double> h = upperHemisphereProduct(B);
  EXPECT_NEAR(h[0], 0.5, 1e-4);  // the rule itself: half the sphere
  double worst = 0;
  for (int i = 0; i < nc * nc; ++i) worst = std::max(worst, std::abs(double(t.row(0)[i]) - h[i]));
  EXPECT_LT(worst, 2e-3) << "M_00 " << t.row(0)[0];
  EXPECT_EQ(stats.rays, 65536u);
}

TEST(Probes, OneBounceOffTheLargePlaneSendsItsAlbedoFromBelow) {
  Mesh plane;
  plane.source = "plane";
  const float rho = 0.6f;
  addQuad(plane, 2000.0f, 0.0f, true, Rgb(rho));
  const auto occ = makeEmbreeOccluder(plane);
  const int B = 3, nc = B * B;
  ThreadExecutor threads;
  const Transfer t = bake(plane, *occ,
                          probeSettings(TransferMode::Interreflected, B, 4096, singleProbe({0, 1, 0})),
                          threads);
  const std::vector<double> h = upperHemisphereProduct(B);
  // Column 0: M_i0 = ρ δ_i0 + (1 − ρ) H_i0 (the probe sees 1 above, ρ below, under L = √4π e_0).
  for (int i = 0; i < nc; ++i) {
    const double want = (i == 0 ? rho : 0.0) + (1 - rho) * h[std::size_t(i) * nc];
    EXPECT_NEAR(t.row(0)[std::size_t(i) * nc], want, 1e-3) << "i " << i << " got " << t.row(0)[std::size_t(i) * nc];
  }
}

TEST(Probes, InAClosedRoomNothingArrivesBouncesIncluded) {
  const Mesh room = box(-1, 1, true, Rgb(0.8f));
  const auto occ = makeEmbreeOccluder(room);
  ThreadExecutor threads;
  ProbeGrid g;
  g.origin = Vec3f(-0.5f);
  g.spacing = Vec3f(0.5f);
  g.count = {3, 3, 3};
  const Transfer t = bake(room, *occ, probeSettings(TransferMode::Interreflected, 3, 1024, g),
                          threads);
  for (std::size_t p = 0; p < t.rowCount(); ++p)
    for (std::size_t i = 0; i < t.stride(); ++i)
      ASSERT_NEAR(t.row(p)[i], 0.0f, 2e-2) << "probe " << p << " entry " << i;
  // Not one probe is taken for one inside geometry: the walls face it.
  ThreadExecutor again;
  BakeStats st;
  (void)bake(room, *occ, probeSettings(TransferMode::Shadowed, 2, 64, g), again, &st);
  EXPECT_EQ(st.vertices, 27u);
}

TEST(Probes, AProbeInsideASolidIsRefilledFromItsNeighbours) {
  // A solid cube around the middle probe of a row of five; the others see open sky around it.
  const Mesh solid = box(-0.25f, 0.25f, false, Rgb(0.5f));
  const auto occ = makeEmbreeOccluder(solid);
  ProbeGrid g;
  g.origin = Vec3f(-2.0f, 0.0f, 0.0f);
  g.spacing = Vec3f(1.0f);
  g.count = {5, 1, 1};
  ThreadExecutor threads;
  const Transfer t = bake(solid, *occ, probeSettings(TransferMode::Shadowed, 3, 512, g), threads);
  for (std::size_t i = 0; i < t.stride(); ++i)
    EXPECT_FLOAT_EQ(t.row(2)[i], 0.5f * (t.row(1)[i] + t.row(3)[i])) << i;
  // Baked as it is, it would be black: nothing of the sky reaches inside a solid.
  EXPECT_GT(t.row(2)[0], 0.5f);
}

TEST(Probes, AnyRangeAndAnyThreadCountGiveTheWholeBakesRows) {
  Mesh scene = box(-0.3f, 0.3f, false, Rgb(0.5f, 0.4f, 0.3f));
  addQuad(scene, 3.0f, -0.3f, true, Rgb(0.7f, 0.7f, 0.2f));
  const auto occ = makeEmbreeOccluder(scene);
  ProbeGrid g;
  g.origin = Vec3f(-1.0f, -0.2f, -1.0f);
  g.spacing = Vec3f(0.5f, 0.4f, 0.5f);
  g.count = {5, 3, 5};
  BakeSettings s = probeSettings(TransferMode::Interreflected, 3, 128, g);
  ThreadExecutor threads;
  const Transfer whole = bake(scene, *occ, s, threads);
  ASSERT_EQ(whole.channels(), 3);  // the coloured bounce
  for (const RowRange r : {RowRange{0, 10}, RowRange{31, 17}, RowRange{60, 15}}) {
    s.rows = r;
    const Transfer piece = bake(scene, *occ, s, threads);
    ASSERT_EQ(piece.rows(), r);
    for (std::size_t p = 0; p < r.count; ++p)
      for (std::size_t i = 0; i < whole.stride(); ++i)
        ASSERT_EQ(piece.row(p)[i], whole.row(r.first + p)[i]) << "probe " << r.first + p;
  }
  s.rows = {};
  Transfer one;
  {
    ThreadLimit single(1);
    one = bake(scene, *occ, s, threads);
  }
  for (std::size_t k = 0; k < whole.values().size(); ++k)
    ASSERT_EQ(one.values()[k], whole.values()[k]);
}

TEST(Probes, BadGridsAndLayoutsAreRefusedByName) {
  Mesh plane;
  plane.source = "plane";
  addQuad(plane, 1.0f, 0.0f, true, Rgb(0.5f));
  const auto occ = makeEmbreeOccluder(plane);
  ThreadExecutor threads;
  ProbeGrid g = singleProbe({0, 1, 0});
  BakeSettings s = probeSettings(TransferMode::Shadowed, 3, 64, g);
  s.layout = TransferLayout::Vector;
  EXPECT_NE(testing::errorOf([&] { bake(plane, *occ, s, threads); }).find("matrices"),
            std::string::npos);
  s = probeSettings(TransferMode::Shadowed, 3, 64, g);
  s.probes.spacing.y = 0.0f;
  EXPECT_NE(testing::errorOf([&] { bake(plane, *occ, s, threads); }).find("spacing"),
            std::string::npos);
  s.probes = g;
  s.rows = {1, 1};
  EXPECT_NE(testing::errorOf([&] { bake(plane, *occ, s, threads); }).find("probe range"),
            std::string::npos);
  EXPECT_NE(testing::errorOf([] { makeProbeGrid({0, 0, 0}, {1, -1, 1}, {0, 0, 0}, "x"); })
                .find("not a box"),
            std::string::npos);
}

TEST(ProbeGrid, AnAutomaticGridPutsSixteenCellsOnTheLongestSideAndProbesAtTheirCentres) {
  const ProbeGrid g = makeProbeGrid({0, 0, 0}, {4, 1, 2}, {0, 0, 0}, "box");
  EXPECT_EQ(g.count, (std::array<int, 3>{16, 4, 8}));
  EXPECT_FLOAT_EQ(g.spacing.x, 0.25f);
  EXPECT_FLOAT_EQ(g.origin.x, 0.125f);
  EXPECT_FLOAT_EQ(g.position(g.probes() - 1).z, 2.0f - 0.125f);
  const ProbeGrid flat = makeProbeGrid({0, 0, 0}, {2, 0, 2}, {0, 0, 0}, "flat");
  EXPECT_EQ(flat.count[1], 1);
  EXPECT_GT(flat.spacing.y, 0.0f);
  EXPECT_EQ(g.row(3, 2, 1), 3u + 16u * (2u + 4u * 1u));
  EXPECT_EQ(g.cell(g.row(3, 2, 1)), (std::array<int, 3>{3, 2, 1}));
}

TEST(RelightProbes, TrilinearBlendIsExactForALinearFieldAndShadingAUniformSkyGivesTheAlbedo) {
  relight::ProbeLighting l;
  l.grid.origin = Vec3f(1.0f, -1.0f, 0.0f);
  l.grid.spacing = Vec3f(0.5f, 1.0f, 2.0f);
  l.grid.count = {4, 3, 2};
  l.bands = 2;
  const auto field = [](const Vec3f& p, int i) { return 0.3f + 0.1f * i + p.x - 2 * p.y + 0.5f * p.z; };
  for (std::size_t r = 0; r < l.grid.probes(); ++r)
    for (int i = 0; i < 4; ++i) l.coefficients.push_back(Rgb(field(l.grid.position(r), i)));
  const Vec3f at(1.8f, 0.3f, 1.1f);
  Rgb out[4];
  relight::sampleProbes(l, at, out);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(out[i].x, field(at, i), 1e-5f);
  // Outside the grid: clamped to its face.
  relight::sampleProbes(l, Vec3f(-5.0f, 0.3f, 1.1f), out);
  EXPECT_NEAR(out[0].x, field(Vec3f(1.0f, 0.3f, 1.1f), 0), 1e-5f);

  std::vector<Rgb> sky(9, Rgb(0.0f));
  sky[0] = Rgb(float(std::sqrt(4 * kPi)));  // radiance 1 from every direction
  const Rgb e = relight::shadeDiffuse(sky.data(), 3, normalize(Vec3f(0.3f, -0.8f, 0.2f)),
                                      Rgb(0.2f, 0.5f, 0.9f));
  EXPECT_NEAR(e.x, 0.2f, 1e-5f);
  EXPECT_NEAR(e.z, 0.9f, 1e-5f);
}

TEST(RelightProbes, TheLightArrivingAtAnOpenProbeIsTheLightItself) {
  Mesh far;
  far.source = "far";
  addQuad(far, 0.01f, -100.0f, true, Rgb(0.5f));  // all but no solid angle
  const auto occ = makeEmbreeOccluder(far);
  ThreadExecutor threads;
  ProbeGrid g = singleProbe({0, 0, 0});
  const Transfer t = bake(far, *occ, probeSettings(TransferMode::Shadowed, 3, 256, g), threads);
  sh::RgbSh light(3);
  for (int i = 0; i < 9; ++i) light.c[i] = Rgb(0.1f * i, 1.0f - 0.1f * i, 0.5f);
  const relight::ProbeLighting lit = relight::relightProbes(t, light);
  ASSERT_EQ(lit.bands, 3);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(lit.probe(0)[i].y, light.c[i].y, 1e-5f) << i;
}

}  // namespace
}  // namespace prt
