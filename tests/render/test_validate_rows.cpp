// Which rows validation reads (render/validate.hpp: chooseRows, validate). Per texel, the rows
// drawn are valid texels only (never the gutter, never a texel inside geometry), at exactly
// texelRowPoints' points, each valid texel as likely as another; where no texel lies inside
// geometry they are the very rows of the earlier rule (vertexSubset of the covered texels).
// validate() reads the transfer at the validated rows alone: a transfer whose other rows are
// unreadable memory (PROT_NONE: a read faults) validates to the same report as the whole one,
// and a non-finite row is an error only where it is validated.

#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "common/error_text.hpp"
#include "prt/core/error.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/render/validate.hpp"
#include "prt/transport/bake_texels.hpp"

namespace prt::render {
namespace {

using envmap::Environment;
using testing::errorOf;

struct TexelScene {
  Mesh mesh;
  std::unique_ptr<Occluder> occ;
  BakeSettings bake;
  Transfer transfer;
  TransferShape::LightmapSize lightmap() const { return transfer.shape().lightmap; }
};

TexelScene bakeTexelScene(const std::string& name, int side, TransferLayout layout, int samples) {
  TexelScene s;
  s.mesh = builtinScene(name);
  s.occ = makeEmbreeOccluder(s.mesh);
  s.bake.mode = TransferMode::Shadowed;
  s.bake.layout = layout;
  s.bake.bands = 3;
  s.bake.samples = samples;
  if (layout == TransferLayout::Matrix) s.bake.material = parseMaterial("phong?ks=0.4&exponent=6");
  s.transfer = bakeTexels(s.mesh, *s.occ, s.bake, s.mesh.lightmapUvs, side, side, 2).transfer;
  return s;
}

/// The covered texels in texel order (sampleTexels').
std::vector<std::uint32_t> coveredTexels(const TexelScene& s) {
  const TexelSamples all =
      sampleTexels(s.mesh, s.mesh.lightmapUvs, s.lightmap().width, s.lightmap().height);
  std::vector<std::uint32_t> covered;
  for (const TexelSample& t : all.samples) covered.push_back(t.texel);
  return covered;
}

// The Cornell box's blocks stand on its floor: some covered texels lie inside geometry. The
// rows drawn are valid ones, ascending, each with texelRowPoints' own point, normal and albedo,
// and every valid one when asked for all (0, or more than there are); each valid texel is drawn
// as often as another over many seeds.
TEST(ValidateRows, TexelRowsAreValidTexelsAtTheirOwnPointsDrawnUniformly) {
  const TexelScene s = bakeTexelScene("builtin:cornell?grid=8", 32, TransferLayout::Vector, 8);
  const RowPoints whole = texelRowPoints(s.mesh, *s.occ, s.lightmap());
  const std::size_t covered = coveredTexels(s).size();
  ASSERT_LT(whole.valid.size(), covered) << "the test needs texels inside geometry";
  ASSERT_GT(whole.valid.size(), 200u);
  ASSERT_FALSE(whole.albedo.empty());

  const auto expectOwnPoints = [&](const RowChoice& c) {
    ASSERT_TRUE(c.points);
    EXPECT_EQ(c.points->rows, c.rows);
    EXPECT_EQ(c.points->valid, c.rows);
    for (std::size_t i = 0; i < c.rows.size(); ++i) {
      const std::uint32_t t = c.rows[i];
      EXPECT_TRUE(std::binary_search(whole.valid.begin(), whole.valid.end(), t)) << t;
      EXPECT_EQ(c.points->positions[i], whole.positions[t]) << t;
      EXPECT_EQ(c.points->normals[i], whole.normals[t]) << t;
      EXPECT_EQ(c.points->albedo[i], whole.albedo[t]) << t;
    }
  };
  for (std::size_t count : {0ul, 1ul, 40ul, 100000ul}) {
    const RowChoice c = chooseRows(s.mesh, *s.occ, s.transfer, count, 5);
    EXPECT_TRUE(std::is_sorted(c.rows.begin(), c.rows.end()));
    EXPECT_EQ(c.rows.size(), count == 0 ? whole.valid.size() : std::min(count, whole.valid.size()));
    if (count == 0 || count > whole.valid.size()) {
      EXPECT_EQ(c.rows, whole.valid);
    }
    expectOwnPoints(c);
  }
  // The points of texels given (a reference file's rows), valid or not: texelRowPoints' own
  // where they are valid, their neighbours' dilation elsewhere (a gutter texel, one inside
  // geometry), and `valid` the valid ones among them.
  const std::vector<std::uint32_t> coveredList = coveredTexels(s);
  std::vector<std::uint32_t> asked = {whole.valid[7], whole.valid[100]};
  for (std::uint32_t t : coveredList)
    if (!std::binary_search(whole.valid.begin(), whole.valid.end(), t)) {
      asked.push_back(t);  // inside geometry
      break;
    }
  for (std::uint32_t t = 0; t < s.lightmap().texels(); ++t)
    if (!std::binary_search(coveredList.begin(), coveredList.end(), t)) {
      asked.push_back(t);  // the gutter
      break;
    }
  ASSERT_EQ(asked.size(), 4u);
  std::sort(asked.begin(), asked.end());
  for (const bool allValid : {true, false}) {
    const std::vector<std::uint32_t> texels =
        allValid ? std::vector<std::uint32_t>{whole.valid[7], whole.valid[100]} : asked;
    const RowPoints at = texelRowPointsAt(s.mesh, *s.occ, s.lightmap(), texels);
    EXPECT_EQ(at.rows, texels);
    EXPECT_EQ(at.valid.size(), 2u);
    for (std::size_t i = 0; i < texels.size(); ++i) {
      EXPECT_EQ(at.positions[i], whole.positions[texels[i]]) << texels[i];
      EXPECT_EQ(at.normals[i], whole.normals[texels[i]]) << texels[i];
      EXPECT_EQ(at.albedo[i], whole.albedo[texels[i]]) << texels[i];
    }
  }

  EXPECT_EQ(chooseRows(s.mesh, *s.occ, s.transfer, 40, 5).rows,
            chooseRows(s.mesh, *s.occ, s.transfer, 40, 5).rows);
  EXPECT_NE(chooseRows(s.mesh, *s.occ, s.transfer, 40, 5).rows,
            chooseRows(s.mesh, *s.occ, s.transfer, 40, 6).rows);

  // 20 of the V valid texels over 600 seeds: each is drawn Binomial(600, 20/V) times, and
  // Σ (h − e)² / var over the V texels has mean V and standard deviation about √(2V): it stays
  // within 5 of them (the counts' fixed sum only lowers it).
  constexpr int kSeeds = 600, kCount = 20;
  std::vector<double> hits(s.lightmap().texels(), 0.0);
  for (int seed = 0; seed < kSeeds; ++seed)
    for (std::uint32_t t : chooseRows(s.mesh, *s.occ, s.transfer, kCount, seed).rows) hits[t] += 1;
  const double V = double(whole.valid.size()), p = kCount / V;
  const double expected = kSeeds * p, var = expected * (1 - p);
  double chi2 = 0;
  for (std::uint32_t t : whole.valid) chi2 += (hits[t] - expected) * (hits[t] - expected) / var;
  EXPECT_LT(chi2, V + 5 * std::sqrt(2 * V));
  EXPECT_GT(chi2, V - 5 * std::sqrt(2 * V));
}

// Without texels inside geometry (a plane), the draw is the earlier rule's — vertexSubset over
// the valid texels, which are then the covered ones — row for row.
TEST(ValidateRows, WithoutTexelsInsideGeometryTheRowsAreVertexSubsetsOfTheCoveredTexels) {
  const TexelScene s = bakeTexelScene("builtin:plane?grid=6", 40, TransferLayout::Vector, 8);
  const std::vector<std::uint32_t> covered = coveredTexels(s);
  ASSERT_EQ(texelRowPoints(s.mesh, *s.occ, s.lightmap()).valid, covered);
  for (std::uint64_t seed : {0ull, 1ull, 99ull}) {
    std::vector<std::uint32_t> earlier;
    for (std::uint32_t k : vertexSubset(covered.size(), 50, seed)) earlier.push_back(covered[k]);
    EXPECT_EQ(chooseRows(s.mesh, *s.occ, s.transfer, 50, seed).rows, earlier) << seed;
  }
}

/// `t`'s rows in memory where only the pages holding `readable` rows can be read: reading any
/// other faults (SIGSEGV), so a computation that reads them cannot pass.
Transfer guardedRows(const Transfer& t, const std::vector<std::uint32_t>& readable) {
  const std::size_t page = std::size_t(::sysconf(_SC_PAGESIZE));
  const std::size_t rowBytes = t.stride() * sizeof(float);
  const std::size_t bytes = (t.rowCount() * rowBytes + page - 1) / page * page;
  void* p = ::mmap(nullptr, bytes, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw Error("mmap failed");
  std::shared_ptr<void> keeper(p, [bytes](void* q) { ::munmap(q, bytes); });
  auto* base = static_cast<unsigned char*>(p);
  for (std::uint32_t r : readable) {
    const std::size_t first = r * rowBytes / page, last = ((r + 1) * rowBytes - 1) / page;
    if (::mprotect(base + first * page, (last - first + 1) * page, PROT_READ | PROT_WRITE) != 0)
      throw Error("mprotect failed");
  }
  for (std::uint32_t r : readable) std::memcpy(base + r * rowBytes, t.row(r), rowBytes);
  return Transfer::dense(
      t.shape(), FloatArray::view(keeper, reinterpret_cast<const float*>(p), t.values().size()));
}

// A per-texel transfer whose unvalidated rows cannot be read validates to the same table and
// per-texel errors as the whole transfer in memory: validation reads the rows it validates
// and no other (diffuse vectors, and glossy matrices relit at their texels' points).
TEST(ValidateRows, ValidateReadsTheValidatedRowsAlone) {
  const Environment env = envmap::builtinEnvironment("builtin:sky", 128);
  for (const TransferLayout layout : {TransferLayout::Vector, TransferLayout::Matrix}) {
    const bool matrix = layout == TransferLayout::Matrix;
    const TexelScene s = bakeTexelScene("builtin:cornell?grid=8", matrix ? 32 : 64, layout, 16);
    const sh::RgbSh light = envmap::projectEnvironment(env, 3);
    ValidateSettings vs;
    vs.reference.samples = 32;
    vs.reference.seed = 3;
    vs.reference.eye = frameMesh(s.mesh, 640, 480).eye;
    vs.maxVertices = 12;
    const std::vector<std::uint32_t> rows =
        chooseRows(s.mesh, *s.occ, s.transfer, vs.maxVertices, vs.reference.seed).rows;
    ASSERT_EQ(rows.size(), 12u);
    const Transfer guarded = guardedRows(s.transfer, rows);
    const ValidationReport whole = validate(s.mesh, *s.occ, s.transfer, s.bake, env, light, vs);
    const ValidationReport read = validate(s.mesh, *s.occ, guarded, s.bake, env, light, vs);
    EXPECT_EQ(read.reference.vertices, rows);
    EXPECT_EQ(formatTable(read), formatTable(whole)) << toString(layout);
    EXPECT_EQ(read.vertexError, whole.vertexError) << toString(layout);
  }
}

// A non-finite value (a corrupt file, read mapped: io/bake_file.hpp, mapBake) is refused by name
// where its row is validated, and never read elsewhere.
TEST(ValidateRows, ANonFiniteRowIsRefusedWhereItIsValidated) {
  const TexelScene s = bakeTexelScene("builtin:cornell?grid=8", 32, TransferLayout::Vector, 8);
  const Environment env = envmap::builtinEnvironment("builtin:sky", 128);
  const sh::RgbSh light = envmap::projectEnvironment(env, 3);
  ValidateSettings vs;
  vs.reference.samples = 16;
  vs.maxVertices = 10;
  vs.bakeName = "corrupt.glb";
  const std::vector<std::uint32_t> rows =
      chooseRows(s.mesh, *s.occ, s.transfer, vs.maxVertices, vs.reference.seed).rows;
  const auto withNan = [&](std::uint32_t row) {
    Transfer t = s.transfer;
    t.mutableValues()[row * t.stride() + 4] = std::numeric_limits<float>::quiet_NaN();
    return t;
  };
  std::uint32_t unvalidated = 0;
  while (std::binary_search(rows.begin(), rows.end(), unvalidated)) ++unvalidated;
  EXPECT_NO_THROW(validate(s.mesh, *s.occ, withNan(unvalidated), s.bake, env, light, vs));
  EXPECT_EQ(errorOf([&] { validate(s.mesh, *s.occ, withNan(rows[3]), s.bake, env, light, vs); }),
            "corrupt.glb: the transfer of texel " + std::to_string(rows[3]) +
                " is not finite (a corrupt bake?)");
}

}  // namespace
}  // namespace prt::render
