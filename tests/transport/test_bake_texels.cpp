// Per-texel transfer (transport/bake_texels.hpp, issue 18) against answers it cannot fake:
//   * a plane under unshadowed transfer gives the analytic clamped-cosine projection in every
//     texel, gutter included after dilation;
//   * shadowed transfer of a two-triangle plane at its texels equals the per-vertex bake of the
//     same geometry tessellated with a vertex at every texel centre: exactly at the same seed
//     (the same kernel), within Monte Carlo error at another, and the shadow is there;
//   * inter-reflected transfer of the Cornell box (its packed lightmap UVs) agrees with the
//     per-vertex bake on each wall's mean, and never gains more than the albedo per bounce;
//   * the same values for any thread count and for any texel range (a range's rows are the
//     whole bake's, bit for bit: split bakes merge exactly); bad requests refused by name.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/error_text.hpp"
#include "common/texel_planes.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/lightmap_uvs.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"
#include "prt/transport/texel_validity.hpp"
#include "prt/unwrap/unwrap.hpp"

namespace prt {
namespace {

BakeSettings settings(TransferMode mode, int bands, int samples) {
  BakeSettings s;
  s.mode = mode;
  s.bands = bands;
  s.samples = samples;
  s.seed = 77;
  return s;
}

using testing::coarsePlane;
using testing::texelCentrePlane;

TEST(BakeTexels, PlaneUnshadowedIsTheClampedCosineInEveryTexel) {
  const Mesh m = coarsePlane(false);
  const auto occ = makeEmbreeOccluder(m);
  constexpr int N = 32, P = 2;
  BakeStats stats;
  const TexelBake b = bakeTexels(m, *occ, settings(TransferMode::Unshadowed, 3, 64), m.lightmapUvs,
                                 N, N, P, &stats);
  const Transfer& t = b.transfer;
  EXPECT_EQ(t.domain(), TransferDomain::Texels);
  EXPECT_EQ(t.shape().lightmap.width, N);
  ASSERT_EQ(t.rowCount(), std::size_t(N * N));
  EXPECT_EQ(b.samples.samples.size(), std::size_t(N * N));  // the plane fills the lightmap
  EXPECT_EQ(stats.vertices, std::size_t(N * N));
  // U_lm(n) = (A_l/π) Y_lm(n), n = +Y.
  double y[9];
  sh::eval(3, Vec3d{0, 1, 0}, y);
  const std::vector<double> a = sh::clampedCosineKernel(3);
  for (std::size_t r = 0; r < t.rowCount(); ++r)
    for (int i = 0; i < 9; ++i) {
      const int l = i == 0 ? 0 : i < 4 ? 1 : 2;
      ASSERT_NEAR(t.row(r)[i], a[l] / kPi * y[i], 1e-6) << "texel " << r << " coefficient " << i;
    }
}

TEST(BakeTexels, ShadowedTexelsEqualVerticesAtTheirSamplePoints) {
  constexpr int N = 24;
  const Mesh coarse = coarsePlane(true);
  // The same geometry with a vertex at every texel centre of the plane.
  const Mesh fine = texelCentrePlane(coarse, N);

  BakeSettings s = settings(TransferMode::Shadowed, 3, 1024);
  const auto occCoarse = makeEmbreeOccluder(coarse), occFine = makeEmbreeOccluder(fine);
  BakeStats st, sv;
  const TexelBake texels = bakeTexels(coarse, *occCoarse, s, coarse.lightmapUvs, N, N, 2, &st);
  // Texel j·N + i and vertex j·N + i share their point, normal and seed index: the same
  // kernel gives the same row, to float rounding of the interpolated point.
  const Transfer same = bake(fine, *occFine, s);
  for (int r = 0; r < N * N; ++r)
    for (int i = 0; i < 9; ++i) ASSERT_NEAR(texels.transfer.row(r)[i], same.row(r)[i], 1e-5f) << r;
  // Another seed: independent estimates of the same integrals, within their error.
  s.seed = 78;
  const Transfer vertices = bake(fine, *occFine, s, &sv);
  const double bound = 5 * std::hypot(st.stdErrT0Max, sv.stdErrT0Max) + 2e-3;
  const double open = 0.886227 * 0.282095 * 2;  // T₀ of an unshadowed upward plane: (A₀/π) Y₀₀
  int shadowed = 0;
  double worst = 0;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      const float tt = texels.transfer.row(std::size_t(j) * N + i)[0];
      const float tv = vertices.row(std::size_t(j) * N + i)[0];
      worst = std::max(worst, double(std::abs(tt - tv)));
      EXPECT_NEAR(tt, tv, bound) << "texel " << i << "," << j;
      shadowed += tt < 0.8 * open;
    }
  EXPECT_GT(shadowed, 10) << "the ball's shadow must fall on the plane";
  EXPECT_GT(worst, 0.0) << "independent seeds cannot agree exactly";
  std::cout << "per-texel vs per-vertex shadowed T0 (other seed): worst |diff| " << worst
            << " (bound " << bound << ")\n";
}

TEST(BakeTexels, InterreflectedCornellAgreesWithTheVertexBakeWallByWall) {
  // Per texel on a coarse box (4 × 4 quads a wall), per vertex on a fine one (64 × 64): the same
  // surfaces, each wall's mean over its area where it is not inside geometry (the floor under
  // the blocks: the texels there are refilled from their neighbours, the vertices stay dark).
  const Mesh box = builtinScene("builtin:cornell?grid=4");
  const Mesh fine = builtinScene("builtin:cornell?grid=64");
  const auto occ = makeEmbreeOccluder(box), fineOcc = makeEmbreeOccluder(fine);
  BakeSettings s = settings(TransferMode::Interreflected, 2, 256);
  std::vector<TexelBake> texels;
  for (int k = 0; k <= 2; ++k) {
    s.bounces = k;
    texels.push_back(bakeTexels(box, *occ, s, box.lightmapUvs, 128, 128, 2));
  }
  const Transfer vertices = bake(fine, *fineOcc, s);
  const TexelBake& t = texels.back();
  ASSERT_EQ(t.transfer.channels(), 3);  // the red and green walls colour the bounces
  ASSERT_EQ(box.parts.size(), fine.parts.size());
  std::vector<std::uint8_t> invalidTexel(t.samples.texelCount(), 0);
  for (const std::uint32_t x : t.invalid) invalidTexel[x] = 1;
  EXPECT_GT(t.invalid.size(), 100u) << "the floor under the blocks";
  const std::vector<std::uint8_t> insideVertex =
      insideGeometry(fine, *fineOcc, fine.positions, fine.normals);
  double worst = 0;
  for (std::size_t pi = 0; pi < box.parts.size(); ++pi) {
    const MeshPart& part = box.parts[pi];
    const MeshPart& finePart = fine.parts[pi];
    SCOPED_TRACE(part.name);
    double sumT = 0, sumV = 0;
    std::size_t nT = 0;
    for (const TexelSample& ts : t.samples.samples)
      if (ts.triangle >= part.firstTriangle &&
          ts.triangle < part.firstTriangle + part.triangleCount && !invalidTexel[ts.texel]) {
        for (int c = 0; c < 3; ++c) sumT += t.transfer.row(ts.texel)[c];
        ++nT;
      }
    // The vertex field's mean over the area (texels sample the area uniformly): each vertex
    // weighted by a third of its triangles' area.
    double area = 0;
    for (std::uint32_t f = finePart.firstTriangle;
         f < finePart.firstTriangle + finePart.triangleCount; ++f) {
      const auto& tri = fine.triangles[f];
      if (insideVertex[tri[0]] || insideVertex[tri[1]] || insideVertex[tri[2]]) continue;
      const double a = 0.5 * length(Vec3d(cross(fine.positions[tri[1]] - fine.positions[tri[0]],
                                                fine.positions[tri[2]] - fine.positions[tri[0]])));
      for (std::uint32_t v : tri)
        for (int c = 0; c < 3; ++c) sumV += a / 3 * vertices.row(v)[c];
      area += a;
    }
    ASSERT_GT(nT, 100u);
    const double meanT = sumT / nT, meanV = sumV / area;
    // (measured 3.1% at worst; reading the previous pass with v flipped gives 11%)
    EXPECT_NEAR(meanT, meanV, 0.04 * std::abs(meanV)) << nT << " texels";
    worst = std::max(worst, std::abs(meanT / meanV - 1));
  }
  std::cout << "per-texel (coarse box) vs per-vertex (fine box), inter-reflected wall means: worst "
            << 100 * worst << "%\n";
  // Each bounce adds at most albedo (≤ 0.73) times the largest value of the one before.
  for (int k = 1; k <= 2; ++k) {
    double prevMax = 0, gain = 0;
    for (const TexelSample& ts : t.samples.samples) {
      const double before = texels[k - 1].transfer.row(ts.texel)[0];
      prevMax =
          std::max(prevMax, k == 1 ? before : before - texels[k - 2].transfer.row(ts.texel)[0]);
      gain = std::max(gain, double(texels[k].transfer.row(ts.texel)[0]) - before);
    }
    EXPECT_LE(gain, 0.731 * prevMax + 1e-6) << "bounce " << k;
    EXPECT_GT(gain, 0.0) << "bounce " << k;
  }
}

TEST(BakeTexels, TheSameForAnyThreadCountAndBadRequestsRefused) {
  const Mesh box = builtinScene("builtin:cornell?grid=6");
  const auto occ = makeEmbreeOccluder(box);
  BakeSettings s = settings(TransferMode::Interreflected, 2, 64);
  s.bounces = 1;
  const TexelBake many = bakeTexels(box, *occ, s, box.lightmapUvs, 48, 48, 2);
  TexelBake one;
  {
    const ThreadLimit limit(1);
    one = bakeTexels(box, *occ, s, box.lightmapUvs, 48, 48, 2);
  }
  ASSERT_EQ(one.transfer.values().size(), many.transfer.values().size());
  for (std::size_t i = 0; i < one.transfer.values().size(); ++i)
    ASSERT_EQ(one.transfer.values()[i], many.transfer.values()[i]) << i;
  // Without padding the gutter stays empty; with it, it fills.
  const TexelBake bare = bakeTexels(box, *occ, s, box.lightmapUvs, 48, 48, 0);
  std::size_t filledBare = 0, filledPadded = 0;
  for (std::size_t t = 0; t < bare.filled.size(); ++t) {
    filledBare += bare.filled[t];
    filledPadded += many.filled[t];
    if (!bare.filled[t]) {
      ASSERT_EQ(bare.transfer.row(t)[0], 0.0f);
    }
  }
  EXPECT_EQ(filledBare, bare.samples.samples.size());
  EXPECT_GT(filledPadded, filledBare);
  using testing::errorOf;
  BakeSettings r = s;
  r.rows = {2000, 400};  // past the 48² = 2304 texels
  EXPECT_NE(errorOf([&] {
              bakeTexels(box, *occ, r, box.lightmapUvs, 48, 48, 2);
            }).find("texel range [2000, 2400) is outside the 48 x 48 lightmap"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              bakeTexels(box, *occ, s, box.lightmapUvs, 48, 48, 65);
            }).find("padding must be 0..64"),
            std::string::npos);
  const Mesh ball = builtinScene("builtin:sphere?subdiv=1");
  const auto ballOcc = makeEmbreeOccluder(ball);
  EXPECT_NE(errorOf([&] {
              bakeTexels(ball, *ballOcc, s, ball.lightmapUvs, 48, 48, 2);
            }).find("coordinates for"),
            std::string::npos);
}

// A range of texel rows equals the same rows of the whole bake exactly, for a one-pass mode
// (which samples only the texels the range and its dilation need: the shadowed ranges cost
// less) and for bounces (which read the whole previous pass); ranges that split a row of texels
// and padding that reaches across the cut included.
TEST(BakeTexels, ARangeOfTexelsIsTheWholeBakesRowsExactly) {
  const Mesh box = builtinScene("builtin:cornell?grid=6");
  const auto occ = makeEmbreeOccluder(box);
  for (const TransferMode mode : {TransferMode::Shadowed, TransferMode::Interreflected}) {
    BakeSettings s = settings(mode, 2, 32);
    s.bounces = mode == TransferMode::Interreflected ? 1 : 0;
    const int W = 40, H = 40, padding = 3;
    BakeStats wholeStats;
    const TexelBake whole = bakeTexels(box, *occ, s, box.lightmapUvs, W, H, padding, &wholeStats);
    const std::size_t stride = whole.transfer.stride();
    std::size_t covered = 0;
    for (const RowRange range : {RowRange{0, 613}, RowRange{613, 700}, RowRange{1313, 0}}) {
      SCOPED_TRACE(std::string(toString(mode)) + " from " + std::to_string(range.first));
      BakeSettings r = s;
      r.rows = range;
      BakeStats st;
      const TexelBake part = bakeTexels(box, *occ, r, box.lightmapUvs, W, H, padding, &st);
      const RowRange got = part.transfer.rows();
      EXPECT_EQ(got.first, range.first);
      EXPECT_EQ(got.end(), range.count ? range.end() : std::size_t(W * H));
      ASSERT_EQ(part.transfer.values().size(), got.count * stride);
      for (std::size_t i = 0; i < got.count * stride; ++i)
        ASSERT_EQ(part.transfer.values()[i], whole.transfer.values()[got.first * stride + i])
            << "value " << i;
      covered += st.vertices;
      if (mode == TransferMode::Shadowed) {
        EXPECT_LT(st.rays, wholeStats.rays);
      }
    }
    EXPECT_EQ(covered, wholeStats.vertices) << "each covered texel counted in one range";
  }
}

/// A closed unit cube standing on the coarse plane at its centre (outward counter-clockwise
/// faces, no lightmap area of its own).
Mesh planeWithCube() {
  Mesh m = coarsePlane(false);
  const std::uint32_t base = std::uint32_t(m.positions.size());
  for (int v = 0; v < 8; ++v) {
    const Vec3f p(float(v >> 2) - 0.5f, float((v >> 1) & 1), float(v & 1) - 0.5f);
    m.positions.push_back(p);
    m.normals.push_back(normalize(p - Vec3f(0, 0.5f, 0)));
    m.lightmapUvs.push_back({0, 0});
  }
  for (const auto& t : std::vector<std::array<std::uint32_t, 3>>{{0, 1, 3},
                                                                 {0, 3, 2},
                                                                 {4, 6, 7},
                                                                 {4, 7, 5},
                                                                 {0, 4, 5},
                                                                 {0, 5, 1},
                                                                 {2, 3, 7},
                                                                 {2, 7, 6},
                                                                 {0, 2, 6},
                                                                 {0, 6, 4},
                                                                 {1, 5, 7},
                                                                 {1, 7, 3}})
    m.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  return m;
}

// The plane's texels under the cube see only the cube's insides (its faces from behind): all
// 8 × 8 of them are marked invalid and none outside; those within the padding of a valid
// texel are refilled from it (no dark line along the contact), the buried rest keep their own
// (black, hidden) values; and the validity probe is the same for any thread count.
TEST(BakeTexels, SamplesInsideGeometryAreRefilledFromTheirNeighbours) {
  const Mesh m = planeWithCube();
  const auto occ = makeEmbreeOccluder(m);
  const int N = 32, padding = 2;
  const TexelBake b =
      bakeTexels(m, *occ, settings(TransferMode::Shadowed, 2, 256), m.lightmapUvs, N, N, padding);
  // The footprint u, v ∈ [0.375, 0.625]: texel centres 12.5..19.5 of 32.
  const auto under = [](int i) { return i >= 12 && i <= 19; };
  std::vector<std::uint32_t> expected;
  for (int y = 0; y < N; ++y)
    for (int x = 0; x < N; ++x)
      if (under(x) && under(y)) expected.push_back(std::uint32_t(y * N + x));
  EXPECT_EQ(b.invalid, expected);
  const auto t00 = [&](int x, int y) { return b.transfer.row(std::size_t(y) * N + x)[0]; };
  int refilled = 0, buried = 0;
  for (const std::uint32_t t : b.invalid) {
    const int x = int(t) % N, y = int(t) / N;
    float lowest = 1e9f;  // the darkest valid texel within the dilation's reach
    for (int dy = -padding; dy <= padding; ++dy)
      for (int dx = -padding; dx <= padding; ++dx)
        if (!(under(x + dx) && under(y + dy))) lowest = std::min(lowest, t00(x + dx, y + dy));
    if (lowest < 1e9f) {
      ++refilled;
      EXPECT_GT(lowest, 0.02f);
      EXPECT_GE(t00(x, y), lowest - 1e-6f) << "texel " << x << "," << y << " not refilled";
    } else {
      ++buried;
      EXPECT_LT(std::abs(t00(x, y)), 1e-5f) << "a buried texel keeps its own (unlit) value";
    }
    EXPECT_TRUE(b.filled[t]);
  }
  EXPECT_EQ(refilled, 64 - 16);
  EXPECT_EQ(buried, 16);
  std::vector<Vec3f> p, n;
  for (const TexelSample& s : b.samples.samples) {
    p.push_back(samplePosition(m, s));
    n.push_back(sampleNormal(m, s));
  }
  const std::vector<std::uint8_t> many = insideGeometry(m, *occ, p, n);
  const ThreadLimit one(1);
  EXPECT_EQ(insideGeometry(m, *occ, p, n), many);
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

// On the builtin scenes (their own lightmap UVs, or prt unwrap's atlas where they have none)
// and the Stanford bunny (unwrapped), shadowed per-texel transfer leaves no texel of a chart
// black or unfilled: every covered texel holds a finite value and is filled; every one not
// inside geometry holds T00 > 0; every one inside geometry is refilled from a valid neighbour
// (none buried out of reach of the padding). The sphere has no texel inside geometry, the
// scanned bunny (small self-intersections) almost none. 256 samples: the crevices behind the
// Cornell blocks get about 1% of a typical texel's light, which 64 samples can miss entirely.
TEST(BakeTexels, NoBlackOrInvalidTexelInsideAChartOnTheBuiltinScenesAndTheBunny) {
  std::vector<std::string> scenes = builtinSceneNames();
  for (std::string& n : scenes) n = "builtin:" + n;
  const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
  const bool haveBunny = std::filesystem::exists(bunny);
  if (haveBunny) scenes.push_back(bunny);
  for (const std::string& name : scenes) {
    SCOPED_TRACE(name);
    Mesh m = loadMesh(name);
    const int N = 128, padding = 2;
    if (findLightmapUvs(m, UvSetOption::Auto, N, N).uvs.empty()) {
      UnwrapSettings us;
      us.resolution = N;
      us.padding = padding;
      m = unwrap(m, us).mesh;
    }
    const std::span<const Vec2f> uvs = findLightmapUvs(m, UvSetOption::Auto, N, N).uvs;
    const auto occ = makeEmbreeOccluder(m);
    const TexelBake b =
        bakeTexels(m, *occ, settings(TransferMode::Shadowed, 2, 256), uvs, N, N, padding);
    std::vector<std::uint8_t> invalid(b.samples.texelCount(), 0);
    for (const std::uint32_t t : b.invalid) invalid[t] = 1;
    std::size_t covered = 0, refilled = 0, buried = 0, black = 0;
    for (std::size_t t = 0; t < b.samples.texelCount(); ++t) {
      if (b.samples.sampleOfTexel[t] < 0) continue;
      ++covered;
      const float t00 = b.transfer.row(t)[0];
      ASSERT_TRUE(std::isfinite(t00)) << "texel " << t;
      EXPECT_TRUE(b.filled[t]) << "texel " << t;
      if (!invalid[t]) {
        black += !(t00 > 0);
      } else if (t00 > 0) {
        ++refilled;
      } else {
        ++buried;
      }
    }
    EXPECT_GT(covered, std::size_t(N * N / 10));
    EXPECT_EQ(black, 0u) << "valid texels without light";
    EXPECT_EQ(buried, 0u) << "texels inside geometry left black";
    if (name == "builtin:sphere") {
      EXPECT_EQ(b.invalid.size(), 0u);
    }
    if (name == bunny) {
      EXPECT_LT(b.invalid.size(), covered / 1000 + 1);
    }
    std::cout << name << ": " << covered << " covered texels, " << b.invalid.size()
              << " inside geometry (" << refilled << " refilled)\n";
  }
  if (!haveBunny) GTEST_SKIP() << bunny << " is absent (glmark2-data): checked the builtin scenes";
}

}  // namespace
}  // namespace prt

namespace prt {
namespace {

// A base-colour texture reaches the bounces folded in at the vertices (albedoAtVertices), per
// vertex and per texel: a textured mesh bakes bit for bit as the same mesh with the texture
// folded into its albedo, and unlike the mesh without it (the texture is not dropped).
TEST(BakeTexels, BouncesSeeTheBaseColourTextureAtTheVertices) {
  Mesh textured = builtinScene("builtin:cornell?grid=4");
  textured.albedo.assign(textured.vertexCount(), Rgb(0.9f));
  textured.uvs.assign(textured.vertexCount(), Vec2f(0.25f, 0.5f));
  BaseColourTexture t;
  t.name = "two texels";
  t.image.width = 2;
  t.image.height = 1;
  t.image.rgb = {230, 60, 30, 30, 200, 60};  // orange left, green right
  textured.baseColour = t;
  Mesh folded = textured;
  foldBaseColour(folded);
  Mesh plain = textured;
  plain.baseColour.reset();
  BakeSettings s = settings(TransferMode::Interreflected, 2, 32);
  s.bounces = 1;
  const auto occ = makeEmbreeOccluder(textured);
  for (const bool texels : {false, true}) {
    SCOPED_TRACE(texels ? "per texel" : "per vertex");
    const auto run = [&](const Mesh& m) {
      return texels ? bakeTexels(m, *occ, s, m.lightmapUvs, 24, 24, 2).transfer : bake(m, *occ, s);
    };
    const Transfer a = run(textured), b = run(folded), c = run(plain);
    ASSERT_EQ(a.values().size(), b.values().size());
    EXPECT_EQ(a.channels(), 3);
    EXPECT_EQ(std::memcmp(a.values().data(), b.values().data(), a.values().size() * 4), 0);
    ASSERT_EQ(c.channels(), 1);  // grey without the texture
    double diff = 0;           // T00, red channel against the grey bake's
    for (std::size_t r = 0; r < a.rowCount(); ++r) diff += std::abs(a.row(r)[0] - c.row(r)[0]);
    EXPECT_GT(diff, 1e-3 * double(a.rowCount())) << "the texture must change the bounces";
  }
}

}  // namespace
}  // namespace prt
