// glTF 2.0 meshes through prt::loadMeshBytes: .glb when the input starts with "glTF", .gltf
// (JSON) otherwise. Nothing outside the input is read (no external buffers or images).
#include "fuzz_common.hpp"
#include "prt/geometry/load.hpp"

PRT_FUZZ_TARGET({
  const bool glb = size >= 4 && prt::fuzz::text(data, 4) == "glTF";
  prt::loadMeshBytes(glb ? "fuzz.glb" : "fuzz.gltf", prt::fuzz::bytes(data, size));
})
