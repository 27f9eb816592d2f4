#pragma once
// Which UV set of a mesh holds its lightmap — the one rule (issue 18's `--uv auto|0|1`): the
// lightmap set (Mesh::lightmapUvs: glTF TEXCOORD_1, the builtin scenes' packed charts) when it
// can hold a W × H lightmap, else the texture set (Mesh::uvs: TEXCOORD_0, OBJ vt) when it can
// (non-overlapping, inside [0, 1]²: geometry/texel_sampling.hpp's check); the reasons a set
// was passed over are kept, so a verb can say which it used and why not another.

#include <span>
#include <string>
#include <vector>

#include "prt/geometry/mesh.hpp"

namespace prt {

/// --uv: auto (the rule above), 1 (the lightmap set only), 0 (the texture set only).
enum class UvSetOption { Auto, Lightmap, Texture };
/// Parses "auto" | "0" | "1"; throws prt::Error otherwise.
UvSetOption parseUvSetOption(const std::string& s);

struct LightmapUvChoice {
  std::span<const Vec2f> uvs;  ///< one per vertex of the mesh
  std::string name;            ///< "lightmap UVs" (Mesh::lightmapUvs) or "texture UVs" (Mesh::uvs)
  std::vector<std::string> refused;  ///< why each set tried before it was passed over
};

/// The set `option` picks for a W × H lightmap; empty `uvs` (and every candidate in `refused`)
/// when none can hold it.
LightmapUvChoice findLightmapUvs(const Mesh& mesh, UvSetOption option, int width, int height);
/// The same, throwing prt::Error with one line naming the mesh and why each candidate set cannot
/// hold it (absent, outside [0, 1]², overlapping charts) when none can.
LightmapUvChoice chooseLightmapUvs(const Mesh& mesh, UvSetOption option, int width, int height);

}  // namespace prt
