#include "prt/compress/cpca.hpp"

// Iterative clustered PCA (Sloan, Hall, Hart & Snyder 2003, §4); the algorithm and its
// invariants are stated in the header. Notation: n rows x_p of dimension D, K clusters, N basis
// vectors; all sums over rows run in row order inside fixed chunks so the result does not depend
// on the thread count.

#include <Spectra/SymEigsSolver.h>
#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/sampling.hpp"

namespace prt {

namespace {

using MatrixXfR = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using MatrixXdR = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr std::size_t kChunk = 128;  // rows per fixed chunk (reassignment, reductions)

/// k-means++ seeding (Arthur & Vassilvitskii 2007): the first centre uniform, each next one drawn
/// with probability ∝ squared distance to the nearest centre so far. Returns the rows chosen.
std::vector<std::size_t> seedCentres(const float* x, std::size_t n, std::size_t D, int K,
                                     std::uint64_t seed) {
  Pcg32 rng(seed, 0x6370636173656564ull);  // stream "cpcaseed"
  auto uniformIndex = [&](std::size_t m) {
    const std::uint64_t r = (std::uint64_t(rng.next()) << 32) | rng.next();
    return static_cast<std::size_t>(r % m);
  };
  std::vector<std::size_t> centres{uniformIndex(n)};
  std::vector<float> dist(n, std::numeric_limits<float>::infinity());
  for (int k = 1; k < K; ++k) {
    const float* c = x + centres.back() * D;
    parallelFor(n, 4096, [&](std::size_t b, std::size_t e) {
      for (std::size_t p = b; p < e; ++p) {
        float d = 0;
        for (std::size_t i = 0; i < D; ++i) {
          const float t = x[p * D + i] - c[i];
          d += t * t;
        }
        dist[p] = std::min(dist[p], d);
      }
    });
    double total = 0;
    for (float d : dist) total += d;
    std::size_t pick = 0;
    if (total > 0) {
      const double u = (rng.next() * 0x1p-32 + rng.next() * 0x1p-64) * total;
      double acc = 0;
      pick = n;
      for (std::size_t p = 0; p < n; ++p) {
        acc += dist[p];
        if (acc > u && dist[p] > 0) {
          pick = p;
          break;
        }
      }
      if (pick == n)  // u fell in the rounding slack: the last row with positive distance
        for (std::size_t p = n; p-- > 0;)
          if (dist[p] > 0) {
            pick = p;
            break;
          }
    } else {
      pick = uniformIndex(n);  // every row equals a centre: duplicates are harmless
    }
    centres.push_back(pick);
  }
  return centres;
}

/// Per cluster: mean and N orthonormal principal directions of the member rows (double
/// arithmetic, members in row order). Directions beyond the cluster's rank are zero.
/// The symmetric operator of a cluster's PCA applied without forming the matrix: with Xc the
/// m × D mean-centred rows, y = Xcᵀ(Xc x) (the D × D covariance, up to a factor) or, for the
/// Gram ("snapshot") form, y = Xc(Xcᵀ x) (m × m). 4mD flops per product, against the mD² (or
/// m²D) of forming the matrix — at 9 bands' matrices (D = 6561) forming it is out of reach.
/// The interface is Spectra's (Scalar, rows, cols, perform_op).
class CentredProductOp {
 public:
  using Scalar = double;
  CentredProductOp(const MatrixXdR& xc, bool gram) : xc_(xc), gram_(gram) {
    tmp_.resize(gram ? xc.cols() : xc.rows());
  }
  Eigen::Index rows() const { return gram_ ? xc_.rows() : xc_.cols(); }
  Eigen::Index cols() const { return rows(); }
  void perform_op(const double* in, double* out) const {
    const Eigen::Map<const Eigen::VectorXd> x(in, rows());
    Eigen::Map<Eigen::VectorXd> y(out, rows());
    if (gram_) {
      tmp_.noalias() = xc_.transpose() * x;
      y.noalias() = xc_ * tmp_;
    } else {
      tmp_.noalias() = xc_ * x;
      y.noalias() = xc_.transpose() * tmp_;
    }
  }

 private:
  const MatrixXdR& xc_;
  bool gram_;
  mutable Eigen::VectorXd tmp_;
};

/// Operators of this order or smaller are solved whole (Eigen's SelfAdjointEigenSolver, O(n³)
/// but with no iteration to converge); larger ones by Lanczos for the top N only.
constexpr Eigen::Index kDenseEigenMax = 128;

/// The top `count` eigenpairs (eigenvalues descending, eigenvectors as columns) of the
/// operator, by Spectra's implicitly restarted Lanczos (SymEigsSolver; its starting vector is
/// a fixed-seed pseudo-random one, so the result is deterministic). Returns false when it does
/// not converge (the caller then solves the whole matrix).
bool topEigenpairs(CentredProductOp& op, int count, Eigen::VectorXd& values,
                   Eigen::MatrixXd& vectors) {
  const Eigen::Index n = op.rows();
  const Eigen::Index ncv =
      std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * count + 1, count + 20));
  Spectra::SymEigsSolver<CentredProductOp> eigs(op, count, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, 1000, 1e-10);
  if (eigs.info() != Spectra::CompInfo::Successful) return false;
  values = eigs.eigenvalues();
  vectors = eigs.eigenvectors();
  return true;
}

void fitClusters(const float* x, std::size_t n, std::size_t D, int K, int N,
                 const std::vector<std::uint32_t>& assign, std::vector<float>& means,
                 std::vector<float>& basis) {
  // Members of each cluster in row order (a counting sort: deterministic).
  std::vector<std::size_t> start(static_cast<std::size_t>(K) + 1, 0), members(n);
  for (std::size_t p = 0; p < n; ++p) ++start[assign[p] + 1];
  for (int k = 0; k < K; ++k) start[k + 1] += start[k];
  {
    std::vector<std::size_t> at(start.begin(), start.end() - 1);
    for (std::size_t p = 0; p < n; ++p) members[at[assign[p]]++] = p;
  }
  means.assign(static_cast<std::size_t>(K) * D, 0.0f);
  basis.assign(static_cast<std::size_t>(K) * N * D, 0.0f);
  parallelFor(static_cast<std::size_t>(K), 1, [&](std::size_t kb, std::size_t ke) {
    for (std::size_t k = kb; k < ke; ++k) {
      const std::size_t m = start[k + 1] - start[k];
      if (m == 0) continue;
      const std::size_t* mem = members.data() + start[k];
      Eigen::VectorXd mean = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(D));
      for (std::size_t r = 0; r < m; ++r)
        for (std::size_t i = 0; i < D; ++i) mean[i] += x[mem[r] * D + i];
      mean /= static_cast<double>(m);
      for (std::size_t i = 0; i < D; ++i) means[k * D + i] = static_cast<float>(mean[i]);
      if (N == 0 || m < 2) continue;
      MatrixXdR xc(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(D));
      for (std::size_t r = 0; r < m; ++r)
        for (std::size_t i = 0; i < D; ++i) xc(r, i) = x[mem[r] * D + i] - mean[i];
      float* bk = basis.data() + k * static_cast<std::size_t>(N) * D;
      // Large operators: the top N by Lanczos, on the covariance (m ≥ D) or the Gram matrix.
      const bool gram = m < D;
      const Eigen::Index order = static_cast<Eigen::Index>(std::min(m, D));
      if (order > kDenseEigenMax && N < order) {
        CentredProductOp op(xc, gram);
        Eigen::VectorXd values;
        Eigen::MatrixXd vectors;
        if (topEigenpairs(op, N, values, vectors)) {
          const double top = std::max(values[0], 0.0);
          for (int j = 0; j < N; ++j) {
            if (!(values[j] > 1e-12 * top)) break;  // rank reached: the rest stay zero
            Eigen::VectorXd v = vectors.col(j);
            if (gram) v = xc.transpose() * v;  // B = Xcᵀu / |Xcᵀu|
            v.normalize();
            for (std::size_t i = 0; i < D; ++i) bk[j * D + i] = static_cast<float>(v[i]);
          }
          continue;
        }
      }
      if (m >= D) {
        // Covariance (unnormalised: the eigenvectors are the same) Cᵀ = Xcᵀ Xc, D × D.
        Eigen::MatrixXd cov = xc.transpose() * xc;
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(cov);
        // Eigenvalues ascend: the top N are the last columns.
        for (int j = 0; j < N; ++j) {
          const auto v = es.eigenvectors().col(static_cast<Eigen::Index>(D) - 1 - j);
          for (std::size_t i = 0; i < D; ++i) bk[j * D + i] = static_cast<float>(v[i]);
        }
      } else {
        // Gram ("snapshot") trick: Xc Xcᵀ u = λ u  ⇒  (Xcᵀ Xc)(Xcᵀ u) = λ (Xcᵀ u), m × m.
        Eigen::MatrixXd gram = xc * xc.transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(gram);
        const double top = std::max(es.eigenvalues()[static_cast<Eigen::Index>(m) - 1], 0.0);
        for (int j = 0; j < N && static_cast<std::size_t>(j) < m; ++j) {
          const Eigen::Index c = static_cast<Eigen::Index>(m) - 1 - j;
          if (!(es.eigenvalues()[c] > 1e-12 * top)) break;  // rank reached: the rest stay zero
          Eigen::VectorXd v = xc.transpose() * es.eigenvectors().col(c);
          v.normalize();
          for (std::size_t i = 0; i < D; ++i) bk[j * D + i] = static_cast<float>(v[i]);
        }
      }
    }
  });
}

/// out (m × S) = X (m × D) · stackT (D × S), four rows at a time as outer products: each output
/// is summed over i = 0..D−1 in order whatever the chunking, so results do not depend on the
/// thread count, and the inner loop over S vectorises without reassociation. Compiled for
/// AVX2 and for the baseline, picked at load time (as relight's kernels); -ffp-contract=off
/// (ISO C++) keeps the two bit-identical.
[[gnu::target_clones("arch=haswell", "default")]] void chunkProducts(const float* __restrict x,
                                                                     std::size_t m, std::size_t D,
                                                                     const float* __restrict stackT,
                                                                     std::size_t S,
                                                                     float* __restrict out) {
  std::size_t r = 0;
  for (; r + 4 <= m; r += 4) {
    float* __restrict o0 = out + r * S;
    float* __restrict o1 = o0 + S;
    float* __restrict o2 = o1 + S;
    float* __restrict o3 = o2 + S;
    std::fill_n(o0, 4 * S, 0.0f);
    for (std::size_t i = 0; i < D; ++i) {
      const float a0 = x[r * D + i], a1 = x[(r + 1) * D + i], a2 = x[(r + 2) * D + i],
                  a3 = x[(r + 3) * D + i];
      const float* __restrict s = stackT + i * S;
      for (std::size_t j = 0; j < S; ++j) {
        o0[j] += a0 * s[j];
        o1[j] += a1 * s[j];
        o2[j] += a2 * s[j];
        o3[j] += a3 * s[j];
      }
    }
  }
  for (; r < m; ++r) {
    float* __restrict o = out + r * S;
    std::fill_n(o, S, 0.0f);
    for (std::size_t i = 0; i < D; ++i) {
      const float a = x[r * D + i];
      const float* __restrict s = stackT + i * S;
      for (std::size_t j = 0; j < S; ++j) o[j] += a * s[j];
    }
  }
}

/// Squared reconstruction error of every row in every cluster, the best cluster per row (the
/// current one kept on ties). Via one product per chunk: with P = X [M B]ᵀ,
///   e_k(x) = |x − M_k|² − Σ_j (B_kj·x − B_kj·M_k)².
/// Returns how many rows moved; rowError gets each row's error in its (new) cluster.
std::size_t reassign(const float* x, std::size_t n, std::size_t D, int K, int N,
                     const std::vector<float>& means, const std::vector<float>& basis,
                     std::vector<std::uint32_t>& assign, std::vector<float>& rowError) {
  const std::size_t W = static_cast<std::size_t>(N) + 1;
  // Stacked per cluster: row k·W = M_k, rows k·W + 1 + j = B_kj.
  MatrixXfR stack(static_cast<Eigen::Index>(K * W), static_cast<Eigen::Index>(D));
  for (int k = 0; k < K; ++k) {
    std::copy_n(means.data() + k * D, D, stack.row(k * W).data());
    for (int j = 0; j < N; ++j)
      std::copy_n(basis.data() + (static_cast<std::size_t>(k) * N + j) * D, D,
                  stack.row(k * W + 1 + j).data());
  }
  // Per cluster: |M_k|² and c_kj = B_kj·M_k.
  std::vector<double> mm(static_cast<std::size_t>(K)), c(static_cast<std::size_t>(K) * N);
  for (int k = 0; k < K; ++k) {
    mm[k] = stack.row(k * W).cast<double>().squaredNorm();
    for (int j = 0; j < N; ++j)
      c[k * N + j] = stack.row(k * W + 1 + j).cast<double>().dot(stack.row(k * W).cast<double>());
  }
  const std::size_t S = static_cast<std::size_t>(K) * W;
  std::vector<float> stackT(D * S);
  for (std::size_t s = 0; s < S; ++s)
    for (std::size_t i = 0; i < D; ++i) stackT[i * S + s] = stack(static_cast<Eigen::Index>(s), i);
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::size_t> moved(chunks, 0);
  parallelFor(chunks, 1, [&](std::size_t cb, std::size_t ce) {
    MatrixXfR prod(static_cast<Eigen::Index>(kChunk), static_cast<Eigen::Index>(S));
    for (std::size_t ch = cb; ch < ce; ++ch) {
      const std::size_t lo = ch * kChunk, m = std::min(kChunk, n - lo);
      chunkProducts(x + lo * D, m, D, stackT.data(), S, prod.data());
      for (std::size_t r = 0; r < m; ++r) {
        const std::size_t p = lo + r;
        double xx = 0;
        for (std::size_t i = 0; i < D; ++i) xx += double(x[p * D + i]) * x[p * D + i];
        auto err = [&](std::size_t k) {
          double e = xx - 2.0 * prod(r, k * W) + mm[k];
          for (int j = 0; j < N; ++j) {
            const double t = prod(r, k * W + 1 + j) - c[k * N + j];
            e -= t * t;
          }
          return std::max(e, 0.0);
        };
        std::uint32_t best = assign[p];
        double bestErr = err(best);
        for (int k = 0; k < K; ++k) {
          const double e = err(static_cast<std::size_t>(k));
          if (e < bestErr) {
            bestErr = e;
            best = static_cast<std::uint32_t>(k);
          }
        }
        if (best != assign[p]) ++moved[ch];
        assign[p] = best;
        rowError[p] = static_cast<float>(bestErr);
      }
    }
  });
  std::size_t total = 0;
  for (std::size_t m : moved) total += m;
  return total;
}

/// Gives every empty cluster the row of largest error (lowest index on ties) from a cluster that
/// keeps at least one row. Returns how many rows moved.
std::size_t refillEmpty(int K, std::vector<std::uint32_t>& assign, std::vector<float>& rowError) {
  std::vector<std::size_t> size(static_cast<std::size_t>(K), 0);
  for (std::uint32_t a : assign) ++size[a];
  std::size_t moved = 0;
  for (int k = 0; k < K; ++k) {
    if (size[k] != 0) continue;
    std::size_t worst = assign.size();
    for (std::size_t p = 0; p < assign.size(); ++p)
      if (size[assign[p]] > 1 && (worst == assign.size() || rowError[p] > rowError[worst]))
        worst = p;
    if (worst == assign.size()) break;  // fewer distinct rows than clusters
    --size[assign[worst]];
    assign[worst] = static_cast<std::uint32_t>(k);
    size[k] = 1;
    rowError[worst] = 0;
    ++moved;
  }
  return moved;
}

}  // namespace

CpcaStats measureCpca(const Transfer& field, const Transfer& c) {
  if (field.compressed()) throw Error("compress: the source transfer must be dense");
  if (field.shape() != c.shape())
    throw Error("compress: the compressed transfer has another shape than its source");
  const std::size_t D = field.stride(), n = field.rowCount();
  struct Acc {
    double err = 0, energy = 0, maxRow = 0;
  };
  const Acc a = parallelReduce(
      n, 1024, Acc{},
      [&](std::size_t b, std::size_t e, Acc& acc) {
        std::vector<float> row(D);
        for (std::size_t v = b; v < e; ++v) {
          c.reconstructRow(v, row.data());
          double rowErr = 0;
          for (std::size_t i = 0; i < D; ++i) {
            const double t = double(field.row(v)[i]) - row[i];
            rowErr += t * t;
            acc.energy += double(field.row(v)[i]) * field.row(v)[i];
          }
          acc.err += rowErr;
          acc.maxRow = std::max(acc.maxRow, std::sqrt(rowErr));
        }
      },
      [](Acc& t, const Acc& p) {
        t.err += p.err;
        t.energy += p.energy;
        t.maxRow = std::max(t.maxRow, p.maxRow);
      });
  CpcaStats s;
  s.squaredError = a.err;
  s.signalEnergy = a.energy;
  s.relativeRms = a.energy > 0 ? std::sqrt(a.err / a.energy) : 0;
  s.snrDb =
      a.err > 0 ? 10.0 * std::log10(a.energy / a.err) : std::numeric_limits<double>::infinity();
  s.maxRowError = a.maxRow;
  s.compressionRatio = static_cast<double>(4 * n * D) / static_cast<double>(c.bytes());
  return s;
}

Transfer compressCpca(const Transfer& field, const CpcaOptions& o, CpcaStats* stats,
                      const Transfer* start, const ProgressFn& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (field.compressed()) throw Error("compress: the transfer is already compressed");
  const std::size_t n = field.rowCount(), D = field.stride();
  if (n == 0) throw Error("compress: the transfer has no rows");
  if (o.clusters < 1 || static_cast<std::size_t>(o.clusters) > n)
    throw Error("compress: " + std::to_string(o.clusters) + " clusters for " + std::to_string(n) +
                " rows (need 1 to the row count)");
  if (o.basisCount < 0 || static_cast<std::size_t>(o.basisCount) > D)
    throw Error("compress: " + std::to_string(o.basisCount) +
                " basis vectors (need 0 to the row dimension, " + std::to_string(D) + ")");
  if (o.maxIterations < 0) throw Error("compress: negative iteration count");
  const int K = o.clusters, N = o.basisCount;
  const float* x = field.values().data();

  // The fit's working arrays; they become the transfer's CPCA rows at the end.
  struct {
    std::vector<float> means, basis, weights;
  } c;
  std::vector<std::uint32_t> assign;
  std::vector<float> rowError(n, 0.0f);

  if (start) {
    if (!start->compressed() || start->shape() != field.shape() || start->cpca().clusters != K)
      throw Error("compress: the warm start has another shape or cluster count");
    assign = start->cpca().cluster;
  } else {
    // Seed: the k-means++ centres as means, no basis; one reassignment = nearest centre.
    const std::vector<std::size_t> centres = seedCentres(x, n, D, K, o.seed);
    std::vector<float> means(static_cast<std::size_t>(K) * D), none;
    for (int k = 0; k < K; ++k) std::copy_n(x + centres[k] * D, D, means.data() + k * D);
    assign.assign(n, 0);
    reassign(x, n, D, K, 0, means, none, assign, rowError);
    refillEmpty(K, assign, rowError);
  }

  fitClusters(x, n, D, K, N, assign, c.means, c.basis);
  int it = 0;
  double lastError = std::numeric_limits<double>::infinity();
  while (it < o.maxIterations) {
    if (progress && !progress(static_cast<double>(it) / o.maxIterations)) throw Cancelled();
    ++it;
    std::size_t moved = reassign(x, n, D, K, N, c.means, c.basis, assign, rowError);
    // The error of this pass's assignment under the current bases (row order: deterministic).
    double error = 0;
    for (float e : rowError) error += e;
    moved += refillEmpty(K, assign, rowError);
    if (moved == 0) break;
    fitClusters(x, n, D, K, N, assign, c.means, c.basis);
    if (std::isfinite(lastError) && lastError - error <= o.tolerance * lastError)
      break;  // converged (refit done)
    lastError = error;
  }
  if (progress && !progress(1.0)) throw Cancelled();

  // Weights w_pj = B_kj·(x_p − M_k), in double.
  c.weights.assign(n * static_cast<std::size_t>(N), 0.0f);
  if (N > 0)
    parallelFor(n, 1024, [&](std::size_t b, std::size_t e) {
      for (std::size_t p = b; p < e; ++p) {
        const std::size_t k = assign[p];
        for (int j = 0; j < N; ++j) {
          const float* bv = c.basis.data() + (k * N + j) * D;
          double w = 0;
          for (std::size_t i = 0; i < D; ++i)
            w += double(bv[i]) * (x[p * D + i] - c.means[k * D + i]);
          c.weights[p * N + j] = static_cast<float>(w);
        }
      }
    });
  CpcaRows rows;
  rows.clusters = K;
  rows.basisCount = N;
  rows.cluster = std::move(assign);
  rows.weights = FloatArray(std::move(c.weights));
  rows.means = FloatArray(std::move(c.means));
  rows.basis = FloatArray(std::move(c.basis));
  Transfer out = Transfer::cpca(field.shape(), std::move(rows));
  if (stats) {
    *stats = measureCpca(field, out);
    stats->iterations = it;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return out;
}

std::vector<CpcaSweepPoint> sweepCpca(const Transfer& field, const std::vector<int>& clusters,
                                      int maxBasis, const CpcaFit& fit, double stopAtError,
                                      const ProgressFn& progress) {
  std::vector<CpcaSweepPoint> points;
  const double total = static_cast<double>(clusters.size()) * (maxBasis + 1);
  std::size_t done = 0;
  for (int K : clusters) {
    Transfer prev;
    for (int N = 0; N <= maxBasis; ++N, ++done) {
      if (progress && !progress(done / total)) throw Cancelled();
      CpcaSweepPoint p;
      p.clusters = K;
      p.basisCount = N;
      CpcaOptions o;
      static_cast<CpcaFit&>(o) = fit;
      o.clusters = K;
      o.basisCount = N;
      Transfer c = compressCpca(field, o, &p.stats, N > 0 ? &prev : nullptr);
      p.bytes = c.bytes();
      points.push_back(p);
      prev = std::move(c);
      if (stopAtError > 0 && p.stats.relativeRms <= stopAtError) {
        done += static_cast<std::size_t>(maxBasis - N);
        break;
      }
    }
  }
  return points;
}

Transfer compressCpcaChain(const Transfer& source, const CpcaOptions& o, CpcaStats& stats,
                           const ProgressFn& progress) {
  Transfer prev;
  double seconds = 0;
  for (int n = 0; n <= o.basisCount; ++n) {
    if (progress && !progress(static_cast<double>(n) / (o.basisCount + 1))) throw Cancelled();
    CpcaOptions step = o;
    step.basisCount = n;
    Transfer c = compressCpca(source, step, &stats, n > 0 ? &prev : nullptr);
    seconds += stats.seconds;
    prev = std::move(c);
  }
  stats.seconds = seconds;
  return prev;
}

}  // namespace prt
