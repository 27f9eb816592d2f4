#pragma once
// A relit lightmap as one glTF 2.0 binary (`prt export BAKE --format lightmap | lightmap-sh
// -o NAME.glb`; docs/lightmaps.md, docs/extensions/PRTKIT_lightmap): the bake's mesh, as a
// bake file lays it out (one node and mesh per part, its lightmap UV set as a TEXCOORD), and at
// the glTF root the extension PRTKIT_lightmap — the lightmap's description (the manifest of
// io/engine_lightmaps.hpp: kind, encoding, light, exposure, quantity, the UV set and how f
// decodes) with `layers`, each a FLOAT VEC3 accessor of W × H texels (row-major, row 0 at
// v = 0) holding the encoding's unpacked numbers (LightmapLayers). Floats keep every value:
// no engine's packing or clamping applies, so the layers decode to the encoding exactly.

#include <string>

#include "prt/geometry/mesh.hpp"
#include "prt/io/engine_lightmaps.hpp"

namespace prt::io {

/// The extension's name (declared in extensionsUsed, not required: the mesh stands alone).
inline constexpr const char* kLightmapExtension = "PRTKIT_lightmap";

/// Writes `layers` beside `mesh` to `path` atomically (core/file.hpp's policy). Throws
/// prt::Error naming `path` when the mesh cannot be written, a layer does not fill the
/// lightmap, or the file would pass the 4 GiB a GLB can hold.
void writeLightmapGltf(const std::string& path, const LightmapLayers& layers, const Mesh& mesh);

}  // namespace prt::io
