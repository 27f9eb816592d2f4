#pragma once
// Internal: the per-format readers behind loadMesh. Each returns the raw mesh as the file holds
// it (positions, normals where the file has them — a zero normal marks "none for this vertex",
// albedo, uvs, triangles with indices already checked against the vertex count); loadMesh then
// validates and cleans it up in one place (finishMesh).

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "prt/geometry/load.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/image/image.hpp"

namespace prt::detail {

Mesh readObj(const std::string& path, LoadReport& report);
/// OBJ from memory: mtllib names resolve to files in `baseDir`, or all to `*mtlText` when it is
/// given (textures are then not read).
Mesh readObjText(const std::string& label, std::string_view text, const std::string& baseDir,
                 const std::string* mtlText, LoadReport& report);
Mesh readPly(const std::string& label, std::span<const unsigned char> bytes, LoadReport& report);
Mesh readOff(const std::string& label, std::string_view text, LoadReport& report);
Mesh readGltf(const std::string& path, LoadReport& report);
/// glTF from memory (.glb when `binary`); external buffers and images are read from `baseDir`
/// only when `allowFiles`.
Mesh readGltfBytes(const std::string& label, std::span<const unsigned char> bytes, bool binary,
                   const std::string& baseDir, bool allowFiles, LoadReport& report);

/// The OFF header keywords readOff takes (ending in OFF: OFF, COFF, NOFF, CNOFF).
bool isOffKeyword(std::string_view key);

/// Inflates gzip (or zlib) data, streamed, refusing more than limits().maxDecompressedBytes of
/// output; throws Error(label, ...) on corrupt, truncated or oversized input. With `format`
/// ("ply" or "off") the output's header is checked as soon as the first bytes are out (within
/// the first 64 KiB), so a bomb that is not that format stops there instead of at the cap.
std::vector<unsigned char> gunzip(const std::string& label, std::span<const unsigned char> bytes,
                                  std::string_view format = {});

/// Validates a freshly read mesh and brings it to the invariants stated in load.hpp.
void finishMesh(Mesh& m, const std::string& label, LoadReport& report);

/// "face 12 references vertex 900 (mesh has 512)" as an Error naming `label`.
[[noreturn]] void throwBadIndex(const std::string& label, std::size_t face, long long index,
                                std::size_t count, const char* what = "vertex");

}  // namespace prt::detail
