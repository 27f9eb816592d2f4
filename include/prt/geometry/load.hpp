#pragma once
// Loading meshes and scenes from files. One entry point dispatches on the extension
// (case-insensitive; a trailing ".gz" is decompressed first):
//
//   .obj        Wavefront OBJ (tinyobjloader) with its .mtl: Kd → albedo, map_Kd → base colour
//               texture (Mesh::baseColour; sampled into the albedo where faces differ)
//   .ply        Stanford PLY, ASCII or binary little/big endian (our own reader)
//   .off        Object File Format (OFF, COFF, NOFF, CNOFF), ASCII
//   .gltf .glb  glTF 2.0 (tinygltf): all triangle primitives of the default scene, node transforms
//               applied, baseColorFactor × COLOR_0 → albedo, baseColorTexture → base colour
//               texture (sampled into the albedo where primitives differ)
//   builtin:NAME  a generated scene (see builtin.hpp)
//
// The vertex order of each format, the colour conventions and what is repaired or rejected are
// documented in docs/formats-meshes.md; the OBJ order (one vertex per distinct position/uv/normal
// index triple, in order of first appearance in the faces) is the GAMES202 course's, which its
// transport.txt files rely on.
//
// Every loaded mesh has unit normals (the file's, or angle-weighted vertex normals where it has
// none), no zero-area triangles (they are dropped and counted), finite coordinates, indices in
// range and at least one part. Errors: prt::Error("FILE: what is wrong").

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "prt/geometry/mesh.hpp"

namespace prt {

/// The albedo given to vertices without a material colour when a scene mixes meshes with and
/// without albedo (a mesh alone without colours keeps an empty albedo: "uniform").
inline constexpr float kDefaultAlbedo = 0.8f;
/// The largest albedo component a loader accepts: a diffuse albedo above 1 already reflects more
/// than it receives; far above it (an MTL "Kd 1e30") is a broken file whose transfer overflows.
inline constexpr float kMaxAlbedo = 100.0f;

/// Rejects positions the ray tracer cannot handle, naming the first offender and the figure:
/// non-finite, or a coordinate beyond limits().maxCoordinate (Embree asserts on ray origins past
/// 1.844e18, and squared distances overflow floats well before; see prt/core/limits.hpp). Every
/// loader runs it, the bake reader too (naming the file given), and so does the Embree occluder
/// for meshes built in code.
void checkMeshExtent(const Mesh& mesh, const std::string& label);
/// checkMeshExtent, plus non-finite normals, texture coordinates or albedo and albedo above
/// kMaxAlbedo. Every loader runs it.
void checkMeshValues(const Mesh& mesh, const std::string& label);

/// What the loader repaired or noticed, for the CLI to print.
struct LoadReport {
  std::size_t degenerateTriangles = 0;  ///< zero-area triangles dropped
  std::size_t computedNormals =
      0;  ///< vertices whose normal was computed (none or invalid in the file)
  std::size_t unusedVertices = 0;        ///< vertices referenced by no (kept) triangle
  std::size_t polygonsTriangulated = 0;  ///< faces with more than 3 corners, fan-triangulated
  std::vector<std::string> warnings;     ///< one line each, already naming the file

  /// Adds another report's counts and warnings.
  void merge(const LoadReport& other);
};

/// Loads one mesh file or builtin:NAME. Throws prt::Error("FILE: what is wrong").
Mesh loadMesh(const std::string& path, LoadReport* report = nullptr);

/// Loads a mesh held in memory; `name`'s extension chooses the format as for loadMesh (".ply.gz"
/// included). Nothing outside `bytes` is read: an OBJ's mtllib and a glTF's external buffers
/// and images are not available (materials are then missing, with a warning). For fuzzing and
/// for callers that hold files in memory.
Mesh loadMeshBytes(const std::string& name, std::span<const unsigned char> bytes,
                   LoadReport* report = nullptr);

/// Loads several inputs (files or builtin:NAME) and merges them into one Mesh, one MeshPart per
/// input part, so the objects shadow each other. Mesh::source joins the inputs with '+'.
Mesh loadScene(const std::vector<std::string>& inputs, LoadReport* report = nullptr);

/// Appends `part` to `scene` (indices offset, parts appended; albedo filled with kDefaultAlbedo
/// on whichever side lacks it when exactly one side has it). A base-colour texture is kept for
/// a scene of one mesh only: appending to a non-empty scene folds both sides' textures into
/// their albedo (foldBaseColour, mesh.hpp).
void appendMesh(Mesh& scene, const Mesh& part);

/// The extensions loadMesh accepts (without dot, lower case; "gz" variants not listed).
std::vector<std::string> meshExtensions();

}  // namespace prt
