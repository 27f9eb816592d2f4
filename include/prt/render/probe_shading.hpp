#pragma once
// Meshes lit through relit probes (issue 32): each vertex's diffuse exit radiance from the
// trilinear blend of the eight probes around it and its normal (relight/relight_probes.hpp) —
// what a dynamic object gets from a probe grid, and what prt render draws for a probe bake
// (the scene and an object placed in it).

#include <vector>

#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/relight/probe_lighting.hpp"
#include "prt/render/exposure.hpp"

namespace prt::render {

/// Per vertex of `mesh`: ρ E(n)/π through the probes at the vertex (albedo ρ: the mesh's, white
/// where it has none). Parallel over the vertices.
std::vector<Rgb> shadeThroughProbes(const relight::ProbeLighting& lighting, const Mesh& mesh);

/// surveyFrame of `mesh` shaded through the probes of `transfer` (a complete probe bake's)
/// relit under `light` turned by `rotation` (on its coefficients), seen through `camera`: the
/// exposure prt web opens a probe bake at. `bands` > 0 cuts the transfer first.
FrameSurvey probeSurvey(const Mesh& mesh, const Transfer& transfer, const sh::RgbSh& light,
                        const Mat3d& rotation, const Camera& camera, int width, int height,
                        image::ToneMap op, int bands = 0);

}  // namespace prt::render
