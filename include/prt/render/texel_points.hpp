#pragma once
// The rows of a per-texel transfer as points for the reference and validation (issue 18): each
// texel's sample point, normal and albedo exactly as bakeTexels made them
// (geometry/texel_sampling.hpp), and which texels may be validated — covered, and not inside
// geometry (transport/texel_validity.hpp; those hold their neighbours' values, not their own).

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "prt/geometry/mesh.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/render/reference.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/shape.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::render {

/// W·H rows over the mesh's lightmap UVs (throws prt::Error without them or on a bad size). Rows
/// that are not valid — the gutter and the texels inside geometry — take the point, normal and
/// albedo of their valid neighbours, dilated as the bake dilates their transfer (max(padding, 1)
/// rings; inside texels no valid texel reaches keep their own), so that a row relit where the
/// view and the lobe matter (matrices) is relit where its transfer came from.
/// The albedo at a point is the diffuse colour there with the base-colour texture folded in at
/// the vertices (albedoAtVertices, as the bake's bounces and the reference see it); without
/// `withTexture` the mesh's albedo alone (an image multiplies the texture per pixel). `how` is
/// the dilation of the rows these points are for (transfer/row_dilation.hpp): copied, a gutter
/// row is relit at the point of the neighbour it copied.
RowPoints texelRowPoints(const Mesh& mesh, const Occluder& occluder,
                         const TransferShape::LightmapSize& lightmap, bool withTexture = true,
                         TexelDilation how = TexelDilation::Mean);

/// The points of some texels alone (`texels`: distinct, ascending), each exactly as
/// texelRowPoints gives it, and which of them are valid — at the cost of those texels (their
/// samples, their inside-geometry probe) and one pass over the triangles, not of the lightmap:
/// what the reference and validation of a subset read (RowPoints::rows = `texels`). Where one
/// of them is not valid (the gutter, inside geometry), whose point is its valid neighbours',
/// the whole lightmap's points are made and those of `texels` kept.
RowPoints texelRowPointsAt(const Mesh& mesh, const Occluder& occluder,
                           const TransferShape::LightmapSize& lightmap,
                           std::span<const std::uint32_t> texels,
                           TexelDilation how = TexelDilation::Mean);

/// The texels' own sample points (before any dilation), for `texels` alone (distinct,
/// ascending): an entry for each (RowPoints::rows = `texels`), its point, normal and albedo where
/// a triangle covers it (else (0, 0, 0) with normal +Z), and `valid` those covered and not inside
/// geometry. The cost of texelRowPointsAt without its fallback: what a draw of valid texels
/// probes its candidates with.
RowPoints texelSamplePoints(const Mesh& mesh, const Occluder& occluder,
                            const TransferShape::LightmapSize& lightmap,
                            std::span<const std::uint32_t> texels);

/// Throws prt::Error naming `verb` ("validate") unless `transfer` holds every row of its domain
/// on `mesh` (every vertex, or every texel of its lightmap over the mesh's lightmap UVs).
void requireWholeDomain(const Mesh& mesh, const Transfer& transfer, const std::string& verb);

/// The texels' shading points a GPU viewer needs beside `transfer` (packTexelPoints of
/// texelRelight's points: per-texel matrices are shaded at each texel's own point, Haar rows
/// relit at its normal), or empty when it needs none (SH vectors, per-vertex rows). `occluder`
/// is built from `mesh` when null.
std::vector<float> shadingPoints(const Mesh& mesh, const Transfer& transfer,
                                 const Material& material, const Occluder* occluder = nullptr);

/// How a per-texel transfer is relit for an image, the one rule for prt render, auto exposure
/// and the Python module:
///  * vectors are relit white, texel by texel, and the albedo multiplies per pixel (pixelAlbedo,
///    texelAlbedo of render.hpp), as it varies across a texel; Haar rows (vectors) are relit at
///    their texels' normals (`points`: an occluded-part row's unshadowed light is the normal's,
///    relight/relight_haar.hpp);
///  * matrices are relit at each texel's sample point (`points`: the eye's direction and the lobe
///    need its position and normal) with the texel's albedo, since only their diffuse term takes
///    the albedo (kd ⊙ diffuse + ks ⊙ glossy): the pixel multiplies nothing more but the
///    base-colour texture (render/base_colour.hpp), which the rows' albedo leaves out.
struct TexelRelight {
  RowPoints points;                  ///< matrices and Haar: the rows' points (else empty)
  std::span<const Rgb> pixelAlbedo;  ///< what texelRadianceShader multiplies (empty: nothing)
  relight::Surface surface() const { return {points.positions, points.normals, points.albedo}; }
};
TexelRelight texelRelight(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                          const Material& material);

/// The rows' points as a GPU viewer reads them (shaders/prt_lightmap.glsl, uPoints): three RGBA
/// texels per row, (position, 0), (normal, 0), (albedo, 0) — white where the points hold none.
std::vector<float> packTexelPoints(const RowPoints& points);

}  // namespace prt::render
