#include "prt/transport/passes.hpp"

// The pass list of every kind of bake (see the header), on the kernels of bake.cpp (vectors)
// and bake_matrix.cpp (matrices), and the in-process driver bake() runs.

#include <algorithm>
#include <cstdio>
#include <string>

#include "bake_common.hpp"
#include "bake_haar.hpp"
#include "probe_domain.hpp"
#include "prt/core/error.hpp"
#include "prt/core/hash.hpp"
#include "prt/core/parallel.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/row_dilation.hpp"
#include "texel_domain.hpp"

namespace prt {

using namespace bakedetail;

namespace {

enum class StatsKind { Vector, Matrix, MatrixDiffuse, MatrixGlossy, HaarBounces };

RowRange overlap(RowRange a, RowRange b) {
  const std::size_t lo = std::max(a.first, b.first), hi = std::min(a.end(), b.end());
  return hi > lo ? RowRange{lo, hi - lo} : RowRange{lo, 0};
}

}  // namespace

struct BakePasses::Impl {
  const Mesh& mesh;
  const Occluder& occluder;
  BakeSettings settings;
  RowRange rows;  ///< the bake's range
  std::vector<BakePassInfo> info;
  /// Per pass: the vector tables (its pass index in the vector bake is its own k) or the matrix
  /// tables.
  std::vector<std::shared_ptr<const VectorSetup>> vector;
  std::vector<std::shared_ptr<const MatrixSetup>> matrix;
  /// Per pass: the Haar tables (a Haar bake's one pass), else null.
  std::vector<std::shared_ptr<const HaarSetup>> haar;
  TransferShape result;
  bool sum = false, fullSum = false;
  int sumChannels = 1;
  StatsKind statsKind = StatsKind::Vector;
  /// Per texel: the lightmap's samples (empty domain per vertex).
  std::unique_ptr<TexelDomain> texels;
  /// Per probe: the grid's points and which lie inside geometry.
  std::unique_ptr<ProbeDomain> probes;
  TexelSamples noSamples;
  std::vector<std::uint32_t> noTexels;

  Impl(const Mesh& m, const Occluder& o, const BakeSettings& s)
      : mesh(m), occluder(o), settings(s) {}

  bool perTexel() const { return texels != nullptr; }

  /// The domain of a pass of `layout`: the bake's, except the vector passes of a probe bake,
  /// which are the diffuse transfer of the mesh's surfaces its probes gather (over vertices).
  TransferDomain passDomain(TransferLayout layout) const {
    return settings.domain == TransferDomain::Probes && layout == TransferLayout::Vector
               ? TransferDomain::Vertices
               : settings.domain;
  }

  /// Rows of the whole of `domain`.
  std::size_t wholeRows(TransferDomain domain) const {
    return domain == TransferDomain::Vertices ? mesh.vertexCount()
                                              : bakedetail::domainRows(mesh, settings);
  }

  /// A pass whose rows are in the basis and bands of `of` (the bake's settings, or those of the
  /// SH bounce an inter-reflected Haar bake holds).
  void add(std::string name, TransferLayout layout, int channels, RowRange r, PassInput input,
           bool variance, std::shared_ptr<const VectorSetup> v,
           std::shared_ptr<const MatrixSetup> mx, const BakeSettings* of = nullptr) {
    const BakeSettings& basis = of ? *of : settings;
    BakePassInfo p;
    p.name = std::move(name);
    p.shape = basis.inBasis(TransferShape{passDomain(layout), layout, basis.bands, channels, r});
    if (perTexel()) p.shape.lightmap = {texels->width, texels->height, texels->padding, false};
    if (p.shape.domain == TransferDomain::Probes) p.shape.probes = settings.probes;
    p.input = input;
    p.variance = variance;
    info.push_back(std::move(p));
    vector.push_back(std::move(v));
    matrix.push_back(std::move(mx));
    haar.push_back(nullptr);
  }

  /// The vector passes 0..K of `vs` (K = its bounces): all over the whole domain except the
  /// last, which covers `last`.
  void addVectorPasses(const BakeSettings& vs, RowRange all, RowRange last, bool variance) {
    const auto setup = makeVectorSetup(mesh, vs);
    const int bounces = vs.effectiveBounces();
    const int channels = bounces > 0 && !vectorAlbedoGrey(*setup) ? 3 : 1;
    add("direct", TransferLayout::Vector, 1, bounces == 0 ? last : all, PassInput::None, variance,
        setup, nullptr, &vs);
    for (int k = 1; k <= bounces; ++k)
      add("bounce " + std::to_string(k), TransferLayout::Vector, channels,
          k == bounces ? last : all, PassInput::Previous, variance, setup, nullptr, &vs);
    sumChannels = bounces > 0 ? channels : 1;
  }
};

BakePasses::BakePasses(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                       const BakePassOptions& options)
    : impl_(std::make_unique<Impl>(mesh, occluder, settings)) {
  const BakePlan plan = planBake(mesh, settings, options.checkMemory);
  const int channels = plan.footprint.channels;
  Impl& m = *impl_;
  m.rows = plan.rows;
  const RowRange all{0, plan.domainRows};
  const int bounces = settings.effectiveBounces();
  if (settings.domain == TransferDomain::Probes) {
    // The probes' matrices over the range widened by the refill's reach; with bounces, first
    // the surfaces' diffuse transfer of one bounce less over every vertex, which they gather.
    ProbeDomain grid;
    grid.grid = settings.probes;
    const RowRange last = grid.widen(m.rows);
    m.probes = std::make_unique<ProbeDomain>(makeProbeDomain(mesh, occluder, settings.probes, last));
    if (bounces == 0) {
      m.add("probes", TransferLayout::Matrix, channels, last, PassInput::None, true, nullptr,
            makeMatrixSetup(mesh, settings, false, false, channels));
      m.statsKind = StatsKind::Matrix;
    } else {
      const RowRange vertices{0, mesh.vertexCount()};
      m.addVectorPasses(*plan.diffuseSource, vertices, vertices, false);
      m.add("probes", TransferLayout::Matrix, channels, last, PassInput::Sum, true, nullptr,
            makeMatrixSetup(mesh, settings, true, false, channels));
      m.fullSum = true;
      m.statsKind = StatsKind::MatrixDiffuse;
    }
    m.result = m.info.back().shape;
    m.result.rows = m.rows;
    return;
  }
  // The last pass's rows: the range, per texel widened by the dilation's reach; the samples
  // kept are those the passes compute (all of them when an earlier pass is read whole).
  RowRange last = m.rows;
  if (settings.domain == TransferDomain::Texels) {
    const auto& lm = settings.lightmap;
    const std::span<const Vec2f> uvs = options.lightmapUvs.empty()
                                           ? std::span<const Vec2f>(mesh.lightmapUvs)
                                           : options.lightmapUvs;
    TexelDomain probe;
    probe.width = lm.width, probe.height = lm.height, probe.padding = lm.padding;
    last = probe.widen(m.rows);
    m.texels = std::make_unique<TexelDomain>(makeTexelDomain(
        mesh, occluder, uvs, lm.width, lm.height, lm.padding, bounces > 0 ? all : last));
  }
  if (settings.basis == TransferBasis::Haar) {
    // The rows' pruned wavelet transfer; inter-reflected, first their bounce in SH: its direct
    // pass (read by the first bounce, not summed: the Haar rows hold the direct light) and its
    // bounces, whose sum the rows read and keep.
    PassInput input = PassInput::None;
    if (plan.haarBounce) {
      m.addVectorPasses(*plan.haarBounce, all, all, true);
      m.info.front().summed = false;
      m.info.front().variance = false;
      m.fullSum = true;
      input = PassInput::Sum;
    }
    m.add(plan.haarBounce ? "Haar rows" : "direct", TransferLayout::Vector, channels, last, input,
          true, nullptr, nullptr);
    m.haar.back() = makeHaarSetup(settings);
    m.statsKind = plan.haarBounce ? StatsKind::HaarBounces : StatsKind::Vector;
  } else if (settings.layout == TransferLayout::Vector) {
    m.addVectorPasses(settings, all, last, true);
    m.sum = bounces > 0;
    m.statsKind = StatsKind::Vector;
  } else if (bounces == 0) {
    m.add("matrices", TransferLayout::Matrix, channels, last, PassInput::None, true, nullptr,
          makeMatrixSetup(mesh, settings, false, false, channels));
    m.statsKind = StatsKind::Matrix;
  } else if (plan.diffuseSource) {
    // Diffuse bounce surfaces: the vector transfer with K − 1 bounces over the whole domain
    // (the sum of its passes), then the matrices that gather it.
    m.addVectorPasses(*plan.diffuseSource, all, all, false);
    m.add("matrices", TransferLayout::Matrix, channels, last, PassInput::Sum, true, nullptr,
          makeMatrixSetup(mesh, settings, true, false, channels));
    m.fullSum = true;
    m.statsKind = StatsKind::MatrixDiffuse;
  } else {
    // Glossy bounce surfaces: the matrices of orders 0..K, each from the one before.
    for (int j = 0; j <= bounces; ++j) {
      const BakeSettings& o = plan.glossyOrders[static_cast<std::size_t>(j)];
      const int c = plan.glossyChannels[static_cast<std::size_t>(j)];
      m.add(j == bounces ? "matrices" : "matrices of order " + std::to_string(j),
            TransferLayout::Matrix, c, j == bounces ? last : all,
            j == 0 ? PassInput::None : PassInput::Previous, j == bounces, nullptr,
            makeMatrixSetup(mesh, o, j > 0, j > 0, c));
    }
    m.statsKind = StatsKind::MatrixGlossy;
  }
  m.result = m.info.back().shape;
  m.result.rows = m.rows;
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
int BakePasses::sumChannels() const {
  return impl_->sumChannels;
}
std::size_t BakePasses::resultBytes() const {
  const std::size_t bytes = bakeFootprint(impl_->mesh, impl_->settings).transferBytes;
  return impl_->sum ? 2 * bytes : bytes;
}
bool BakePasses::resultIsLastPass() const {
  return !impl_->sum;
}
bool BakePasses::sums() const {
  return impl_->sum || impl_->fullSum;
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
std::size_t BakePasses::domainRows() const {
  return bakedetail::domainRows(impl_->mesh, impl_->settings);
}
const TexelSamples& BakePasses::texelSamples() const {
  return impl_->perTexel() ? impl_->texels->samples : impl_->noSamples;
}
const std::vector<std::uint32_t>& BakePasses::texelsInsideGeometry() const {
  return impl_->perTexel() ? impl_->texels->invalid : impl_->noTexels;
}

PassSource BakePasses::prepare(int k, const Transfer& input) const {
  PassSource src;
  if (pass(k).input == PassInput::None) return src;
  PRT_CHECK(input.rows().first == 0 && input.rowCount() == impl_->wholeRows(input.domain()),
            "a pass input covers the whole domain");
  src.stride_ = input.stride();
  if (!impl_->perTexel()) {
    src.transfer_ = &input;
    return src;
  }
  std::vector<std::uint8_t> filled;
  src.image_ = std::make_shared<const std::vector<float>>(impl_->texels->layOut(
      input.values().data(), input.rows(), src.stride_, rowDilation(input.shape().basis), filled));
  return src;
}

std::uint64_t BakePasses::compute(int k, RowRange rows, const PassSource& input, float* out,
                                  double* variance, Progress* progress) const {
  const BakePassInfo& p = pass(k);
  PRT_CHECK(rows.first >= p.shape.rows.first && rows.end() <= p.shape.rows.end(),
            "rows outside the pass");
  PRT_CHECK(p.input == PassInput::None || input.transfer_ || input.image_,
            "the pass's input is prepared");
  const Impl& m = *impl_;
  if (rows.count == 0) return 0;
  const auto k0 = static_cast<std::size_t>(k);
  if (p.shape.domain == TransferDomain::Probes) {
    const ProbeDomain& d = *m.probes;
    const std::span<const RowPoint> points(d.points.data() + (rows.first - d.kept.first),
                                           rows.count);
    return computeMatrixProbeRows(m.mesh, m.occluder, *m.matrix[k0], points, input.transfer_, out,
                                  variance, progress);
  }
  if (!m.perTexel()) {
    const Transfer* in = input.transfer_;
    if (m.haar[k0]) {
      const HaarBounceSource bounce =
          in ? HaarBounceSource{in->values().data(), in->stride()} : HaarBounceSource{};
      return computeHaarRows(m.mesh, m.occluder, *m.haar[k0], rows, bounce, p.shape.stride(), out,
                             variance, progress);
    }
    if (m.vector[k0])
      return computeVectorRows(m.mesh, m.occluder, *m.vector[k0], k, rows, in, p.shape.channels,
                               out, variance, progress);
    return computeMatrixRows(m.mesh, m.occluder, *m.matrix[k0], rows, in, out, variance, progress);
  }
  // Per texel: the rows' covered texels, computed as one run of sample points, then placed at
  // their texels; the texels no triangle covers hold zeros.
  const TexelDomain& d = *m.texels;
  const auto [b, e] = d.samplesIn(rows);
  const std::span<const RowPoint> points(d.points.data() + b, e - b);
  const std::size_t stride = p.shape.stride();
  std::vector<float> values(points.size() * stride);
  std::vector<double> var(points.size());
  const TexelImage image =
      input.image_ ? texelImage(d, *input.image_, input.stride_) : TexelImage{};
  const TexelImage* source = input.image_ ? &image : nullptr;
  // A Haar row reads its own texel of the bounce's sum, laid out as the lightmap.
  const HaarBounceSource bounce =
      input.image_ ? HaarBounceSource{input.image_->data(), input.stride_} : HaarBounceSource{};
  const std::uint64_t rays =
      m.haar[k0]     ? computeHaarTexelRows(m.occluder, *m.haar[k0], points, bounce, stride,
                                            values.data(), var.data(), progress)
      : m.vector[k0] ? computeTexelRows(m.mesh, m.occluder, *m.vector[k0], k, points, source,
                                        p.shape.channels, values.data(), var.data(), progress)
                     : computeMatrixTexelRows(m.mesh, m.occluder, *m.matrix[k0], points, source,
                                              values.data(), var.data(), progress);
  std::fill_n(out, rows.count * stride, 0.0f);
  if (variance) std::fill_n(variance, rows.count, 0.0);
  const auto& s = d.samples.samples;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t r = s[b + i].texel - rows.first;
    std::copy_n(values.data() + i * stride, stride, out + r * stride);
    if (variance) variance[r] = var[i];
  }
  if (progress) progress->advance(rows.count - points.size());
  return rays;
}

void BakePasses::accumulate(int k, RowRange passRows, const float* values, RowRange sumRows,
                            float* sum) const {
  const BakePassInfo& p = pass(k);
  PRT_CHECK(p.summed, "the pass is summed");
  const int nc = p.shape.coeffs();
  const int pc = p.shape.channels, sc = impl_->sumChannels;
  PRT_CHECK(pc == 1 || pc == sc, "pass channels fit the sum");
  int first = 0;  // the first pass summed sets the sum, later ones add
  while (!pass(first).summed) ++first;
  const std::size_t ps = static_cast<std::size_t>(nc) * pc, ss = static_cast<std::size_t>(nc) * sc;
  const RowRange both = overlap(passRows, sumRows);
  for (std::size_t v = both.first; v < both.end(); ++v) {
    const float* a = values + (v - passRows.first) * ps;
    float* s = sum + (v - sumRows.first) * ss;
    if (k == first) {
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

Transfer BakePasses::finish(const Transfer& last, std::vector<std::uint8_t>* filled) const {
  const Impl& m = *impl_;
  if (m.probes) {
    // Probes inside geometry refilled from their neighbours, then cut to the bake's range.
    const std::size_t stride = last.stride();
    std::vector<float> values(last.values().begin(), last.values().end());
    m.probes->refill(values.data(), last.rows(), stride);
    const auto from = std::ptrdiff_t((m.rows.first - last.rows().first) * stride);
    std::vector<float> cut(values.begin() + from,
                           values.begin() + from + std::ptrdiff_t(m.rows.count * stride));
    TransferShape shape = last.shape();
    shape.rows = m.rows;
    return Transfer::dense(shape, FloatArray(std::move(cut)));
  }
  if (!m.perTexel()) {
    PRT_CHECK(last.rows() == m.rows, "the result covers the bake's range");
    return last;
  }
  const TexelDomain& d = *m.texels;
  const std::size_t stride = last.stride();
  std::vector<std::uint8_t> mask;
  std::vector<float> image =
      d.layOut(last.values().data(), last.rows(), stride, rowDilation(last.shape().basis), mask);
  if (d.padding == 0)  // the dilation fed the bounces; without padding the gutter stays empty
    for (std::size_t t = 0; t < d.texels(); ++t)
      if (d.samples.sampleOfTexel[t] < 0) {
        mask[t] = 0;
        std::fill_n(image.begin() + std::ptrdiff_t(t * stride), stride, 0.0f);
      }
  if (filled) *filled = std::move(mask);
  if (m.rows.count < d.texels())
    image = std::vector<float>(image.begin() + std::ptrdiff_t(m.rows.first * stride),
                               image.begin() + std::ptrdiff_t(m.rows.end() * stride));
  TransferShape shape = last.shape();
  shape.rows = m.rows;
  return Transfer::dense(shape, FloatArray(std::move(image)));
}

BakeStats BakePasses::stats(const std::vector<std::uint64_t>& rays,
                            const std::vector<double>& seconds, RowRange varianceRows,
                            const std::vector<double>& variance, double secondsTotal,
                            int threads) const {
  const Impl& m = *impl_;
  PRT_CHECK(rays.size() == m.info.size() && seconds.size() == m.info.size(), "one figure per pass");
  PRT_CHECK(variance.size() == varianceRows.count, "one variance per row");
  // The error estimate over the range's sampled rows: every vertex, the covered texels.
  std::vector<double> sampled;
  const RowRange r = overlap(varianceRows, m.rows);
  for (std::size_t v = r.first; v < r.end(); ++v)
    if (!m.perTexel() || m.texels->samples.sampleOfTexel[v] >= 0)
      sampled.push_back(variance[v - varianceRows.first]);
  BakeStats st;
  if (m.statsKind == StatsKind::Vector) {
    st = vectorStats(rays, seconds, sampled);
  } else if (m.statsKind == StatsKind::HaarBounces) {
    // The direct light: the Haar rows (last) and the bounce's SH direct pass (first).
    std::vector<std::uint64_t> r{rays.back() + rays.front()};
    std::vector<double> sec{seconds.back() + seconds.front()};
    r.insert(r.end(), rays.begin() + 1, rays.end() - 1);
    sec.insert(sec.end(), seconds.begin() + 1, seconds.end() - 1);
    st = vectorStats(r, sec, sampled);
  } else {
    st = matrixStats(m.statsKind == StatsKind::MatrixDiffuse  ? MatrixPassKind::DiffuseBounces
                     : m.statsKind == StatsKind::MatrixGlossy ? MatrixPassKind::GlossyBounces
                                                              : MatrixPassKind::Direct,
                     rays, seconds, sampled, secondsTotal);
  }
  st.threads = threads;
  st.vertices = sampled.size();
  st.secondsTotal = secondsTotal;
  return st;
}

std::string bakeIdentity(const Mesh& mesh, const BakeSettings& s) {
  const std::string hex = meshFingerprint(mesh);
  const RowRange rows = bakeRows(mesh, s);
  std::string domain = "vertices";
  if (s.domain == TransferDomain::Probes) {
    char origin[96];
    std::snprintf(origin, sizeof origin, " from %.9g,%.9g,%.9g", double(s.probes.origin.x),
                  double(s.probes.origin.y), double(s.probes.origin.z));
    domain = s.probes.describe() + origin;
  } else if (s.domain == TransferDomain::Texels) {
    Fnv1a uv;
    uv.addAll(mesh.lightmapUvs);
    domain = "texels of a " + std::to_string(s.lightmap.width) + "x" +
             std::to_string(s.lightmap.height) + " lightmap (padding " +
             std::to_string(s.lightmap.padding) + ", UVs " + uv.hex() + ")";
  }
  std::string adaptive;
  if (s.adaptive()) {
    char e[40];
    std::snprintf(e, sizeof e, "%.17g", s.targetError);
    adaptive = std::string("target error ") + e + ", ";
  }
  return std::to_string(mesh.vertexCount()) + " vertices, " + std::to_string(mesh.triangleCount()) +
         " triangles, mesh " + hex + "; " + toString(s.mode) + " " + toString(s.layout) + ", " +
         (s.basis == TransferBasis::Haar
              ? "Haar " + std::to_string(s.haar.resolution) + "^2 cube, " +
                    std::to_string(s.haar.terms) + " terms, "
              : std::to_string(s.bands) + " bands, ") +
         std::to_string(s.samples) + " samples, " + adaptive +
         std::to_string(s.effectiveBounces()) + " bounces, seed " + std::to_string(s.seed) + ", " +
         toString(s.sampling) + ", " + s.material.spec() + ", " + domain + " " +
         std::to_string(rows.first) + ".." + std::to_string(rows.end());
}

int PassExecutor::threads() const {
  return maxThreads();
}

void PassExecutor::agree(std::exception_ptr failure) {
  if (failure) std::rethrow_exception(failure);
}

PassExecutor::Rows ThreadExecutor::run(const BakePasses& passes, int k, const PassSource& input,
                                       const ProgressFn& progressFn) {
  const auto t0 = Clock::now();
  const BakePassInfo& p = passes.pass(k);
  Rows r;
  r.values = Transfer::zeros(p.shape);
  if (p.variance) r.variance.assign(p.shape.rows.count, 0.0);
  Progress progress(progressFn, p.shape.rows.count);
  r.rays = passes.compute(k, p.shape.rows, input, r.values.mutableValues(),
                          p.variance ? r.variance.data() : nullptr, &progress);
  r.seconds = seconds(t0);
  return r;
}

namespace {

/// The rows of `t` in `rows` (inside t's), as a transfer of its shape.
Transfer cropRows(const Transfer& t, RowRange rows) {
  if (t.rows() == rows) return t;
  TransferShape shape = t.shape();
  shape.rows = rows;
  const std::size_t stride = t.stride();
  const float* v = t.values().data() + (rows.first - t.rows().first) * stride;
  return Transfer::dense(shape, FloatArray(std::vector<float>(v, v + rows.count * stride)));
}

}  // namespace

PassState startPasses(const BakePasses& passes) {
  PassState st;
  const RowRange all{0, passes.domainRows()};
  if (passes.sums()) {
    // Over the domain of the passes it sums (pass 0's: the mesh's vertices for a probe bake).
    TransferShape shape = passes.pass(0).shape;
    shape.layout = TransferLayout::Vector;
    shape.channels = passes.sumChannels();
    shape.rows = {0, shape.domain == TransferDomain::Vertices ? passes.mesh().vertexCount()
                                                               : all.count};
    st.sum = Transfer::zeros(shape);
  }
  st.varianceRows = all;
  st.variance.assign(all.count, 0.0);
  return st;
}

void runPass(const BakePasses& passes, PassExecutor& executor, PassState& state,
             const ProgressFn& progress) {
  const int k = state.done;
  PRT_CHECK(k < passes.count(), "every pass is done");
  const BakePassInfo& p = passes.pass(k);
  const bool last = k == passes.count() - 1;
  const PassSource input =
      passes.prepare(k, p.input == PassInput::Sum ? state.sum : state.previous);
  PassExecutor::Rows r = executor.run(passes, k, input, passes.passProgress(k, progress));
  state.rays.push_back(r.rays);
  state.seconds.push_back(r.seconds);
  const bool held = !r.values.empty();
  const RowRange rows = held ? r.values.rows() : RowRange{p.shape.rows.first, 0};
  // The error estimate: the pass's variances over the rows both cover.
  if (p.variance && !r.variance.empty()) {
    const RowRange both = overlap(rows, state.varianceRows);
    for (std::size_t v = both.first; v < both.end(); ++v)
      state.variance[v - state.varianceRows.first] += r.variance[v - rows.first];
  }
  // The running sum: every pass of a summed bake; the passes before the last of a bake whose
  // last pass reads it.
  if (!state.sum.empty() && held && p.summed && (passes.resultIsSum() || !last))
    passes.accumulate(k, rows, r.values.values().data(), state.sum.rows(),
                      state.sum.mutableValues());
  // From here on the state is of the rows this pass covers here: the sum and the variances
  // narrow to them (the bake's range after its last pass; a job-array shard's rows; nothing on
  // an MPI rank that does not hold the last pass).
  if (!state.sum.empty() && state.sum.domain() == p.shape.domain) {
    const RowRange keep = overlap(rows, state.sum.rows());
    if (keep.count == 0)
      state.sum = Transfer();
    else if (!(keep == state.sum.rows()))
      state.sum = cropRows(state.sum, keep);
  }
  const RowRange keep = overlap(rows, state.varianceRows);
  if (!(keep == state.varianceRows)) {
    std::vector<double> v(
        state.variance.begin() + std::ptrdiff_t(keep.first - state.varianceRows.first),
        state.variance.begin() + std::ptrdiff_t(keep.end() - state.varianceRows.first));
    state.variance = std::move(v);
    state.varianceRows = keep;
  }
  state.previous = std::move(r.values);
  state.done = k + 1;
}

Transfer finishPasses(const BakePasses& passes, const PassState& state, double secondsTotal,
                      int threads, BakeStats* stats, std::vector<std::uint8_t>* filled) {
  PRT_CHECK(state.done == passes.count(), "every pass is done");
  const Transfer& last = passes.resultIsSum() ? state.sum : state.previous;
  if (last.empty()) return Transfer();  // an MPI rank other than 0
  if (stats)
    *stats = passes.stats(state.rays, state.seconds, state.varianceRows, state.variance,
                          secondsTotal, threads);
  return passes.finish(last, filled);
}

Transfer runBakePasses(const BakePasses& passes, PassExecutor& executor, BakeStats* stats,
                       const ProgressFn& progress) {
  const auto start = Clock::now();
  PassState state = startPasses(passes);
  while (state.done < passes.count()) runPass(passes, executor, state, progress);
  return finishPasses(passes, state, seconds(start), executor.threads(), stats);
}

}  // namespace prt

namespace prt {

Transfer bake(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
              PassExecutor& executor, BakeStats* stats, const ProgressFn& progress,
              TexelBakeInfo* texels) {
  const auto start = Clock::now();
  std::unique_ptr<BakePasses> made;
  std::exception_ptr failure;
  try {
    made = std::make_unique<BakePasses>(mesh, occluder, settings, executor.passOptions());
    executor.begin(*made);
  } catch (...) {
    failure = std::current_exception();
  }
  executor.agree(failure);
  const BakePasses& passes = *made;
  PassState state = startPasses(passes);
  while (state.done < passes.count()) runPass(passes, executor, state, progress);
  Transfer t = finishPasses(passes, state, seconds(start), executor.threads(), stats,
                            texels ? &texels->filled : nullptr);
  if (texels) {
    texels->samples = passes.texelSamples();
    texels->inside = passes.texelsInsideGeometry();
  }
  return t;
}

}  // namespace prt
