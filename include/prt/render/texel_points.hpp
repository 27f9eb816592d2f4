#pragma once
// The rows of a per-texel transfer as points for the reference and validation (issue 18): each
// texel's sample point, normal and albedo exactly as bakeTexels made them
// (geometry/texel_sampling.hpp), and which texels may be validated — covered, and not inside
// geometry (transport/texel_validity.hpp; those hold their neighbours' values, not their own).

#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/reference.hpp"
#include "prt/transfer/shape.hpp"

namespace prt::render {

/// W·H rows over the mesh's lightmap UVs (throws prt::Error without them or on a bad size).
RowPoints texelRowPoints(const Mesh& mesh, const Occluder& occluder,
                         const TransferShape::LightmapSize& lightmap);

}  // namespace prt::render
