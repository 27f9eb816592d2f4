#include "prt/transport/passes.hpp"

// The pass list of every kind of bake (see the header), on the kernels of bake.cpp (vectors)
// and bake_matrix.cpp (matrices), and the in-process driver bake() runs.

#include <algorithm>
#include <cstdio>
#include <string>

#include "bake_common.hpp"
#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/sh.hpp"

namespace prt {

using namespace bakedetail;

namespace {

enum class StatsKind { Vector, Matrix, MatrixDiffuse, MatrixGlossy };

RowRange overlap(RowRange a, RowRange b) {
  const std::size_t lo = std::max(a.first, b.first), hi = std::min(a.end(), b.end());
  return hi > lo ? RowRange{lo, hi - lo} : RowRange{lo, 0};
}

}  // namespace

struct BakePasses::Impl {
  const Mesh& mesh;
  const Occluder& occluder;
  BakeSettings settings;
  RowRange rows;
  std::vector<BakePassInfo> info;
  /// Per pass: the vector tables (its pass index in the vector bake is its own k) or the matrix
  /// tables.
  std::vector<std::shared_ptr<const VectorSetup>> vector;
  std::vector<std::shared_ptr<const MatrixSetup>> matrix;
  TransferShape result;
  bool sum = false, fullSum = false;
  int sumChannels = 1;
  StatsKind statsKind = StatsKind::Vector;

  Impl(const Mesh& m, const Occluder& o, const BakeSettings& s)
      : mesh(m), occluder(o), settings(s) {}

  void add(std::string name, TransferLayout layout, int channels, RowRange r, PassInput input,
           bool variance, std::shared_ptr<const VectorSetup> v,
           std::shared_ptr<const MatrixSetup> mx) {
    BakePassInfo p;
    p.name = std::move(name);
    p.shape = TransferShape{TransferDomain::Vertices, layout, settings.bands, channels, r};
    p.input = input;
    p.variance = variance;
    info.push_back(std::move(p));
    vector.push_back(std::move(v));
    matrix.push_back(std::move(mx));
  }

  /// The vector passes 0..K of `vs` (K = its bounces): all over the whole mesh except the last,
  /// which covers `last`.
  void addVectorPasses(const BakeSettings& vs, RowRange all, RowRange last, bool variance) {
    const auto setup = makeVectorSetup(mesh, vs);
    const int bounces = vs.effectiveBounces();
    const int channels = bounces > 0 && !vectorAlbedoGrey(*setup) ? 3 : 1;
    add("direct", TransferLayout::Vector, 1, bounces == 0 ? last : all, PassInput::None, variance,
        setup, nullptr);
    for (int k = 1; k <= bounces; ++k)
      add("bounce " + std::to_string(k), TransferLayout::Vector, channels,
          k == bounces ? last : all, PassInput::Previous, variance, setup, nullptr);
    sumChannels = bounces > 0 ? channels : 1;
  }
};

BakePasses::BakePasses(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings)
    : BakePasses(mesh, occluder, settings, true) {}

BakePasses::BakePasses(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                       bool checkMemory)
    : impl_(std::make_unique<Impl>(mesh, occluder, settings)) {
  validateBake(mesh, settings);
  if (checkMemory) checkFootprint(mesh, settings, bakeFootprint(mesh, settings));
  Impl& m = *impl_;
  m.rows = bakeRows(mesh, settings);
  const RowRange all{0, mesh.vertexCount()};
  const int bounces = settings.effectiveBounces();
  if (settings.layout == TransferLayout::Vector) {
    m.addVectorPasses(settings, all, m.rows, true);
    m.sum = bounces > 0;
    m.result = m.info.back().shape;
    m.statsKind = StatsKind::Vector;
    return;
  }
  const int channels = bakeFootprint(mesh, settings).channels;
  if (bounces == 0) {
    m.add("matrices", TransferLayout::Matrix, channels, m.rows, PassInput::None, true, nullptr,
          makeMatrixSetup(mesh, settings, false, false, channels));
    m.statsKind = StatsKind::Matrix;
  } else if (!settings.glossyBounces(TransferLayout::Matrix)) {
    // Diffuse bounce surfaces: the vector transfer with K − 1 bounces over the whole mesh (the
    // sum of its passes), then the matrices that gather it.
    m.addVectorPasses(diffuseBounceSource(settings), all, all, false);
    m.add("matrices", TransferLayout::Matrix, channels, m.rows, PassInput::Sum, true, nullptr,
          makeMatrixSetup(mesh, settings, true, false, channels));
    m.fullSum = true;
    m.statsKind = StatsKind::MatrixDiffuse;
  } else {
    // Glossy bounce surfaces: the matrices of orders 0..K, each from the one before.
    const std::vector<BakeSettings> orders = glossyBounceOrders(settings);
    for (int j = 0; j <= bounces; ++j) {
      const BakeSettings& o = orders[static_cast<std::size_t>(j)];
      const int c = bakeFootprint(mesh, o).channels;
      m.add(j == bounces ? "matrices" : "matrices of order " + std::to_string(j),
            TransferLayout::Matrix, c, j == bounces ? m.rows : all,
            j == 0 ? PassInput::None : PassInput::Previous, j == bounces, nullptr,
            makeMatrixSetup(mesh, o, j > 0, j > 0, c));
    }
    m.statsKind = StatsKind::MatrixGlossy;
  }
  m.result = m.info.back().shape;
}

BakePasses::~BakePasses() = default;

int BakePasses::count() const {
  return static_cast<int>(impl_->info.size());
}
const BakePassInfo& BakePasses::pass(int k) const {
  PRT_CHECK(k >= 0 && k < count(), "pass index out of range");
  return impl_->info[static_cast<std::size_t>(k)];
}
const TransferShape& BakePasses::resultShape() const {
  return impl_->result;
}
bool BakePasses::resultIsSum() const {
  return impl_->sum;
}
bool BakePasses::needsFullSum() const {
  return impl_->fullSum;
}
int BakePasses::sumChannels() const {
  return impl_->sumChannels;
}
ProgressFn BakePasses::passProgress(int k, const ProgressFn& whole) const {
  if (!whole) return {};
  const auto work = [this](int j) {
    const TransferShape& s = pass(j).shape;
    return double(s.rows.count) * (s.isMatrix() ? s.coeffs() : 1);
  };
  double before = 0, total = 0;
  for (int j = 0; j < count(); ++j) (j < k ? before : total) += work(j);
  total += before;
  const double lo = before / total, share = work(k) / total;
  return [whole, lo, share](double f) { return whole(lo + share * f); };
}
const BakeSettings& BakePasses::settings() const {
  return impl_->settings;
}
const Mesh& BakePasses::mesh() const {
  return impl_->mesh;
}

std::uint64_t BakePasses::compute(int k, RowRange rows, const Transfer& input, float* out,
                                  double* variance, Progress* progress) const {
  const BakePassInfo& p = pass(k);
  PRT_CHECK(rows.first >= p.shape.rows.first && rows.end() <= p.shape.rows.end(),
            "rows outside the pass");
  const Impl& m = *impl_;
  const Transfer* in = nullptr;
  if (p.input != PassInput::None) {
    PRT_CHECK(input.rows().first == 0 && input.rowCount() == m.mesh.vertexCount(),
              "a pass input covers the whole mesh");
    in = &input;
  }
  if (rows.count == 0) return 0;
  const auto k0 = static_cast<std::size_t>(k);
  if (m.vector[k0])
    return computeVectorRows(m.mesh, m.occluder, *m.vector[k0], k, rows, in, p.shape.channels, out,
                             variance, progress);
  return computeMatrixRows(m.mesh, m.occluder, *m.matrix[k0], rows, in, out, variance, progress);
}

void BakePasses::accumulate(int k, RowRange passRows, const float* values, RowRange sumRows,
                            float* sum) const {
  const BakePassInfo& p = pass(k);
  const int nc = p.shape.coeffs();
  const int pc = p.shape.channels, sc = impl_->sumChannels;
  PRT_CHECK(pc == 1 || pc == sc, "pass channels fit the sum");
  const std::size_t ps = static_cast<std::size_t>(nc) * pc, ss = static_cast<std::size_t>(nc) * sc;
  const RowRange both = overlap(passRows, sumRows);
  for (std::size_t v = both.first; v < both.end(); ++v) {
    const float* a = values + (v - passRows.first) * ps;
    float* s = sum + (v - sumRows.first) * ss;
    if (k == 0) {
      for (int i = 0; i < nc; ++i)
        for (int c = 0; c < sc; ++c) s[i * sc + c] = a[i * pc + (pc == 1 ? 0 : c)];
    } else if (pc == sc) {
      for (std::size_t i = 0; i < ss; ++i) s[i] += a[i];
    } else {
      for (int i = 0; i < nc; ++i)
        for (int c = 0; c < sc; ++c) s[i * sc + c] += a[i];
    }
  }
}

BakeStats BakePasses::stats(const std::vector<std::uint64_t>& rays,
                            const std::vector<double>& seconds, const std::vector<double>& variance,
                            double secondsTotal, int threads) const {
  const Impl& m = *impl_;
  PRT_CHECK(rays.size() == m.info.size() && seconds.size() == m.info.size(), "one figure per pass");
  BakeStats st;
  if (m.statsKind == StatsKind::Vector) {
    st = vectorStats(rays, seconds, variance);
  } else {
    st = matrixStats(m.statsKind == StatsKind::MatrixDiffuse  ? MatrixPassKind::DiffuseBounces
                     : m.statsKind == StatsKind::MatrixGlossy ? MatrixPassKind::GlossyBounces
                                                              : MatrixPassKind::Direct,
                     rays, seconds, variance, secondsTotal);
  }
  st.threads = threads;
  st.vertices = m.rows.count;
  st.secondsTotal = secondsTotal;
  return st;
}

std::string bakeIdentity(const Mesh& mesh, const BakeSettings& s) {
  const std::string hex = meshFingerprint(mesh);
  const RowRange rows = bakeRows(mesh, s);
  return std::to_string(mesh.vertexCount()) + " vertices, " + std::to_string(mesh.triangleCount()) +
         " triangles, mesh " + hex + "; " + toString(s.mode) + " " + toString(s.layout) + ", " +
         std::to_string(s.bands) + " bands, " + std::to_string(s.samples) + " samples, " +
         std::to_string(s.effectiveBounces()) + " bounces, seed " + std::to_string(s.seed) + ", " +
         toString(s.sampling) + ", " + s.material.spec() + ", vertices " +
         std::to_string(rows.first) + ".." + std::to_string(rows.end());
}

Transfer runBakePasses(const BakePasses& passes, BakeStats* stats, const ProgressFn& progressFn) {
  const auto start = Clock::now();
  const int count = passes.count();
  const std::size_t n = passes.mesh().vertexCount();
  const TransferShape& result = passes.resultShape();
  const RowRange rows = result.rows;

  const bool summing = passes.resultIsSum() || passes.needsFullSum();
  TransferShape sumShape = result;
  sumShape.layout = TransferLayout::Vector;
  sumShape.channels = passes.sumChannels();
  sumShape.rows = passes.needsFullSum() ? RowRange{0, n} : rows;
  Transfer sum = summing ? Transfer::zeros(sumShape) : Transfer();
  float* const sumData = summing ? sum.mutableValues() : nullptr;

  std::vector<double> variance(rows.count, 0.0);
  std::vector<std::uint64_t> rays;
  std::vector<double> secs;
  Transfer prev;
  for (int k = 0; k < count; ++k) {
    const BakePassInfo& p = passes.pass(k);
    const auto t0 = Clock::now();
    Progress progress(passes.passProgress(k, progressFn), p.shape.rows.count);
    Transfer out = Transfer::zeros(p.shape);
    std::vector<double> var(p.variance ? p.shape.rows.count : 0);
    const Transfer& input = p.input == PassInput::Sum ? sum : prev;
    rays.push_back(passes.compute(k, p.shape.rows, input, out.mutableValues(),
                                  p.variance ? var.data() : nullptr, &progress));
    if (p.variance)
      for (std::size_t v = std::max(rows.first, p.shape.rows.first);
           v < std::min(rows.end(), p.shape.rows.end()); ++v)
        variance[v - rows.first] += var[v - p.shape.rows.first];
    if (summing && !(k == count - 1 && !passes.resultIsSum()))
      passes.accumulate(k, p.shape.rows, out.values().data(), sumShape.rows, sumData);
    prev = std::move(out);
    secs.push_back(seconds(t0));
  }
  if (stats) *stats = passes.stats(rays, secs, variance, seconds(start), maxThreads());
  return passes.resultIsSum() ? sum : prev;
}

}  // namespace prt
