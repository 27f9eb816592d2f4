#include "prt/render/lightmap_seams.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/geometry/uv_seams.hpp"

namespace prt::render {

namespace {

constexpr int kPointsPerEdge = 16;

}  // namespace

SeamStats measureSeams(const Mesh& mesh, const Transfer& transfer) {
  const TransferShape& shape = transfer.shape();
  if (shape.domain != TransferDomain::Texels || transfer.rows().first != 0 ||
      transfer.rowCount() != shape.lightmap.texels())
    throw Error(mesh.source, "the seam metric is of a complete per-texel transfer");
  if (mesh.lightmapUvs.size() != mesh.vertexCount())
    throw Error(mesh.source, "the seam metric needs the mesh's lightmap UVs");
  const int W = shape.lightmap.width, H = shape.lightmap.height, C = shape.channels;
  // Exit radiance under a white sky per texel: √(4π) T₀, the mean over channels.
  const Transfer dense = transfer.toDense();
  std::vector<float> white(shape.lightmap.texels());
  const float k = float(std::sqrt(4.0 * 3.14159265358979323846)) / float(C);
  for (std::size_t t = 0; t < white.size(); ++t) {
    float s = 0;
    for (int c = 0; c < C; ++c) s += dense.row(t)[c];
    white[t] = k * s;
  }
  const auto fetch = [&](Vec2f uv) {
    const TexelTaps taps = bilinearTaps(uv, W, H);
    float r = 0;
    for (int k = 0; k < 4; ++k) r += white[taps.texel[k]] * taps.weight[k];
    return r;
  };
  SeamStats st;
  double weighted = 0, sumR = 0, points = 0;
  std::vector<std::pair<double, double>> diffs;  // (|ΔR|, length weight)
  const std::vector<Vec2f>& uv = mesh.lightmapUvs;
  for (const UvSeamEdge& edge : findUvSeams(mesh, uv)) {
    const auto [a0, b0] = edge.side[0];
    const auto [a1, b1] = edge.side[1];
    ++st.edges;
    st.length += edge.length;
    for (int i = 0; i < kPointsPerEdge; ++i) {
      const float s = (float(i) + 0.5f) / kPointsPerEdge;
      const auto lerp = [s](Vec2f p, Vec2f q) {
        return Vec2f{p.x + (q.x - p.x) * s, p.y + (q.y - p.y) * s};
      };
      const float ra = fetch(lerp(uv[a0], uv[b0])), rb = fetch(lerp(uv[a1], uv[b1]));
      diffs.emplace_back(std::abs(double(ra) - double(rb)), edge.length);
      sumR += 0.5 * (double(ra) + double(rb));
      points += 1;
    }
  }
  if (points == 0) return st;
  const double meanR = std::max(sumR / points, 1e-30);
  double wsum = 0;
  for (const auto& [d, w] : diffs) {
    weighted += d * w;
    wsum += w;
    st.maxMismatch = std::max(st.maxMismatch, d / meanR);
  }
  st.mismatch = wsum > 0 ? weighted / wsum / meanR : 0.0;
  return st;
}

}  // namespace prt::render
