#include "prt/io/mesh_file.hpp"

#include <cstdint>
#include <sstream>

#include "bake_mesh.hpp"
#include "glb.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"

namespace prt {

namespace {

void streamMeshGlb(const Mesh& source, const std::string& generator, std::ostream& os) {
  // Without a texture set the lightmap set is also TEXCOORD_0 (encodeMesh then writes it as
  // TEXCOORD_1 beside it).
  const Mesh* meshPtr = &source;
  Mesh withTexture;
  if (source.uvs.empty() && !source.lightmapUvs.empty()) {
    withTexture = source;
    withTexture.uvs = source.lightmapUvs;
    meshPtr = &withTexture;
  }
  const Mesh& mesh = *meshPtr;
  const std::vector<MeshPart> parts = io::partsOf(mesh);
  try {
    io::checkMeshForWriting(mesh, parts);
  } catch (const Error& e) {
    std::string why = e.what();
    if (why.rfind("bake file: ", 0) == 0) why.erase(0, 11);
    throw Error("mesh file: " + why);
  }
  io::glb::BinaryChunk bin;
  nlohmann::json gltf = {{"asset", {{"generator", generator}, {"version", "2.0"}}}};
  io::encodeMesh(mesh, parts, {}, nullptr, bin, gltf);
  gltf["accessors"] = bin.accessors();
  gltf["bufferViews"] = bin.views();
  gltf["buffers"] = nlohmann::json::array({{{"byteLength", bin.length()}}});
  std::string text = gltf.dump();
  if (io::glb::fileBytes(text, bin) > std::uint64_t(0xffffffffu))
    throw Error("mesh file: the mesh exceeds the 4 GiB a GLB file can hold");
  io::glb::write(os, std::move(text), bin);
}

}  // namespace

std::string encodeMeshGlb(const Mesh& mesh, const std::string& generator) {
  std::ostringstream out;
  streamMeshGlb(mesh, generator, out);
  return out.str();
}

void writeMeshGlb(const std::string& path, const Mesh& mesh, const std::string& generator) {
  try {
    writeFileAtomically(path, [&](std::ostream& os) { streamMeshGlb(mesh, generator, os); });
  } catch (const Error& e) {
    const std::string what = e.what();
    throw Error(what.rfind(path, 0) == 0 ? what : path + ": " + what);
  }
}

}  // namespace prt
