#pragma once
// What prt view draws of a probe bake (issue 32): the scene's mesh, the moving object placed in
// the grid and, on request, a small octahedron at every probe — one mesh whose every vertex is
// shaded through the relit probes around it on the CPU (render::shadeThroughProbes, what prt
// render draws), uploaded as exit radiance (the CpuRadiance path: the shader interpolates it).
// A turning light costs one B² × B² product per probe and channel and one trilinear blend and
// convolution per vertex; nothing is re-baked.

#include <span>
#include <vector>

#include "moving_object.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/exposure.hpp"

namespace prt::viewer {

/// The mesh drawn for a probe bake: its scene (base colour folded into the albedo), `object`
/// where it is (none: the scene alone), and with `showProbes` an octahedron at each probe (a
/// fifth of the smallest spacing across, white), so that each shows the light arriving there.
Mesh probeSceneMesh(const BakeFile& bake, const MovingObject* object, bool showProbes);

/// Each vertex of `mesh` lit through the probes of `transfer` (cut to `bands`) relit under
/// `rotatedLight` (the light already turned, bands² coefficients).
std::vector<Rgb> shadeProbeScene(const Transfer& transfer, int bands,
                                 std::span<const Rgb> rotatedLight, const Mesh& mesh);

/// prt render's exposure rule for the first view of a mesh drawn from per-vertex radiance (a probe
/// scene, a Haar bake): render::surveyFrame.
render::FrameSurvey vertexRadianceSurvey(const Mesh& mesh, std::span<const Rgb> radiance,
                                         const render::Camera& camera, int width, int height,
                                         image::ToneMap op);

}  // namespace prt::viewer
