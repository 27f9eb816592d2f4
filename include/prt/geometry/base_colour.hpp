#pragma once
// A material's base-colour texture (glTF pbrMetallicRoughness.baseColorTexture, MTL map_Kd), kept
// with the mesh so that images multiply it per pixel (render/base_colour.hpp) instead of only
// at the vertices. glTF 2.0 §3.9.2 defines the diffuse colour as
//
//   base colour(p) = baseColorFactor × texture(uv(p)) × COLOR_0(p)
//
// and the mesh keeps the two factors apart: Mesh::albedo holds baseColorFactor × COLOR_0 (MTL:
// Kd) per vertex, this texture the rest, read at the mesh's texture set Mesh::uvs (TEXCOORD_0,
// OBJ vt).
//
// Conventions (one for every source, so the texture writes to a .glb as it is):
//  * the texels are the file's 8-bit sRGB codes (image::Srgb8Image), decoded to linear where
//    sampled, before filtering, as a GPU's sRGB texture is;
//  * texel (x, y) is centred on UV ((x + ½)/W, (y + ½)/H): row 0 lies at v = 0, glTF's top row.
//    OBJ's v runs up the image, so an OBJ texture is stored upside down (its bottom row first);
//  * bilinear filtering, repeat wrapping in u and v (glTF's default sampler; MTL's default, no
//    -clamp), no mipmaps. The alpha channel is dropped (surfaces are opaque).

#include <string>

#include "prt/core/vec.hpp"
#include "prt/image/image.hpp"

namespace prt {

struct BaseColourTexture {
  image::Srgb8Image image;  ///< row 0 at v = 0 (see above)
  std::string name;         ///< where it came from ("wood.png", "image 0"), for messages
  bool operator==(const BaseColourTexture&) const = default;
};

/// The linear colour of `texture` at `uv`: the four texels around it (repeat wrapping) decoded
/// from sRGB and blended bilinearly. White for a non-finite uv or an empty texture.
Rgb sampleBaseColour(const BaseColourTexture& texture, Vec2f uv);

}  // namespace prt
