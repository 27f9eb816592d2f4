#include "prt/unwrap/lscm.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

namespace prt {

std::vector<Uv2> lscm(std::span<const Vec3d> p,
                      std::span<const std::array<std::uint32_t, 3>> triangles) {
  const std::size_t n = p.size();
  if (n < 3 || triangles.empty()) return {};
  // Pins: the extreme vertices along the longest axis of the bounding box (Lévy et al. §5.2),
  // the lowest index on ties.
  Vec3d lo = p[0], hi = p[0];
  for (const Vec3d& q : p) lo = min(lo, q), hi = max(hi, q);
  const Vec3d ext = hi - lo;
  const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
  std::size_t a = 0, b = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (p[i][axis] < p[a][axis]) a = i;
    if (p[i][axis] > p[b][axis]) b = i;
  }
  if (a == b) return {};
  std::vector<Uv2> uv(n, Uv2{0, 0});
  uv[b] = {length(p[b] - p[a]), 0};
  std::vector<int> col(n, -1);
  int free = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (i != a && i != b) col[i] = free++;

  // Local frames; a triangle is "without area" below 1e-10 of the chart's mean doubled area.
  struct Local {
    double x[3], y[3], weight;
  };
  std::vector<Local> local(triangles.size());
  double meanArea2 = 0, meanEdge = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Vec3d e1 = p[tri[1]] - p[tri[0]], e2 = p[tri[2]] - p[tri[0]];
    meanArea2 += length(cross(e1, e2));
    meanEdge += length(e1) + length(e2) + length(p[tri[2]] - p[tri[1]]);
  }
  meanArea2 /= double(triangles.size());
  meanEdge /= 3.0 * double(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Vec3d e1 = p[tri[1]] - p[tri[0]], e2 = p[tri[2]] - p[tri[0]];
    const double len1 = length(e1), area2 = length(cross(e1, e2));
    Local& L = local[t];
    if (area2 > 1e-10 * meanArea2 && len1 > 0) {
      // x along e1, y in the triangle's plane towards the third corner: d_T = x1 y2.
      L = {{0, len1, dot(e2, e1) / len1}, {0, 0, area2 / len1}, 1.0 / std::sqrt(area2)};
    } else {
      const double s = meanEdge > 0 ? meanEdge : 1.0;
      const double h = s * std::sqrt(3.0) / 2;
      L = {{0, s, s / 2}, {0, 0, h}, 1e-3 / std::sqrt(s * h)};
    }
  }

  using Triplet = Eigen::Triplet<double>;
  std::vector<Triplet> entries;
  entries.reserve(triangles.size() * 12);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(Eigen::Index(2 * triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Local& L = local[t];
    const int r = int(2 * t);
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      const double wa = (L.x[k2] - L.x[k1]) * L.weight, wb = (L.y[k2] - L.y[k1]) * L.weight;
      const std::uint32_t j = triangles[t][k];
      if (col[j] >= 0) {
        entries.emplace_back(r, 2 * col[j], wa);
        entries.emplace_back(r, 2 * col[j] + 1, -wb);
        entries.emplace_back(r + 1, 2 * col[j], wb);
        entries.emplace_back(r + 1, 2 * col[j] + 1, wa);
      } else {
        rhs[r] -= wa * uv[j][0] - wb * uv[j][1];
        rhs[r + 1] -= wb * uv[j][0] + wa * uv[j][1];
      }
    }
  }
  // The normal equations; A, Aᵀ, the triplets and the frames are let go before the
  // factorisation, which needs the most memory (its fill: the solve peaks at about 1.5 kB per
  // triangle of a 500k-triangle chart): they held about 0.5 kB per triangle that would
  // otherwise sit beside it (issue 31: a 500k-triangle plane peaked at 1.13 GB, now 0.90 GB).
  Eigen::SparseMatrix<double> AtA;
  Eigen::VectorXd Atb;
  {
    Eigen::SparseMatrix<double> A(Eigen::Index(2 * triangles.size()), 2 * free);
    A.setFromTriplets(entries.begin(), entries.end());
    std::vector<Triplet>().swap(entries);
    std::vector<Local>().swap(local);
    const Eigen::SparseMatrix<double> At = A.transpose();
    AtA = At * A;
    Atb = At * rhs;
  }
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(AtA);
  if (solver.info() != Eigen::Success) return {};
  const Eigen::VectorXd x = solver.solve(Atb);
  if (solver.info() != Eigen::Success || !x.allFinite()) return {};
  // A singular system (part of the chart hanging on a vertex) factors with a zero pivot that
  // LDLᵀ does not report: check the solution satisfies the normal equations.
  const double residual = (AtA * x - Atb).norm(), scale = Atb.norm() + 1e-300;
  if (!(residual <= 1e-6 * scale)) return {};
  for (std::size_t i = 0; i < n; ++i)
    if (col[i] >= 0) uv[i] = {x[2 * col[i]], x[2 * col[i] + 1]};
  return uv;
}

}  // namespace prt
