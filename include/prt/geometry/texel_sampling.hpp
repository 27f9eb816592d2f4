#pragma once
// The lightmap domain's geometry (issue 18): checking a UV set can hold a lightmap, placing one
// sample per covered texel (the TexelSamples type: geometry/texel_samples.hpp) — or, without the
// whole lightmap's arrays, which texels are covered and the samples of a few of them — the
// sample's point and normal on the mesh, and dilating per-texel values into the gutter around
// charts so bilinear filtering at a chart's edge never reads an empty texel.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "prt/geometry/mesh.hpp"
#include "prt/geometry/texel_coverage.hpp"
#include "prt/geometry/texel_samples.hpp"

namespace prt {

/// The largest lightmap side sampleTexels takes (8192² texels: ~1.4 GB of working buffers).
inline constexpr int kMaxLightmapSide = 8192;
/// The most rings of gutter a bake dilates into (Dilation reads within that many texels).
inline constexpr int kMaxLightmapPadding = 64;

/// Checks that `uvs` (one per vertex of `mesh`) can hold a W × H lightmap: finite, inside
/// [0, 1]², and no texel centre strictly inside two triangles (overlapping charts would share
/// texels). Throws prt::Error with one line naming mesh.source, `what` (the UV set: "TEXCOORD_1")
/// and, for an overlap, the two triangles and a texel they share.
void checkLightmapUvs(const Mesh& mesh, std::span<const Vec2f> uvs, int width, int height,
                      const std::string& what);

/// The first vertex whose UV in `uvs` is not finite or lies outside [0, 1]² (to 1e-6), if any.
std::optional<std::size_t> firstUvOutside(std::span<const Vec2f> uvs);
/// Throws prt::Error naming the mesh and the first vertex firstUvOutside finds: what every lightmap needs, and what every reader of a per-texel
/// bake checks before it samples (a corrupt UV must never reach the rasteriser).
void checkUvsInside(const Mesh& mesh, std::span<const Vec2f> uvs, const std::string& what);

/// One sample per texel covered by a triangle in UV space (texel_samples.hpp has the rule).
/// Where several triangles cover one texel (along a shared edge) the one holding its centre
/// wins, else the nearest, ties to the lower triangle index: deterministic. Triangles with no
/// UV area are skipped; the parts of triangles outside [0, 1]² are clipped away (a UV of any
/// size sweeps only the lightmap's texels). Throws prt::Error on a size out of
/// 1..kMaxLightmapSide or UVs that do
/// not match the mesh.
TexelSamples sampleTexels(const Mesh& mesh, std::span<const Vec2f> uvs, int width, int height);

/// Which texels sampleTexels would sample (those a triangle covers), one bit each, without
/// placing the samples: W·H/8 bytes where sampleTexels holds some 30 per texel. Throws as
/// sampleTexels does.
TexelCoverage coverTexels(const Mesh& mesh, std::span<const Vec2f> uvs, int width, int height);

/// sampleTexels' samples of `texels` alone (distinct, ascending): the same triangle, weights and
/// centre flag for each that a triangle covers, none for the others, in texel order. One pass
/// over the triangles, each tested against the texels asked for within its bounds only, and
/// memory for those texels alone: what a few rows of a large lightmap cost (prt validate).
std::vector<TexelSample> sampleTexelsAt(const Mesh& mesh, std::span<const Vec2f> uvs, int width,
                                        int height, std::span<const std::uint32_t> texels);

/// The sample's point on the mesh (its barycentric blend of the triangle's positions).
Vec3f samplePosition(const Mesh& mesh, const TexelSample& s);
/// The sample's unit normal (the blend of the vertex normals, normalised; the face normal where
/// the blend vanishes).
Vec3f sampleNormal(const Mesh& mesh, const TexelSample& s);

/// How a dilated texel takes its filled neighbours' values.
enum class TexelDilation {
  Mean,       ///< their mean (values that blend: SH coefficients, points, normals)
  CopyFirst,  ///< the first of them whole, in the order (−1,−1), (0,−1), (1,−1), (−1,0), …:
              ///< values that are records, which a mean would scramble
};

/// Dilates per-texel values (`stride` floats per texel, W·H texels) into at most `padding` rings
/// of unfilled texels around the filled ones: each ring, an unfilled texel with filled
/// neighbours (of the 8, filled before the ring) takes their values as `how` says and becomes
/// filled. Every texel within Chebyshev distance `padding` of a filled one is filled afterwards;
/// no other changes.
void dilateTexels(std::span<float> values, int stride, std::vector<std::uint8_t>& filled, int width,
                  int height, int padding, TexelDilation how = TexelDilation::Mean);

}  // namespace prt
