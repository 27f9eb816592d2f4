#pragma once
// A mesh alone as a plain glTF binary (no prtkit extension): what `prt unwrap` writes, for any
// glTF tool, engine or viewer, and for prtkit's own loader (geometry/load.hpp) to read back.
// The mesh is written as a bake file's is (src/io/bake_mesh: one node and mesh per part,
// POSITION, NORMAL, COLOR_0 = linear albedo, uint32 indices, one shared vertex buffer):
//
//   TEXCOORD_0  the texture set (Mesh::uvs); without one, the lightmap set again, as glTF
//               numbers a primitive's sets from 0 without gaps
//   TEXCOORD_1  the lightmap set (Mesh::lightmapUvs), when the mesh has one

#include <string>

#include "prt/core/version.hpp"
#include "prt/geometry/mesh.hpp"

namespace prt {

/// The .glb bytes of `mesh`. Throws prt::Error when the mesh cannot be written (empty, no
/// normal per vertex, attributes or parts that do not match its vertices, over 4 GiB).
std::string encodeMeshGlb(const Mesh& mesh, const std::string& generator = kGenerator);

/// Writes encodeMeshGlb(mesh) to `path` through core/file.hpp's policy (a temporary renamed
/// into place; "-" is standard output). Errors name the path.
void writeMeshGlb(const std::string& path, const Mesh& mesh,
                  const std::string& generator = kGenerator);

}  // namespace prt
