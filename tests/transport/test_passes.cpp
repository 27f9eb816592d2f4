// The bake as a list of passes (prt/transport/passes.hpp), which every scheduler drives: any
// split of any pass into pieces, computed in any order, reassembles into bake()'s transfer and
// statistics bit for bit — the property MPI ranks and job-array shards rest on.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/passes.hpp"

namespace prt {
namespace {

/// Runs the passes as a scheduler would: each pass in random pieces, computed in random order,
/// the same bookkeeping as runBakePasses (accumulate, variance, stats).
Transfer bakeInPieces(const BakePasses& passes, std::mt19937& rng, BakeStats* stats) {
  const std::size_t n = passes.mesh().vertexCount();
  const TransferShape& result = passes.resultShape();
  const bool summing = passes.resultIsSum() || passes.needsFullSum();
  TransferShape sumShape = result;
  sumShape.layout = TransferLayout::Vector;
  sumShape.channels = passes.sumChannels();
  sumShape.rows = passes.needsFullSum() ? RowRange{0, n} : result.rows;
  Transfer sum = summing ? Transfer::zeros(sumShape) : Transfer();
  float* sumData = summing ? sum.mutableValues() : nullptr;
  std::vector<double> variance(result.rows.count, 0.0);
  std::vector<std::uint64_t> rays;
  Transfer prev;
  for (int k = 0; k < passes.count(); ++k) {
    const BakePassInfo& p = passes.pass(k);
    Transfer out = Transfer::zeros(p.shape);
    float* values = out.mutableValues();
    std::vector<double> var(p.shape.rows.count, 0.0);
    // Cut points at random, pieces computed in a random order.
    std::vector<std::size_t> cuts = {0, p.shape.rows.count};
    for (int c = 0; c < 7; ++c) cuts.push_back(rng() % (p.shape.rows.count + 1));
    std::sort(cuts.begin(), cuts.end());
    std::vector<std::size_t> order(cuts.size() - 1);
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::uint64_t r = 0;
    for (std::size_t i : order) {
      const std::size_t lo = cuts[i], hi = cuts[i + 1];
      r += passes.compute(k, {p.shape.rows.first + lo, hi - lo},
                          p.input == PassInput::Sum ? sum : prev, values + lo * p.shape.stride(),
                          var.data() + lo);
    }
    rays.push_back(r);
    if (p.variance)
      for (std::size_t v = result.rows.first; v < result.rows.end(); ++v)
        if (v >= p.shape.rows.first && v < p.shape.rows.end())
          variance[v - result.rows.first] += var[v - p.shape.rows.first];
    if (summing && !(k == passes.count() - 1 && !passes.resultIsSum()))
      passes.accumulate(k, p.shape.rows, out.values().data(), sumShape.rows, sumData);
    prev = std::move(out);
  }
  *stats = passes.stats(rays, std::vector<double>(rays.size(), 0.0), variance, 0.0, 1);
  return passes.resultIsSum() ? sum : prev;
}

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
    BakeStats expected, got;
    const Transfer whole = bake(mesh, *occluder, s, &expected);
    const BakePasses passes(mesh, *occluder, s);
    EXPECT_EQ(passes.count(), c.bounces + 1) << c.what;
    const Transfer pieces = bakeInPieces(passes, rng, &got);
    expectSame(pieces, whole, c.what);
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
}

}  // namespace
}  // namespace prt
