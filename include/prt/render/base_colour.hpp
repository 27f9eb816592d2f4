#pragma once
// The base-colour texture in images of a relit mesh (issue 18): the one rule prt render's
// per-vertex and per-texel paths share.
//
// With the diffuse colour kd(p) = albedo(p) ⊙ texture(uv(p)) (geometry/base_colour.hpp), the exit
// radiance of material.hpp is
//
//   e(p, v) = texture(uv(p)) ⊙ [albedo(p) ⊙ D(p)] + ks ⊙ G(p, v),
//
// D(p) = (1/π) ∫ L'_p(ω) max(n·ω, 0) dω the relit diffuse transfer and G the glossy lobe's. The
// bracket is what relighting and render.hpp's shaders already draw: the albedo applied per row
// (vertices; texels of matrices) and interpolated, or per pixel (texel vectors, texelAlbedo).
// The texture varies inside a triangle and inside a texel, so it multiplies at the pixel: the
// drawn diffuse radiance times the texture sampled bilinearly at the hit's texture UV (Mesh::uvs
// interpolated with the hit's barycentrics). That is exact where the texture is constant over
// a triangle, and what a GPU shows for a Gouraud-shaded textured triangle everywhere else.
//
// The texture multiplies kd, not ks: under a glossy material and matrix transfer the two parts
// are relit apart (splitForTexture) and the glossy part added after, untextured. Vectors have
// no glossy part (a lobe needs a matrix).
//
// A material that sets kd (--material lambert?kd=...) replaces the whole diffuse colour — the
// albedo, as relighting does, and the texture with it: nothing then multiplies at the pixel.
// The viewers apply the same rule in their fragment stage (shaders/prt_fragment.glsl). Per-vertex
// stages (the bake's bounces, prt reference and validate, Python) see the texture folded in at
// the vertices (geometry/mesh.hpp: albedoAtVertices, foldBaseColour).

#include <optional>

#include "prt/geometry/mesh.hpp"
#include "prt/render/primary.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::render {

/// The texture an image multiplies per pixel: the mesh's base-colour texture, unless the
/// material sets kd (nullptr: none). With texelAlbedo (render.hpp), what every pixel multiplies.
const BaseColourTexture* pixelTexture(const Mesh& mesh, const Material& material);

/// The materials to relight with when a texture multiplies the diffuse part only.
struct TextureSplit {
  Material diffuse;                ///< relit for the part the texture multiplies
  std::optional<Material> glossy;  ///< relit for the part added untextured (none: no such part)
};
/// `material` itself and no glossy part, unless a texture applies to a glossy material over
/// matrix transfer: then its diffuse half (ks = 0) and its glossy half (kd = 0), relit apart.
TextureSplit splitForTexture(const Material& material, const BaseColourTexture* texture,
                             const Transfer& transfer);

/// The pixel of a textured mesh: `diffuse` (a shader of render.hpp drawing the part the texture
/// multiplies) times `texture` at the hit's interpolated Mesh::uvs, plus `glossy` (drawing the
/// untextured part; empty: none). Throws prt::Error unless the mesh has one UV per vertex.
ShadeFn texturedShader(const Mesh& mesh, const BaseColourTexture& texture, ShadeFn diffuse,
                       ShadeFn glossy = {});

}  // namespace prt::render
