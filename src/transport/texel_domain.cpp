#include "texel_domain.hpp"

// The lightmap domain's pieces (see the header). The rule for texels inside geometry
// (texel_validity.hpp): their points are baked like the rest but do not count as covered, so a
// lightmap refills them from valid neighbours wherever one lies within the dilation's reach,
// and they keep their own (dark, hidden) value where none does.

#include <algorithm>

#include "prt/core/parallel.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/transport/texel_validity.hpp"

namespace prt::bakedetail {

RowRange TexelDomain::widen(RowRange range) const {
  if (range.count == 0) return range;
  const std::size_t w = std::size_t(width), ring = std::size_t(rings());
  const std::size_t y0 = range.first / w, y1 = (range.end() - 1) / w;
  const std::size_t lo = (y0 > ring ? y0 - ring : 0) * w,
                    hi = std::min<std::size_t>(std::size_t(height), y1 + ring + 1) * w;
  return {lo, hi - lo};
}

std::pair<std::size_t, std::size_t> TexelDomain::samplesIn(RowRange rows) const {
  const auto& s = samples.samples;
  const auto byTexel = [](const TexelSample& a, std::size_t t) { return a.texel < t; };
  const auto lo = std::lower_bound(s.begin(), s.end(), rows.first, byTexel);
  const auto hi = std::lower_bound(lo, s.end(), rows.end(), byTexel);
  return {std::size_t(lo - s.begin()), std::size_t(hi - s.begin())};
}

std::vector<float> TexelDomain::layOut(const float* values, RowRange rows, std::size_t stride,
                                       TexelDilation dilation,
                                       std::vector<std::uint8_t>& filled) const {
  std::vector<float> image(texels() * stride, 0.0f);
  filled.assign(texels(), 0);
  const auto [b, e] = samplesIn(rows);
  const auto& s = samples.samples;
  const auto row = [&](std::size_t i) { return values + (s[i].texel - rows.first) * stride; };
  for (std::size_t i = b; i < e; ++i) {
    if (inside[i]) continue;
    std::copy_n(row(i), stride, image.begin() + std::ptrdiff_t(s[i].texel * stride));
    filled[s[i].texel] = 1;
  }
  dilateTexels(image, int(stride), filled, width, height, rings(), dilation);
  for (std::size_t i = b; i < e; ++i)
    if (inside[i] && !filled[s[i].texel]) {
      std::copy_n(row(i), stride, image.begin() + std::ptrdiff_t(s[i].texel * stride));
      filled[s[i].texel] = 1;
    }
  return image;
}

TexelDomain makeTexelDomain(const Mesh& mesh, const Occluder& occluder, std::span<const Vec2f> uvs,
                            int width, int height, int padding, RowRange keep) {
  checkLightmapUvs(mesh, uvs, width, height, "the lightmap UV set");
  TexelDomain d;
  d.width = width, d.height = height, d.padding = padding, d.uvs = uvs;
  d.samples = sampleTexels(mesh, uvs, width, height);
  if (keep.count < d.texels()) {
    std::vector<TexelSample> kept;
    for (const TexelSample& t : d.samples.samples)
      if (t.texel >= keep.first && t.texel < keep.end()) kept.push_back(t);
    std::fill(d.samples.sampleOfTexel.begin(), d.samples.sampleOfTexel.end(), -1);
    for (std::size_t i = 0; i < kept.size(); ++i)
      d.samples.sampleOfTexel[kept[i].texel] = static_cast<std::int32_t>(i);
    d.samples.samples = std::move(kept);
  }
  const std::vector<TexelSample>& s = d.samples.samples;
  d.points.resize(s.size());
  parallelFor(s.size(), 256, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      d.points[i] = {samplePosition(mesh, s[i]), sampleNormal(mesh, s[i]), s[i].texel};
  });
  std::vector<Vec3f> positions(s.size()), normals(s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    positions[i] = d.points[i].position, normals[i] = d.points[i].normal;
  d.inside = insideGeometry(mesh, occluder, positions, normals);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (d.inside[i]) d.invalid.push_back(s[i].texel);
  return d;
}

}  // namespace prt::bakedetail
