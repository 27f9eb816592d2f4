#include "prt/transport/lightmap_seam_fix.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/geometry/uv_seams.hpp"

namespace prt {

namespace {

/// One least-squares row: bilinear weights on side A (+) and side B (−), by texel.
using SeamRow = std::vector<std::pair<std::size_t, double>>;

SeamRow seamRow(Vec2f ua, Vec2f ub, int width, int height) {
  SeamRow row;
  const TexelTaps a = bilinearTaps(ua, width, height), b = bilinearTaps(ub, width, height);
  for (int k = 0; k < 4; ++k) {
    row.emplace_back(a.texel[k], double(a.weight[k]));
    row.emplace_back(b.texel[k], -double(b.weight[k]));
  }
  // Taps clamped to one texel, or shared by both sides, count once.
  std::sort(row.begin(), row.end());
  SeamRow merged;
  for (const auto& [t, w] : row)
    if (!merged.empty() && merged.back().first == t)
      merged.back().second += w;
    else
      merged.emplace_back(t, w);
  return merged;
}

}  // namespace

void fixLightmapSeams(const Mesh& mesh, std::span<const Vec2f> uvs, int width, int height,
                      std::span<float> values, std::size_t stride,
                      std::span<const std::uint8_t> free, SeamFixStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t texels = std::size_t(width) * std::size_t(height);
  if (width < 1 || height < 1 || stride == 0 || values.size() != texels * stride ||
      free.size() != texels)
    throw Error(mesh.source, "fixLightmapSeams: buffers do not match the lightmap");
  const std::vector<UvSeamEdge> seams = findUvSeams(mesh, uvs);

  // The rows: kSeamSamplesPerTexel per texel of the edge's longer side in the lightmap.
  std::vector<SeamRow> rows;
  for (const UvSeamEdge& e : seams) {
    const Vec2f a0 = uvs[e.side[0][0]], b0 = uvs[e.side[0][1]];
    const Vec2f a1 = uvs[e.side[1][0]], b1 = uvs[e.side[1][1]];
    const auto texelLength = [&](Vec2f p, Vec2f q) {
      return std::hypot(double(q.x - p.x) * width, double(q.y - p.y) * height);
    };
    const double len = std::max(texelLength(a0, b0), texelLength(a1, b1));
    const int n = std::max(2, int(std::ceil(len * kSeamSamplesPerTexel)));
    for (int i = 0; i < n; ++i) {
      const float s = (float(i) + 0.5f) / float(n);
      const auto lerp = [s](Vec2f p, Vec2f q) {
        return Vec2f{p.x + (q.x - p.x) * s, p.y + (q.y - p.y) * s};
      };
      rows.push_back(seamRow(lerp(a0, b0), lerp(a1, b1), width, height));
    }
  }
  // The unknowns: the free texels any row touches, by texel.
  std::vector<std::size_t> unknowns;
  for (const SeamRow& r : rows)
    for (const auto& [t, w] : r)
      if (free[t]) unknowns.push_back(t);
  std::sort(unknowns.begin(), unknowns.end());
  unknowns.erase(std::unique(unknowns.begin(), unknowns.end()), unknowns.end());
  const auto indexOf = [&](std::size_t t) -> std::ptrdiff_t {
    const auto it = std::lower_bound(unknowns.begin(), unknowns.end(), t);
    return it != unknowns.end() && *it == t ? it - unknowns.begin() : -1;
  };
  if (stats) *stats = {seams.size(), rows.size(), unknowns.size(), 0.0};
  if (unknowns.empty()) return;

  // Normal equations N x = B: N = Σ a aᵀ + λ I over the unknowns; B = λ x₀ − Σ a (a_fixed · v).
  const Eigen::Index n = Eigen::Index(unknowns.size()), m = Eigen::Index(stride);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd rhs(n, m);
  for (Eigen::Index i = 0; i < n; ++i) {
    triplets.emplace_back(i, i, kSeamDataWeight);
    for (Eigen::Index c = 0; c < m; ++c)
      rhs(i, c) = kSeamDataWeight * double(values[unknowns[std::size_t(i)] * stride + c]);
  }
  std::vector<double> fixedPart(stride);
  for (const SeamRow& r : rows) {
    std::fill(fixedPart.begin(), fixedPart.end(), 0.0);
    bool anyFixed = false;
    for (const auto& [t, w] : r)
      if (!free[t]) {
        anyFixed = true;
        for (std::size_t c = 0; c < stride; ++c) fixedPart[c] += w * double(values[t * stride + c]);
      }
    for (const auto& [ti, wi] : r) {
      const std::ptrdiff_t i = indexOf(ti);
      if (i < 0) continue;
      for (const auto& [tj, wj] : r)
        if (const std::ptrdiff_t j = indexOf(tj); j >= 0) triplets.emplace_back(i, j, wi * wj);
      if (anyFixed)
        for (std::size_t c = 0; c < stride; ++c) rhs(i, Eigen::Index(c)) -= wi * fixedPart[c];
    }
  }
  Eigen::SparseMatrix<double> normal(n, n);
  normal.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success)
    throw Error(mesh.source, "the seam fix's least-squares system could not be factorised");
  const Eigen::MatrixXd x = solver.solve(rhs);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index c = 0; c < m; ++c)
      values[unknowns[std::size_t(i)] * stride + std::size_t(c)] = float(x(i, c));
  if (stats)
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Transfer fixLightmapSeams(const Mesh& mesh, std::span<const Vec2f> uvs, const Transfer& transfer,
                          SeamFixStats* stats) {
  const TransferShape& shape = transfer.shape();
  const std::string name = mesh.source.empty() ? "mesh" : mesh.source;
  if (shape.domain != TransferDomain::Texels)
    throw Error(name, "the seam fix is of per-texel transfer");
  if (transfer.compressed())
    throw Error(name, "the seam fix needs dense texels (fix the seams before compressing)");
  const TransferShape::LightmapSize lm = shape.lightmap;
  if (transfer.rows().first != 0 || transfer.rowCount() != lm.texels())
    throw Error(name,
                "the seam fix needs the whole lightmap (a seam joins texels of other ranges: "
                "merge the ranges first)");
  if (uvs.size() != mesh.vertexCount())
    throw Error(name, "the seam fix needs the lightmap UVs the transfer is over");
  std::vector<std::uint8_t> free(lm.texels(), 1);
  if (lm.padding == 0) {
    const TexelSamples s = sampleTexels(mesh, uvs, lm.width, lm.height);
    for (std::size_t t = 0; t < free.size(); ++t) free[t] = s.covered(t) ? 1 : 0;
  }
  std::vector<float> values(transfer.values().begin(), transfer.values().end());
  fixLightmapSeams(mesh, uvs, lm.width, lm.height, values, transfer.stride(), free, stats);
  TransferShape fixed = shape;
  fixed.lightmap.seamsFixed = true;
  return Transfer::dense(fixed, FloatArray(std::move(values)));
}

}  // namespace prt
