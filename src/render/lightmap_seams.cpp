#include "prt/render/lightmap_seams.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/envmap/analytic.hpp"
#include "prt/envmap/sky.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/geometry/uv_seams.hpp"

namespace prt::render {

namespace {

constexpr int kPointsPerEdge = 16;

}  // namespace

std::vector<SeamLight> seamLights(int bands) {
  const envmap::PreethamSky sky{envmap::SkyParams{}};
  return {{"white sky", envmap::constantSh(bands, Rgb(1.0f))},
          {"sun", envmap::directionalSh(bands, sky.sunDirection(), Rgb(1.0f))}};
}

SeamStats measureSeams(const Mesh& mesh, const Transfer& transfer, const sh::RgbSh& light) {
  const TransferShape& shape = transfer.shape();
  if (shape.domain != TransferDomain::Texels || transfer.rows().first != 0 ||
      transfer.rowCount() != shape.lightmap.texels())
    throw Error(mesh.source, "the seam metric is of a complete per-texel transfer");
  if (mesh.lightmapUvs.size() != mesh.vertexCount())
    throw Error(mesh.source, "the seam metric needs the mesh's lightmap UVs");
  if (transfer.isMatrix())
    throw Error(mesh.source, "the seam metric is of vector transfer (matrices shade by normal)");
  const int W = shape.lightmap.width, H = shape.lightmap.height, C = shape.channels;
  const int n = std::min(shape.coeffs(), static_cast<int>(light.c.size()));
  // Exit radiance per texel: Σᵢ Lᵢ Tᵢ per colour, the mean of the three (a scalar transfer
  // serves each colour; an RGB one pairs channel c with colour c).
  const Transfer dense = transfer.toDense();
  std::vector<float> white(shape.lightmap.texels());
  for (std::size_t t = 0; t < white.size(); ++t) {
    const float* row = dense.row(t);
    double s = 0;
    for (int i = 0; i < n; ++i)
      for (int colour = 0; colour < 3; ++colour)
        s += double(light.c[i][colour]) * row[i * C + (C == 3 ? colour : 0)];
    white[t] = float(s / 3.0);
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

SeamStats measureSeams(const Mesh& mesh, const Transfer& transfer) {
  return measureSeams(mesh, transfer, seamLights(transfer.bands()).front().light);
}

}  // namespace prt::render
