#pragma once
// How a Haar bake (issue 33, docs/haar.md) is drawn in an image: the one rule prt render, the
// viewer's first exposure and its per-frame relight follow.
//  * Per vertex: each row relit under the light with the albedo at the vertices (the material's
//    kd, else the mesh's albedo with its base-colour texture folded in, geometry/albedo), the
//    radiance blended across each triangle with the hit's barycentrics.
//  * Per texel: each row relit at its texel's normal (render::texelRelight: a gutter texel at
//    the neighbour whose row it copies — an occluded-part row adds the unshadowed light at its
//    normal) with kd, else white; fetched with prt render's bilinear taps, the mesh's albedo
//    (unless kd) and the base-colour texture (render/base_colour.hpp) multiplied per pixel, as
//    over an SH lightmap.

#include <span>
#include <string>
#include <vector>

#include "prt/geometry/mesh.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/primary.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::render {

/// The rows' exit radiance as haarShader relights them: per vertex at the mesh's normals with
/// the albedo at the vertices, per texel at `texelNormals` (texelRelight's points) with kd or
/// white. What a viewer uploads at each turn of the light.
std::vector<Rgb> haarRadiance(const Mesh& mesh, const Transfer& transfer, const Material& material,
                              const haar::HaarLight& light,
                              std::span<const Vec3f> texelNormals = {});

/// `transfer` (Haar, every row of its domain on `mesh`) relit under `light` into `radiance`
/// (one value a row), and the shader that draws it. The shader reads `mesh` and `radiance`,
/// which must outlive it. Throws prt::Error(label, ...) naming the row a non-finite value
/// reached (render::checkFiniteRadiance).
ShadeFn haarShader(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                   const Material& material, const haar::HaarLight& light,
                   std::vector<Rgb>& radiance, const std::string& label);

}  // namespace prt::render
