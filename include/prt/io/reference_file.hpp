#pragma once
// Reference files: `prt reference` output, read back by `prt validate --reference` and
// `prt render --reference` instead of recomputing the brute-force radiance (docs/validation.md).
//
// JSON:
//   {"format": "prtkit-reference", "formatVersion": 1, "prtkitVersion": "0.1.0",
//    "bake": {"file": "bunny.glb", "vertices": N, "fingerprint": "…"},
//    "light": {"source": "courtyard.exr", "fingerprint": "…", "rotation": [9 numbers, row-major]},
//    "mode": "shadowed", "bounces": 1, "material": "lambert?kd=0.8", "eye": [x, y, z],
//    "samples": 1024, "seed": 0, "mis": "power", "rays": R,
//    "vertices": [...], "radiance": [[r, g, b], ...], "stdError": [[r, g, b], ...]}
// Per texel (issue 18), "bake" also holds "lightmap": {"width": W, "height": H,
// "uvFingerprint": "…"} and the rows are "texels": [...] (texel (x, y) is y·W + x, each a valid
// texel's sample point, render/texel_points.hpp) instead of "vertices".
// The fingerprints tie a reference to the mesh and the environment it was computed for (an
// meshFingerprint of geometry/mesh.hpp, the mesh's identity in a bake checkpoint too; FNV-1a
// of the environment's texels and of its radiance along fixed directions), so a reference is never
// compared with another scene's relighting. Older reference files (before formatVersion) carry no
// fingerprints and are refused with that reason.
// Binary (.bin, no metadata, not read back): "PRTREF1\0", uint32 count, then count ×
// (uint32 vertex, 3 float radiance, 3 float standard error), little-endian.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/transfer/shape.hpp"

namespace prt::io {

inline constexpr int kReferenceFormatVersion = 1;

struct ReferenceFile {
  std::string prtkitVersion;
  std::string bakeFile;
  std::size_t meshVertices = 0;
  std::string meshFingerprint;
  std::string lightSource;
  std::string environmentFingerprint;
  std::array<double, 9> rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};  ///< row-major
  std::string mode;
  int bounces = 0;
  std::string material;
  std::optional<Vec3f> eye;  ///< the eye glossy vertices were seen from
  int samples = 0;
  std::uint64_t seed = 0;
  std::string mis;
  std::uint64_t rays = 0;
  double seconds = 0;  ///< not written (the file is deterministic); read when present
  /// Per texel (a bake over TransferDomain::Texels): the lightmap the rows are texels of, and
  /// the fingerprint of the lightmap UVs its texels' points lie on; 0 × 0 when the rows are
  /// vertices.
  int lightmapWidth = 0, lightmapHeight = 0;
  std::string lightmapUvFingerprint;
  bool texels() const { return lightmapWidth > 0; }
  TransferDomain domain() const { return texels() ? TransferDomain::Texels : TransferDomain::Vertices; }
  /// The rows it estimates are those of `shape` over `mesh`: per texel, its lightmap's size and
  /// a fingerprint of the mesh's lightmap UVs; per vertex, none.
  void setRows(const Mesh& mesh, const TransferShape& shape);
  /// The rows' bound: meshVertices, or the lightmap's texel count.
  std::size_t rowCount() const {
    return texels() ? std::size_t(lightmapWidth) * std::size_t(lightmapHeight) : meshVertices;
  }
  std::vector<std::uint32_t> vertices;  ///< the rows (vertices or texels), ascending, < rowCount()
  std::vector<Rgb> radiance, stdError;  ///< one per entry of `vertices`
};

void writeReferenceJson(const std::string& path, const ReferenceFile& ref);
void writeReferenceBinary(const std::string& path, const ReferenceFile& ref);
ReferenceFile readReferenceJson(const std::string& path);
/// The same from text in memory; `name` is used in messages.
ReferenceFile parseReferenceJson(std::string_view text, const std::string& name);

/// 16 hex digits identifying an environment (the mesh's: meshFingerprint, geometry/mesh.hpp).
std::string environmentFingerprint(const envmap::Environment& env);
/// 16 hex digits identifying a mesh's lightmap UVs (FNV-1a of them, bitwise): what a per-texel
/// reference's points depend on besides the geometry.
std::string lightmapUvFingerprint(const Mesh& mesh);

}  // namespace prt::io
