// A relit lightmap as glTF with PRTKIT_lightmap (lightmap_gltf.hpp).

#include "prt/io/lightmap_gltf.hpp"

#include <cstdint>

#include "bake_mesh.hpp"
#include "glb.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"

namespace prt::io {

void writeLightmapGltf(const std::string& path, const LightmapLayers& layers, const Mesh& mesh) {
  const std::vector<MeshPart> parts = partsOf(mesh);
  try {
    checkMeshForWriting(mesh, parts);
  } catch (const Error& e) {
    throw Error(path, e.what());
  }
  const std::size_t texels = std::size_t(layers.manifest.at("lightmap").at("width").get<int>()) *
                             std::size_t(layers.manifest.at("lightmap").at("height").get<int>());
  nlohmann::json gltf = {
      {"asset", {{"generator", layers.manifest.value("generator", "prtkit")}, {"version", "2.0"}}}};
  glb::BinaryChunk bin;
  encodeMesh(mesh, parts, {}, nullptr, bin, gltf);
  nlohmann::json ext = layers.manifest;
  ext.erase("generator");
  nlohmann::json list = nlohmann::json::array();
  // Rgb is three packed floats: a layer's texels are its accessor's VEC3 elements as they lie.
  static_assert(sizeof(Rgb) == 3 * sizeof(float));
  for (const LightmapLayer& l : layers.layers) {
    if (l.texels.size() != texels)
      throw Error(path, "lightmap layer " + l.name + " holds " + std::to_string(l.texels.size()) +
                            " texels, " + std::to_string(texels) + " expected");
    const int view = bin.view(l.texels.data(), l.texels.size() * sizeof(Rgb), 0, 0,
                              "lightmap " + l.name);
    list.push_back({{"name", l.name},
                    {"accessor", bin.accessor(view, 0, l.texels.size(), "VEC3", 5126,
                                              "lightmap " + l.name)},
                    {"holds", l.holds}});
  }
  ext["layers"] = std::move(list);
  gltf["extensionsUsed"] = nlohmann::json::array({kLightmapExtension});
  gltf["extensions"][kLightmapExtension] = std::move(ext);
  gltf["accessors"] = bin.accessors();
  gltf["bufferViews"] = bin.views();
  gltf["buffers"] = nlohmann::json::array({{{"byteLength", bin.length()}}});
  std::string text = gltf.dump();
  if (glb::fileBytes(text, bin) > std::uint64_t(0xffffffffu))
    throw Error(path, "the lightmap and its mesh exceed the 4 GiB a GLB file can hold");
  writeFileAtomically(path, [&](std::ostream& os) { glb::write(os, std::move(text), bin); });
}

}  // namespace prt::io
