#pragma once
// The lightmap domain of a bake (prt/transport/bake_texels.hpp), private to src/transport: where
// its rows are integrated (one sample point per covered texel), which of those points lie
// inside geometry, and how a pass over texel rows becomes the dilated lightmap a bounce or the
// result reads. passes.cpp asks it at its dispatch points; nothing else branches on texels.

#include <cstdint>
#include <span>
#include <vector>

#include "bake_common.hpp"
#include "prt/geometry/texel_sampling.hpp"

namespace prt::bakedetail {

struct TexelDomain {
  int width = 0, height = 0;
  int padding = 0;  ///< rings of gutter the result is dilated into
  std::span<const Vec2f> uvs;
  /// The covered texels kept (those the passes compute: all, or a range's widened by the
  /// dilation's reach), in texel order, with their points and inside-geometry flags.
  TexelSamples samples;
  std::vector<RowPoint> points;
  std::vector<std::uint8_t> inside;
  std::vector<std::uint32_t> invalid;  ///< texels of the points inside geometry, ascending

  std::size_t texels() const { return std::size_t(width) * std::size_t(height); }
  /// Rings a pass is dilated by before another reads it (at least one, so that a bilinear tap
  /// at a chart's edge reads its neighbour even without padding).
  int rings() const { return padding > 0 ? padding : 1; }
  /// `range` widened to whole texel rows `rings()` above and below: every texel the dilation
  /// of the range's texels reads.
  RowRange widen(RowRange range) const;
  /// The samples of texels in `rows`: [first, end) indices into samples.samples.
  std::pair<std::size_t, std::size_t> samplesIn(RowRange rows) const;
  /// `values` (rows `rows` of texels, `stride` floats each) laid out as the whole lightmap:
  /// the texels of points outside geometry set and dilated rings() rings; points inside
  /// geometry that no dilation reached keep their own value. `filled` (W·H) says which texels
  /// hold a value. `dilation`: how a gutter texel takes its neighbours' rows, as the rows'
  /// basis asks (transfer/row_dilation.hpp).
  std::vector<float> layOut(const float* values, RowRange rows, std::size_t stride,
                            TexelDilation dilation, std::vector<std::uint8_t>& filled) const;
};

/// The lightmap of `width` × `height` texels over `uvs` (checked by checkLightmapUvs), its
/// samples kept in texel rows `keep`, their points and which lie inside geometry.
TexelDomain makeTexelDomain(const Mesh& mesh, const Occluder& occluder, std::span<const Vec2f> uvs,
                            int width, int height, int padding, RowRange keep);

/// A texel pass's source image as the kernels read it.
inline TexelImage texelImage(const TexelDomain& d, const std::vector<float>& image,
                             std::size_t stride) {
  return TexelImage{image.data(), d.width, d.height, stride, d.uvs};
}

}  // namespace prt::bakedetail
