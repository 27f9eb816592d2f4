#pragma once
// Per-texel transfer (the lightmap domain, issue 18): the bakes of transport/bake.hpp — diffuse
// vectors and glossy matrices; unshadowed, shadowed and inter-reflected (diffuse or glossy
// bounce surfaces); the same estimators and per-row seeding — at one sample point per texel of a
// W × H lightmap that a triangle covers in the mesh's lightmap UVs (geometry/texel_sampling.hpp:
// the centre, else the nearest point of the triangle inside the texel), instead of at the
// vertices. Bounces read the previous pass (or order, or the diffuse sum a matrix gathers) where
// a ray lands through the hit's lightmap UV, bilinearly, from that pass dilated into the gutter.
// Matrices per texel are large — B⁴ floats per texel and channel: 1024² texels at 5 bands are
// 2.6 GB — so texelBakeFootprint states the memory first, and the bake refuses what would not fit.
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
#include "prt/transport/bake.hpp"

namespace prt {

struct TexelBake {
  Transfer transfer;                 ///< TransferDomain::Texels, width · height rows
  TexelSamples samples;              ///< where each covered texel was sampled
  std::vector<std::uint8_t> filled;  ///< per texel: covered, or reached by dilation
  /// Covered texels whose sample point lies inside geometry (texel_validity.hpp), ascending:
  /// refilled from their valid neighbours (kept as baked where none is within the padding).
  std::vector<std::uint32_t> invalid;
};

/// What a per-texel bake holds in memory, known before it starts (bakeFootprint of the texel
/// domain: the channels rule is the same, RGB when a bounce's albedo, or a glossy bounce's ks,
/// is coloured; bytesPerRow is per texel).
using TexelBakeFootprint = BakeFootprint;
TexelBakeFootprint texelBakeFootprint(const Mesh& mesh, const BakeSettings& settings, int width,
                                      int height);
/// `settings` over the texels of a width × height lightmap dilated `padding` rings.
BakeSettings texelSettings(const BakeSettings& settings, int width, int height, int padding);

/// Bakes settings.layout transfer at the covered texels of a width × height
/// lightmap over `uvs` (one per vertex, checked by checkLightmapUvs), dilated `padding` rings
/// (0..kMaxLightmapPadding); settings.rows is a range of texel rows (count 0: to the last). Throws
/// prt::Error as bake() does, on a UV set that cannot hold the lightmap or a range outside it,
/// and when texelBakeFootprint would not fit in this machine's memory (stating the figure).
TexelBake bakeTexels(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                     std::span<const Vec2f> uvs, int width, int height, int padding,
                     BakeStats* stats = nullptr, const ProgressFn& progress = {});

}  // namespace prt
