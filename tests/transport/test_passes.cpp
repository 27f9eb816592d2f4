// The bake as a list of passes (prt/transport/passes.hpp), which every executor drives: any
// split of any pass into pieces, computed in any order, reassembles into bake()'s transfer and
// statistics bit for bit, per vertex and per texel — the property MPI ranks and job-array shards
// rest on.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"
#include "prt/transport/passes.hpp"

namespace prt {
namespace {

/// An executor as a scheduler might be: each pass in random pieces, computed in a random order
/// (the one pass driver, runBakePasses, joins them).
class PiecesExecutor : public PassExecutor {
 public:
  explicit PiecesExecutor(std::mt19937& rng) : rng_(rng) {}
  Rows run(const BakePasses& passes, int k, const PassSource& input, const ProgressFn&) override {
    const BakePassInfo& p = passes.pass(k);
    Rows r;
    r.values = Transfer::zeros(p.shape);
    float* values = r.values.mutableValues();
    r.variance.assign(p.shape.rows.count, 0.0);
    // Cut points at random, pieces computed in a random order.
    std::vector<std::size_t> cuts = {0, p.shape.rows.count};
    for (int c = 0; c < 7; ++c) cuts.push_back(rng_() % (p.shape.rows.count + 1));
    std::sort(cuts.begin(), cuts.end());
    std::vector<std::size_t> order(cuts.size() - 1);
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng_);
    for (std::size_t i : order) {
      const std::size_t lo = cuts[i], hi = cuts[i + 1];
      r.rays += passes.compute(k, {p.shape.rows.first + lo, hi - lo}, input,
                               values + lo * p.shape.stride(), r.variance.data() + lo);
    }
    if (!p.variance) r.variance.clear();
    return r;
  }
  int threads() const override { return 1; }

 private:
  std::mt19937& rng_;
};

void expectSame(const Transfer& a, const Transfer& b, const std::string& what) {
  ASSERT_EQ(a.shape(), b.shape()) << what;
  EXPECT_EQ(0, std::memcmp(a.values().data(), b.values().data(), a.values().size() * 4)) << what;
}

TEST(BakePasses, AnySplitOfEveryPassReassemblesIntoTheBake) {
  const Mesh mesh = builtinScene("cornell");
  const auto occluder = makeEmbreeOccluder(mesh);
  std::mt19937 rng(7);
  struct Case {
    const char* what;
    TransferMode mode;
    TransferLayout layout;
    int bounces;
    const char* material;
    RowRange rows;
    int lightmap = 0;  ///< per texel: the lightmap's side (0: per vertex)
  };
  const Case cases[] = {
      {"shadowed vectors", TransferMode::Shadowed, TransferLayout::Vector, 0, "", {}},
      {"RGB bounces, a range",
       TransferMode::Interreflected,
       TransferLayout::Vector,
       2,
       "",
       {1000, 3000}},
      {"diffuse-bounce matrices",
       TransferMode::Interreflected,
       TransferLayout::Matrix,
       2,
       "",
       {0, 1500}},
      {"glossy-bounce matrices",
       TransferMode::Interreflected,
       TransferLayout::Matrix,
       2,
       "phong?exponent=8&ks=0.3,0.4,0.5",
       {200, 700}},
      {"texels: RGB bounces, a range",
       TransferMode::Interreflected,
       TransferLayout::Vector,
       2,
       "",
       {700, 500},
       48},
      {"texels: shadowed vectors, a range",
       TransferMode::Shadowed,
       TransferLayout::Vector,
       0,
       "",
       {900, 300},
       40},
      {"texels: diffuse-bounce matrices",
       TransferMode::Interreflected,
       TransferLayout::Matrix,
       1,
       "",
       {},
       24},
      {"texels: glossy-bounce matrices",
       TransferMode::Interreflected,
       TransferLayout::Matrix,
       2,
       "phong?exponent=8&ks=0.3,0.4,0.5",
       {100, 300},
       24},
  };
  for (const Case& c : cases) {
    BakeSettings s;
    s.mode = c.mode;
    s.layout = c.layout;
    s.bounces = c.bounces;
    s.bands = c.layout == TransferLayout::Matrix ? 2 : 3;
    s.samples = 16;
    s.seed = 11;
    if (*c.material) s.material = parseMaterial(c.material);
    s.rows = c.rows;
    if (c.lightmap) {
      s.domain = TransferDomain::Texels;
      s.lightmap = {c.lightmap, c.lightmap, 2, false};
    }
    BakeStats expected, got;
    const Transfer whole = bake(mesh, *occluder, s, &expected);
    const BakePasses passes(mesh, *occluder, s);
    EXPECT_EQ(passes.count(), c.bounces + 1) << c.what;
    PiecesExecutor pieces(rng);
    const Transfer split = runBakePasses(passes, pieces, &got, {});
    expectSame(split, whole, c.what);
    if (c.lightmap) {
      // The same bake as the per-texel call makes it.
      BakeSettings t = s;
      t.domain = TransferDomain::Vertices;
      expectSame(
          bakeTexels(mesh, *occluder, t, mesh.lightmapUvs, c.lightmap, c.lightmap, 2).transfer,
          whole, c.what);
    }
    EXPECT_EQ(got.rays, expected.rays) << c.what;
    EXPECT_EQ(got.raysBounce, expected.raysBounce) << c.what;
    EXPECT_EQ(got.stdErrT0Mean, expected.stdErrT0Mean) << c.what;
    EXPECT_EQ(got.stdErrConstMax, expected.stdErrConstMax) << c.what;
    EXPECT_EQ(got.vertices, expected.vertices) << c.what;
  }
}

TEST(BakePasses, TheIdentityTellsBakesApart) {
  const Mesh mesh = builtinScene("sphere-plane");
  BakeSettings s;
  const std::string a = bakeIdentity(mesh, s);
  EXPECT_EQ(a, bakeIdentity(mesh, s));
  BakeSettings t = s;
  t.seed = 1;
  EXPECT_NE(bakeIdentity(mesh, t), a);
  t = s;
  t.samples = 2048;
  EXPECT_NE(bakeIdentity(mesh, t), a);
  Mesh moved = mesh;
  moved.positions[5].x += 1e-6f;
  EXPECT_NE(bakeIdentity(moved, s), a);
  // The domain: per texel, the lightmap's size, its padding and the UVs it lies over.
  const Mesh box = builtinScene("cornell");
  t = s;
  const std::string vertices = bakeIdentity(box, t);
  t.domain = TransferDomain::Texels;
  t.lightmap = {64, 64, 2, false};
  const std::string texels = bakeIdentity(box, t);
  EXPECT_NE(texels, vertices);
  t.lightmap.padding = 3;
  EXPECT_NE(bakeIdentity(box, t), texels);
  t.lightmap.padding = 2;
  Mesh shifted = box;
  ASSERT_GT(shifted.lightmapUvs.size(), 3u);
  shifted.lightmapUvs[3].x += 1e-3f;
  EXPECT_NE(bakeIdentity(shifted, t), texels);
}

}  // namespace
}  // namespace prt
