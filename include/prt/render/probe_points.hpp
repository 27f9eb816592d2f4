#pragma once
// The rows of a probe bake as points for the reference and validation (issue 32). A probe holds
// the SH of the light arriving at a point in space; what an object moving through the grid sees
// of it is the radiance its surfaces reflect, so that is what is validated, with no SH anywhere
// in the reference: at each validated probe p the six axis normals n_a (+x, −x, +y, −y, +z, −z),
// and at each the exit radiance of a white diffuse surface facing n_a there,
//
//   e(p, n_a) = (1/π) ∫ L_in(p, ω) max(n_a·ω, 0) dω,
//
// the reference's diffuse estimate at that point and normal (reference.hpp), against PRT's
// ρ E(n_a)/π from the probe's relit SH (relight_probes.hpp: shadeDiffuse). Validation row
// kProbeNormals·p + a is probe p seen by normal a. Probes inside geometry hold their neighbours'
// mean (the bake's refill), not their own light, and are never drawn.

#include <cstddef>
#include <cstdint>

#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/reference.hpp"
#include "prt/transfer/probe_grid.hpp"

namespace prt::render {

/// Normals per validated probe, and the validation row of probe p and normal a.
inline constexpr int kProbeNormals = 6;
constexpr std::size_t probeNormalRow(std::size_t probe, int axis) {
  return probe * kProbeNormals + std::size_t(axis);
}
/// Unit normal a of a probe: +x, −x, +y, −y, +z, −z.
Vec3f probeNormal(int axis);

/// `count` probes of `grid` outside geometry (0 or more than there are: every one), a uniformly
/// random subset of them in the seeded order subsetOrder (validate.hpp) gives — only the probes
/// drawn are tested for being inside geometry (transport/texel_validity.hpp:
/// insideGeometryAllAround) — as points: kProbeNormals entries per probe (rows probeNormalRow,
/// ascending), at the probe's position with each axis normal, white (albedo empty).
RowPoints drawProbePoints(const Mesh& mesh, const Occluder& occluder, const ProbeGrid& grid,
                          std::size_t count, std::uint64_t seed);

}  // namespace prt::render
