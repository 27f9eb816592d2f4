#include "prt/transfer/transfer.hpp"

#include <algorithm>
#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/transfer/haar_rows.hpp"

namespace prt {

namespace {

/// The first b bands of one row of `from` (stride floats) into `to` (the cut stride): vectors the
/// first b²·C values, matrices the leading b² × b² block of every B² × B² row.
void cutRow(const TransferShape& from, int b, const float* src, float* dst) {
  const std::size_t c = static_cast<std::size_t>(from.channels);
  const std::size_t nb = static_cast<std::size_t>(b * b);
  if (from.layout == TransferLayout::Vector) {
    std::copy_n(src, nb * c, dst);
    return;
  }
  const std::size_t nB = static_cast<std::size_t>(from.coeffs());
  for (std::size_t i = 0; i < nb; ++i) std::copy_n(src + i * nB * c, nb * c, dst + i * nb * c);
}

/// `count` rows of `from` cut to b bands (each of from.stride() floats in, the cut stride out).
FloatArray cutRows(const TransferShape& from, int b, const float* src, std::size_t count) {
  const std::size_t in = from.stride(), out = from.withBands(b).stride();
  std::vector<float> dst(count * out);
  parallelFor(count, 1024, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t r = lo; r < hi; ++r) cutRow(from, b, src + r * in, dst.data() + r * out);
  });
  return FloatArray(std::move(dst));
}

void requireFinite(const FloatArray& a, const std::string& what, const char* name,
                   std::size_t stride) {
  const float* p = a.data();
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!std::isfinite(p[i]))
      throw Error(what, std::string("the transfer's ") + name + " hold a non-finite value (" +
                            (stride ? "row " + std::to_string(i / stride) + ", " : "") +
                            "element " + std::to_string(i) + ")");
}

}  // namespace

Transfer Transfer::zeros(const TransferShape& shape) {
  return dense(shape, FloatArray::zeros(shape.rows.count * shape.stride()));
}

Transfer Transfer::dense(const TransferShape& shape, FloatArray values) {
  if (values.size() != shape.rows.count * shape.stride())
    throw Error("transfer: " + std::to_string(values.size()) + " values for " +
                std::to_string(shape.rows.count) + " rows of " + std::to_string(shape.stride()));
  Transfer t;
  t.shape_ = shape;
  t.representation_ = Representation::Dense;
  t.values_ = std::move(values);
  return t;
}

Transfer Transfer::cpca(const TransferShape& shape, CpcaRows rows) {
  const std::size_t D = shape.stride(), n = shape.rows.count;
  // (N may exceed D: a compressed transfer cut to fewer bands keeps its N weights per row.)
  if (rows.clusters < 1 || rows.basisCount < 0)
    throw Error("transfer: " + std::to_string(rows.clusters) + " clusters and " +
                std::to_string(rows.basisCount) + " basis vectors");
  const std::size_t K = static_cast<std::size_t>(rows.clusters),
                    N = static_cast<std::size_t>(rows.basisCount);
  if (rows.cluster.size() != n || rows.weights.size() != n * N || rows.means.size() != K * D ||
      rows.basis.size() != K * N * D)
    throw Error("transfer: the compressed arrays do not match the shape (" + shape.describe() +
                ")");
  Transfer t;
  t.shape_ = shape;
  t.representation_ = Representation::Cpca;
  t.cpca_ = std::move(rows);
  return t;
}

const FloatArray& Transfer::values() const {
  PRT_CHECK(representation_ == Representation::Dense, "dense values of a compressed transfer");
  return values_;
}

float* Transfer::mutableValues() {
  PRT_CHECK(representation_ == Representation::Dense, "dense values of a compressed transfer");
  return values_.mutableData();
}

const CpcaRows& Transfer::cpca() const {
  PRT_CHECK(representation_ == Representation::Cpca, "compressed rows of a dense transfer");
  return cpca_;
}

const float* Transfer::clusterMean(std::size_t k) const {
  return cpca().means.data() + k * stride();
}

const float* Transfer::basisVector(std::size_t k, std::size_t j) const {
  return cpca().basis.data() + (k * static_cast<std::size_t>(cpca_.basisCount) + j) * stride();
}

void Transfer::reconstructRow(std::size_t r, float* out) const {
  const std::size_t D = stride();
  if (representation_ == Representation::Dense) {
    std::copy_n(row(r), D, out);
    return;
  }
  // x̂ = M_k + Σ_j w_rj B_kj, summed in j order for every value (the order every kernel and
  // the fitting's error measure use).
  const std::size_t k = cpca_.cluster[r], N = static_cast<std::size_t>(cpca_.basisCount);
  const float* m = clusterMean(k);
  const float* w = cpca_.weights.data() + r * N;
  for (std::size_t i = 0; i < D; ++i) {
    float s = m[i];
    for (std::size_t j = 0; j < N; ++j) s += w[j] * basisVector(k, j)[i];
    out[i] = s;
  }
}

Transfer Transfer::cut(int b) const {
  PRT_CHECK(!isHaar(), "a Haar transfer has no bands to cut");
  PRT_CHECK(b >= 1 && b <= bands(), "cut to more bands than the transfer holds");
  if (b == bands()) return *this;
  const TransferShape to = shape_.withBands(b);
  if (representation_ == Representation::Dense)
    return dense(to, cutRows(shape_, b, values_.data(), rowCount()));
  // Compressed: the ids and weights as they are, every mean and basis vector cut.
  CpcaRows c;
  c.clusters = cpca_.clusters;
  c.basisCount = cpca_.basisCount;
  c.cluster = cpca_.cluster;
  c.weights = cpca_.weights;
  const std::size_t K = static_cast<std::size_t>(c.clusters),
                    N = static_cast<std::size_t>(c.basisCount);
  c.means = cutRows(shape_, b, cpca_.means.data(), K);
  c.basis = cutRows(shape_, b, cpca_.basis.data(), K * N);
  return cpca(to, std::move(c));
}

Transfer Transfer::toDense() const {
  if (representation_ == Representation::Dense) return *this;
  std::vector<float> values(rowCount() * stride());
  parallelFor(rowCount(), 1024, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t r = lo; r < hi; ++r) reconstructRow(r, values.data() + r * stride());
  });
  return dense(shape_, FloatArray(std::move(values)));
}

std::size_t Transfer::bytes() const {
  if (shape_.isHaar())
    return rowCount() * (haar::storedHaarRowBytes(shape_.haar.resolution, shape_.haar.terms) +
                         4 * shape_.haarBounceFloats());
  if (representation_ == Representation::Dense) return shape_.denseBytes();
  const std::size_t id = cpca_.clusters <= 65536 ? 2 : 4;
  const std::size_t N = static_cast<std::size_t>(cpca_.basisCount);
  return rowCount() * (id + 4 * N) +
         4 * static_cast<std::size_t>(cpca_.clusters) * (N + 1) * stride();
}

void Transfer::check(const std::string& what) const {
  shape_.check(what);
  if (representation_ == Representation::Dense) {
    if (values_.size() != rowCount() * stride())
      throw Error(what, "the transfer holds " + std::to_string(values_.size()) +
                            " values, expected " + std::to_string(rowCount() * stride()));
    if (shape_.isHaar()) {
      const std::size_t bounce = shape_.haarBounceOffset(), n = shape_.haarBounceFloats();
      for (std::size_t r = 0; r < rowCount(); ++r) {
        const float* row = values_.data() + r * stride();
        haar::checkRow(row, shape_.haar.resolution, static_cast<std::size_t>(shape_.haar.terms), r,
                       what);
        for (std::size_t i = 0; i < n; ++i)
          if (!std::isfinite(row[bounce + i]))
            throw Error(what, "row " + std::to_string(r) + ": bounce value " + std::to_string(i) +
                                  " is not finite");
      }
      return;
    }
    requireFinite(values_, what, "rows", stride());
    return;
  }
  const std::size_t K = static_cast<std::size_t>(cpca_.clusters);
  for (std::size_t r = 0; r < cpca_.cluster.size(); ++r)
    if (cpca_.cluster[r] >= K)
      throw Error(what, "row " + std::to_string(r) + " names cluster " +
                            std::to_string(cpca_.cluster[r]) + " of " + std::to_string(K));
  requireFinite(cpca_.weights, what, "CPCA weights", 0);
  requireFinite(cpca_.means, what, "CPCA cluster means", 0);
  requireFinite(cpca_.basis, what, "CPCA basis vectors", 0);
}

Transfer Transfer::withFirstRow(std::size_t first) const {
  Transfer t = *this;
  t.shape_.rows.first = first;
  return t;
}

}  // namespace prt
