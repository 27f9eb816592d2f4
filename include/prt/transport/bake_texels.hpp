#pragma once
// Per-texel transfer (the lightmap domain, issue 18): the vector bake of transport/bake.hpp —
// unshadowed, shadowed and inter-reflected, the same estimators and per-row seeding — at one
// sample point per texel of a W × H lightmap that a triangle covers in the mesh's lightmap UVs
// (geometry/texel_sampling.hpp: the centre, else the nearest point of the triangle inside the
// texel), instead of at the vertices. Bounces read the previous pass where a ray lands through
// the hit's lightmap UV, bilinearly, from that pass dilated into the gutter.
//
// The result is a Transfer over TransferDomain::Texels: W·H rows, texel (x, y) row y·W + x;
// the texels no triangle covers hold the dilation of their covered neighbours up to `padding`
// rings, zero beyond; covered texels whose sample point lies inside geometry (under a block,
// behind a wall: texel_validity.hpp) are refilled from their valid neighbours the same way. Texel
// t's samples are seeded by (seed, pass, t) alone: deterministic and independent of the thread
// count, and of the texel range asked for: a range's rows equal the whole bake's (prt bake --domain
// texels --range, prt merge).

#include <cstdint>
#include <span>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

struct TexelBake {
  Transfer transfer;                 ///< TransferDomain::Texels, width · height rows
  TexelSamples samples;              ///< where each covered texel was sampled
  std::vector<std::uint8_t> filled;  ///< per texel: covered, or reached by dilation
  /// Covered texels whose sample point lies inside geometry (texel_validity.hpp), ascending:
  /// refilled from their valid neighbours (kept as baked where none is within the padding).
  std::vector<std::uint32_t> invalid;
};

/// Bakes vector transfer (settings.layout Vector) at the covered texels of a width × height
/// lightmap over `uvs` (one per vertex, checked by checkLightmapUvs), dilated `padding` rings
/// (0..kMaxLightmapPadding); settings.rows is a range of texel rows (count 0: to the last). Throws
/// prt::Error as bake() does, and on a UV set that cannot hold the lightmap, a matrix layout or
/// a range outside the lightmap.
TexelBake bakeTexels(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                     std::span<const Vec2f> uvs, int width, int height, int padding,
                     BakeStats* stats = nullptr, const ProgressFn& progress = {});

}  // namespace prt
