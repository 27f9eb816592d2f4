#pragma once
// The triangle mesh every stage shares. A scene of several objects is merged into one Mesh (so
// they shadow each other and share one BVH); `parts` remembers where each object's vertices and
// triangles lie so writers can split them again.
//
// Vertices are split wherever the source file splits them (a position used with two normals or
// two UVs becomes two vertices); only exact duplicates are welded. Normals are unit length.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/geometry/base_colour.hpp"

namespace prt {

struct MeshPart {
  std::string name;
  std::uint32_t firstVertex = 0, vertexCount = 0;
  std::uint32_t firstTriangle = 0, triangleCount = 0;
};

/// The glossy part of a surface as its file describes it, for the default relighting material
/// (prt/transfer/material.hpp). OBJ/MTL: Ks and the Phong exponent Ns (illumination models with
/// a specular term). glTF: the metallic-roughness model, F0 = mix(0.04, baseColor, metallic)
/// and its perceptual roughness. The diffuse colour stays per vertex in Mesh::albedo.
struct SurfaceGloss {
  enum class Model { Phong, MetallicRoughness };
  Model model = Model::Phong;
  Rgb specular{0.0f};    ///< Ks, or F0 for metallic-roughness
  float exponent = 0;    ///< Phong: Ns
  float roughness = 1;   ///< metallic-roughness: roughnessFactor
  float metallic = 0;    ///< metallic-roughness: metallicFactor
  std::string material;  ///< the file's name of the material it came from
};

struct Mesh {
  std::vector<Vec3f> positions;  ///< world space (scene transforms applied)
  std::vector<Vec3f> normals;    ///< unit, one per vertex
  /// Linear diffuse albedo per vertex (empty: uniform). With a base-colour texture, the factor
  /// it multiplies (glTF baseColorFactor × COLOR_0, MTL Kd): the diffuse colour at p is
  /// albedo(p) × sampleBaseColour(texture, uv(p)). Per-vertex stages (the bake's bounces, prt
  /// reference and validate, Python) see the texture folded in at the vertices
  /// (albedoAtVertices, foldBaseColour); images and the viewers multiply it per pixel
  /// (render/base_colour.hpp).
  std::vector<Rgb> albedo;
  std::vector<Vec2f> uvs;  ///< optional texture coordinates (glTF TEXCOORD_0, OBJ vt)
  /// Optional lightmap coordinates, a second UV set for per-texel data (glTF TEXCOORD_1; the
  /// builtin scenes' packed charts): inside [0, 1]², charts apart (geometry/texel_sampling.hpp
  /// checks). One per vertex, or empty.
  std::vector<Vec2f> lightmapUvs;
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise = front
  std::vector<MeshPart> parts;                          ///< at least one part when loaded
  std::string source;                                   ///< file name or builtin:NAME, for messages
  /// The scene's glossy surface when a file describes one: one for the whole scene (the first
  /// material with a specular term), as relighting applies one lobe.
  std::optional<SurfaceGloss> gloss;
  /// The scene's base-colour texture, read at `uvs` (which then has one UV per vertex): one for
  /// the whole scene, kept when every part uses the same one (the loaders sample textures into
  /// the albedo at the vertices otherwise). geometry/base_colour.hpp.
  std::optional<BaseColourTexture> baseColour;

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return triangles.size(); }
  bool hasAlbedo() const { return !albedo.empty(); }
};

/// Axis-aligned bounds and the bounding sphere of the vertices.
struct Bounds {
  Vec3f lo{0.0f}, hi{0.0f};
  Vec3f centre() const { return (lo + hi) * 0.5f; }
  float radius() const { return length(hi - lo) * 0.5f; }
};
Bounds computeBounds(const Mesh& mesh);

/// The diffuse colour at each vertex: the albedo (white where empty) times the base-colour
/// texture sampled at the vertex's UV; the albedo as it is without a texture.
std::vector<Rgb> albedoAtVertices(const Mesh& mesh);
/// Folds the base-colour texture into the per-vertex albedo (albedoAtVertices) and drops it:
/// the mesh as a consumer that shades per vertex sees it. Nothing without a texture.
void foldBaseColour(Mesh& mesh);

/// 16 hex digits identifying the mesh's geometry: FNV-1a (core/hash.hpp) of its positions,
/// normals, triangles and albedo, bitwise (and, when it has one, of its base-colour texture and
/// the texture UVs it is read at). A bake's checkpoint identity and a reference file's
/// tie to their mesh by it.
std::string meshFingerprint(const Mesh& mesh);

}  // namespace prt
