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
// rings, zero beyond. Texel t's samples are seeded by (seed, pass, t) alone: deterministic and
// independent of the thread count. Library only for now (no CLI, no bake file; issue 18).

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
};

/// Bakes vector transfer (settings.layout Vector; settings.rows left at the whole domain) at the
/// covered texels of a width × height lightmap over `uvs` (one per vertex, checked by
/// checkLightmapUvs), dilated `padding` rings (≥ 0). Throws prt::Error as bake() does, and on a
/// UV set that cannot hold the lightmap, a matrix layout or a row range.
TexelBake bakeTexels(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
                     std::span<const Vec2f> uvs, int width, int height, int padding,
                     BakeStats* stats = nullptr, const ProgressFn& progress = {});

}  // namespace prt
