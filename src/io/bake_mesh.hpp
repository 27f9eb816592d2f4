#pragma once
// The mesh in a bake file: one glTF mesh + node per MeshPart, one triangle primitive each
// (POSITION, NORMAL, TEXCOORD_0 and TEXCOORD_1 (texture and lightmap sets, lightmapTexCoord),
// COLOR_0 = linear albedo, uint32 indices local to the part),
// all parts viewing one shared vertex buffer in the scene's global vertex order, so any glTF
// viewer opens the file as the scene; the mesh's base-colour texture, if any, as material 0's
// baseColorTexture (one embedded PNG). Private to src/io.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake_schema.hpp"
#include "glb.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/gltf/accessor.hpp"

namespace prt::io {

/// The mesh's parts, or one part for all of it.
std::vector<MeshPart> partsOf(const Mesh& mesh);
/// Throws prt::Error("bake file: ...") unless the mesh can be written: not empty, a normal per
/// vertex, albedo and uvs per vertex if any, parts that tile vertices and triangles in order and
/// whose triangles stay inside their part.
void checkMeshForWriting(const Mesh& mesh, const std::vector<MeshPart>& parts);

/// Describes the mesh in `bin` and writes glTF's meshes, nodes, scenes and material (with the
/// base-colour texture's image, sampler and texture) into `gltf`. `attributes` (name, view of VEC4
/// columns over all vertices) become extra primitive attributes of every part (a complete bake's
/// vector transfer); `baseColour` the material's baseColorFactor when the mesh has no per-vertex
/// albedo.
void encodeMesh(const Mesh& mesh, const std::vector<MeshPart>& parts,
                const std::vector<std::pair<std::string, int>>& attributes, const Rgb* baseColour,
                glb::BinaryChunk& bin, nlohmann::json& gltf);

/// The glTF set that holds the mesh's lightmap UVs (Mesh::lightmapUvs): TEXCOORD_1 beside a
/// texture set, TEXCOORD_0 when it is the only one (glTF numbers sets from 0); −1 without.
/// The bake's object records it as "lightmapTexCoord".
int lightmapTexCoord(const Mesh& mesh);

/// The base-colour texture of a bake file's material 0 (encodeMesh's layout only; anything else
/// that holds images is refused), or none. `mesh` is the decoded mesh (its TEXCOORD_0 must be
/// there to read the texture at).
std::optional<BaseColourTexture> decodeBaseColour(const nlohmann::json& gltf,
                                                  const gltf::AccessorReader& accessors,
                                                  const Mesh& mesh, const schema::Reader& r);

/// Reads the mesh of a bake file that declares V vertices and T triangles; TEXCOORD_`lightmap`
/// (−1: none) is its lightmap set, the other TEXCOORD_0 its texture set.
Mesh decodeMesh(const nlohmann::json& gltf, const gltf::AccessorReader& accessors,
                std::size_t vertices, std::size_t triangles, int lightmap, const schema::Reader& r);

}  // namespace prt::io
