#pragma once
// Relighting a probe grid (issue 32; Sloan, Kautz & Snyder 2002, §7): the light arriving at every
// probe from the distant light, L'_p = M_p L, then, for a point anywhere in the grid, the
// trilinear blend of its eight probes and the diffuse shading of a normal there. The light is
// rotated on its coefficients before (sh::Rotation), as for surfaces, so a turning light costs
// one B² × B² product per probe per channel: 32 × 16 × 16 probes at 3 bands are 2 M multiply-adds.
//
// Shading a normal n of albedo ρ from the blended SH L' (Ramamoorthi & Hanrahan 2001):
//   E(n) = Σ_l A_l Σ_m L'_lm Y_lm(n),  A_l the clamped cosine's kernel (A_0 = π, A_1 = 2π/3,
//   A_2 = π/4),  and the exit radiance ρ E(n)/π.

#include "prt/relight/probe_lighting.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

/// The light arriving at every probe of `transfer` (a complete probe bake, dense or CPCA) under
/// `light`, at min(light, transfer) bands. Throws prt::Error when the transfer is not over probes
/// or does not cover the whole grid. Parallel over the probes; independent of the thread count.
ProbeLighting relightProbes(const Transfer& transfer, const sh::RgbSh& light);

/// The light arriving at one probe: its row `matrix` as stored (B² × B² for `transferBands` B,
/// row i arriving, column j source, `channels` (1 or 3) innermost) times the first `bands`²
/// coefficients of `light`, its leading bands² × bands² block alone (bands ≤ both; what
/// Transfer::cut(bands) relights), into out (bands² coefficients).
void relightProbe(const float* matrix, int transferBands, int channels, const sh::RgbSh& light,
                  int bands, Rgb* out);

/// The trilinear blend of the eight probes around `point` (clamped to the grid: outside it, the
/// nearest face's probes) into out (B² coefficients).
void sampleProbes(const ProbeLighting& lighting, const Vec3f& point, Rgb* out);

/// Diffuse exit radiance ρ E(n)/π of a surface with unit normal n lit by the SH `incident`
/// (bands B, B² coefficients; see the top).
Rgb shadeDiffuse(const Rgb* incident, int bands, const Vec3f& normal, const Rgb& albedo);

}  // namespace prt::relight
