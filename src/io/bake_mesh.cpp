#include "bake_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "prt/core/error.hpp"
#include "prt/image/image_io.hpp"

namespace prt::io {

namespace {

using nlohmann::json;
constexpr int kFloat = gltf::kFloat, kUint = gltf::kUnsignedInt;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963, kTriangles = 4;
constexpr int kLinear = 9729, kRepeat = 10497;  // sampler filters and wrap modes (§5.26)

void requireFinite(const std::vector<float>& x, const std::string& what, const schema::Reader& r) {
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]))
      r.fail(what + " holds a non-finite value at element " + std::to_string(i));
}

}  // namespace

std::vector<MeshPart> partsOf(const Mesh& mesh) {
  if (!mesh.parts.empty()) return mesh.parts;
  MeshPart p;
  p.name = "mesh";
  p.vertexCount = static_cast<std::uint32_t>(mesh.vertexCount());
  p.triangleCount = static_cast<std::uint32_t>(mesh.triangleCount());
  return {p};
}

void checkMeshForWriting(const Mesh& m, const std::vector<MeshPart>& parts) {
  const std::size_t V = m.vertexCount(), T = m.triangleCount();
  if (V == 0 || T == 0) throw Error("bake file: the mesh is empty (no vertices or no triangles)");
  if (V > std::numeric_limits<std::uint32_t>::max()) throw Error("bake file: too many vertices");
  if (m.normals.size() != V) throw Error("bake file: mesh has no normal per vertex");
  if (!m.albedo.empty() && m.albedo.size() != V)
    throw Error("bake file: mesh albedo is not per vertex");
  if (!m.uvs.empty() && m.uvs.size() != V) throw Error("bake file: mesh uvs are not per vertex");
  if (!m.lightmapUvs.empty() && m.lightmapUvs.size() != V)
    throw Error("bake file: mesh lightmap uvs are not per vertex");
  if (m.baseColour) {
    const image::Srgb8Image& im = m.baseColour->image;
    if (m.uvs.size() != V)
      throw Error("bake file: the mesh's base colour texture has no texture UV per vertex");
    if (im.width < 1 || im.height < 1 ||
        im.rgb.size() != std::size_t(im.width) * std::size_t(im.height) * 3)
      throw Error("bake file: the mesh's base colour texture is not a " + std::to_string(im.width) +
                  " x " + std::to_string(im.height) + " RGB image");
  }
  std::uint32_t nextV = 0, nextT = 0;
  for (const MeshPart& p : parts) {
    if (p.firstVertex != nextV || p.firstTriangle != nextT || p.vertexCount == 0 ||
        p.triangleCount == 0)
      throw Error("bake file: mesh part '" + p.name +
                  "' does not continue the previous part or is empty");
    nextV += p.vertexCount;
    nextT += p.triangleCount;
    if (nextV > V || nextT > T)
      throw Error("bake file: mesh part '" + p.name + "' overruns the mesh");
    for (std::uint32_t t = p.firstTriangle; t < nextT; ++t)
      for (std::uint32_t i : m.triangles[t])
        if (i < p.firstVertex || i >= nextV)
          throw Error("bake file: triangle " + std::to_string(t) + " of part '" + p.name +
                      "' uses a vertex outside the part");
  }
  if (nextV != V || nextT != T) throw Error("bake file: mesh parts do not cover the mesh");
}

void encodeMesh(const Mesh& mesh, const std::vector<MeshPart>& parts,
                const std::vector<std::pair<std::string, int>>& attributes, const Rgb* baseColour,
                glb::BinaryChunk& bin, json& gltf) {
  const std::size_t V = mesh.vertexCount();
  // Shared vertex data in the scene's global order (parts view slices of it).
  const int posView = bin.view(mesh.positions.data(), V * 12, 12, kArrayBuffer, "positions");
  const int nrmView = bin.view(mesh.normals.data(), V * 12, 12, kArrayBuffer, "normals");
  const int uvView =
      mesh.uvs.empty() ? -1 : bin.view(mesh.uvs.data(), V * 8, 8, kArrayBuffer, "texcoords");
  const int lightmapView = mesh.lightmapUvs.empty() ? -1
                                                    : bin.view(mesh.lightmapUvs.data(), V * 8, 8,
                                                               kArrayBuffer, "lightmap texcoords");
  const int colView =
      mesh.albedo.empty() ? -1 : bin.view(mesh.albedo.data(), V * 12, 12, kArrayBuffer, "albedo");
  // Indices, local to each part (each part's attributes start at its first vertex), made while
  // streaming in blocks.
  const int idxView = bin.view(
      mesh.triangleCount() * 12, 0, kElementArrayBuffer, "indices",
      [&mesh, parts](std::ostream& os) {
        std::vector<std::uint32_t> block;
        for (const MeshPart& p : parts)
          for (std::uint32_t t = p.firstTriangle; t < p.firstTriangle + p.triangleCount;) {
            const std::uint32_t end = std::min(p.firstTriangle + p.triangleCount, t + 4096);
            block.clear();
            for (; t < end; ++t)
              for (int k = 0; k < 3; ++k) block.push_back(mesh.triangles[t][k] - p.firstVertex);
            os.write(reinterpret_cast<const char*>(block.data()),
                     static_cast<std::streamsize>(block.size() * 4));
          }
      });

  json material = {{"name", "prtkit default"},
                   {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
  if (baseColour && mesh.albedo.empty())
    material["pbrMetallicRoughness"]["baseColorFactor"] = {baseColour->x, baseColour->y,
                                                           baseColour->z, 1.0};
  // The base-colour texture as the material's baseColorTexture on TEXCOORD_0 (the texture set,
  // Mesh::uvs): one embedded PNG of its sRGB codes, sampled bilinearly with repeat wrapping, as
  // geometry/base_colour.hpp samples it, so a glTF viewer shows COLOR_0 × texture as prt render
  // does. The PNG is encoded once here and streamed with the binary chunk.
  if (mesh.baseColour) {
    const auto png = std::make_shared<const std::string>(
        image::encodePng(mesh.baseColour->image, "bake file: base colour texture"));
    const int imageView =
        bin.view(png->size(), 0, 0, "base colour texture",
                 [png](std::ostream& os) { os.write(png->data(), std::streamsize(png->size())); });
    gltf["images"] = json::array(
        {{{"bufferView", imageView}, {"mimeType", "image/png"}, {"name", mesh.baseColour->name}}});
    gltf["samplers"] = json::array(
        {{{"magFilter", kLinear}, {"minFilter", kLinear}, {"wrapS", kRepeat}, {"wrapT", kRepeat}}});
    gltf["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
    material["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}, {"texCoord", 0}};
  }
  json meshes = json::array(), nodes = json::array(), sceneNodes = json::array();
  for (const MeshPart& p : parts) {
    const std::size_t n = p.vertexCount;
    Vec3f lo = mesh.positions[p.firstVertex], hi = lo;
    for (std::size_t v = p.firstVertex; v < p.firstVertex + n; ++v) {
      lo = min(lo, mesh.positions[v]);
      hi = max(hi, mesh.positions[v]);
    }
    json attrs;
    attrs["POSITION"] = bin.accessor(posView, p.firstVertex * 12u, n, "VEC3", kFloat, {},
                                     {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
    attrs["NORMAL"] = bin.accessor(nrmView, p.firstVertex * 12u, n, "VEC3", kFloat);
    if (uvView >= 0)
      attrs["TEXCOORD_0"] = bin.accessor(uvView, p.firstVertex * 8u, n, "VEC2", kFloat);
    if (lightmapView >= 0)
      attrs["TEXCOORD_" + std::to_string(lightmapTexCoord(mesh))] =
          bin.accessor(lightmapView, p.firstVertex * 8u, n, "VEC2", kFloat);
    if (colView >= 0)
      attrs["COLOR_0"] = bin.accessor(colView, p.firstVertex * 12u, n, "VEC3", kFloat);
    for (const auto& [name, view] : attributes)
      attrs[name] = bin.accessor(view, p.firstVertex * 16u, n, "VEC4", kFloat);
    const int indices =
        bin.accessor(idxView, p.firstTriangle * 12u, p.triangleCount * 3u, "SCALAR", kUint);
    json primitive = {{"attributes", std::move(attrs)},
                      {"indices", indices},
                      {"material", 0},
                      {"mode", kTriangles}};
    meshes.push_back({{"name", p.name}, {"primitives", json::array({std::move(primitive)})}});
    nodes.push_back({{"name", p.name}, {"mesh", meshes.size() - 1}});
    sceneNodes.push_back(nodes.size() - 1);
  }
  gltf["materials"] = json::array({std::move(material)});
  gltf["meshes"] = std::move(meshes);
  gltf["nodes"] = std::move(nodes);
  gltf["scenes"] = json::array({{{"name", mesh.source}, {"nodes", std::move(sceneNodes)}}});
  gltf["scene"] = 0;
}

std::optional<BaseColourTexture> decodeBaseColour(const json& gltf,
                                                  const gltf::AccessorReader& accessors,
                                                  const Mesh& mesh, const schema::Reader& r) {
  const auto listed = [&](const char* key) {
    return gltf.contains(key) && gltf[key].is_array() ? gltf[key].size() : std::size_t(0);
  };
  const json* texture = nullptr;  // materials[0].pbrMetallicRoughness.baseColorTexture
  if (listed("materials") > 0 && gltf["materials"][0].is_object() &&
      gltf["materials"][0].contains("pbrMetallicRoughness") &&
      gltf["materials"][0]["pbrMetallicRoughness"].is_object() &&
      gltf["materials"][0]["pbrMetallicRoughness"].contains("baseColorTexture"))
    texture = &gltf["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"];
  if (!texture && listed("images") == 0 && listed("textures") == 0) return std::nullopt;
  // Only the layout encodeMesh writes: one PNG in the binary chunk, one texture showing it, the
  // first material's baseColorTexture on TEXCOORD_0.
  const std::string what = "the base colour texture";
  if (!texture || listed("images") != 1 || listed("textures") != 1)
    r.fail(
        "holds images or textures other than one base colour texture of material 0 (it is "
        "not a prtkit bake, or was edited)");
  if (r.integer(*texture, "index", "materials[0] baseColorTexture", 0, 0) != 0 ||
      (r.has(*texture, "texCoord") &&
       r.integer(*texture, "texCoord", "materials[0] baseColorTexture", 0, 0) != 0) ||
      r.integer(gltf["textures"][0], "source", "textures[0]", 0, 0) != 0)
    r.fail(what + " is not texture 0 on TEXCOORD_0 showing image 0");
  const json& img = gltf["images"][0];
  if (r.has(img, "uri")) r.fail("refers to an external image; a bake is one .glb");
  if (!r.has(img, "mimeType") || img["mimeType"] != "image/png")
    r.fail(what + " is not an embedded PNG (mimeType image/png)");
  if (mesh.uvs.size() != mesh.vertexCount())
    r.fail("has a base colour texture but no TEXCOORD_0 texture set to read it at");
  const auto view = r.integer(img, "bufferView", "images[0]", 0, 2147483647.0);
  const std::span<const unsigned char> bytes = accessors.viewBytes(int(view), what);
  BaseColourTexture out;
  try {
    out.image = image::readSrgb8Bytes(what, bytes);
  } catch (const Error& e) {
    r.fail(e.what());
  }
  out.name = r.has(img, "name") && img["name"].is_string() ? img["name"].get<std::string>()
                                                           : std::string("base colour texture");
  return out;
}

int lightmapTexCoord(const Mesh& mesh) {
  return mesh.lightmapUvs.empty() ? -1 : mesh.uvs.empty() ? 0 : 1;
}

Mesh decodeMesh(const json& gltf, const gltf::AccessorReader& ar, std::size_t V, std::size_t T,
                int lightmap, const schema::Reader& r) {
  Mesh mesh;
  // The texture set is the TEXCOORD_0 that is not the lightmap's.
  const std::string textureSet = lightmap == 0 ? "" : "TEXCOORD_0";
  const std::string lightmapSet = lightmap < 0 ? "" : "TEXCOORD_" + std::to_string(lightmap);
  if (!gltf.contains("meshes") || !gltf["meshes"].is_array() || gltf["meshes"].empty())
    r.fail("holds no mesh");
  // The parts: glTF meshes in order, one triangle primitive each, concatenated.
  bool anyUv = false, anyColor = false;
  const json& meshes = gltf["meshes"];
  for (std::size_t mi = 0; mi < meshes.size(); ++mi) {
    const json& gm = meshes[mi];
    const std::string name = gm.is_object() && gm.contains("name") && gm["name"].is_string()
                                 ? gm["name"].get<std::string>()
                                 : "";
    const std::string what = "mesh " + std::to_string(mi) + " ('" + name.substr(0, 60) + "')";
    if (!gm.is_object() || !gm.contains("primitives") || !gm["primitives"].is_array() ||
        gm["primitives"].size() != 1)
      r.fail(what + " does not hold exactly one primitive");
    const json& p = gm["primitives"][0];
    if (!p.is_object()) r.fail(what + "'s primitive is not an object");
    if (p.contains("mode") &&
        !(p["mode"].is_number_integer() && p["mode"].get<int>() == kTriangles))
      r.fail(what + " is not a triangle list");
    const json& attributes = r.member(p, "attributes", what);
    const auto attr = [&](const char* key) -> int {
      if (!attributes.is_object() || !attributes.contains(key)) return -1;
      const json& a = attributes[key];
      if (!a.is_number_integer() || a.get<std::int64_t>() < 0 || a.get<std::int64_t>() > 2147483647)
        r.fail(what + " attribute " + key + " is not an accessor index");
      return a.get<int>();
    };
    const int pa = attr("POSITION");
    if (pa < 0) r.fail(what + " has no POSITION");
    const std::size_t n = ar.count(pa, what + " POSITION");
    if (n == 0 || mesh.positions.size() + n > V)
      r.fail(what + " has more vertices than the bake's vertexCount");
    MeshPart part;
    part.name = name;
    part.firstVertex = static_cast<std::uint32_t>(mesh.positions.size());
    part.vertexCount = static_cast<std::uint32_t>(n);
    part.firstTriangle = static_cast<std::uint32_t>(mesh.triangles.size());

    const auto pos = ar.exact<float>(pa, 3, kFloat, n, what + " POSITION");
    const auto nrm = ar.exact<float>(attr("NORMAL"), 3, kFloat, n, what + " NORMAL");
    requireFinite(pos, what + " POSITION", r);
    requireFinite(nrm, what + " NORMAL", r);
    for (std::size_t v = 0; v < n; ++v) {
      mesh.positions.emplace_back(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
      mesh.normals.emplace_back(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
    }
    const bool hasUv = !textureSet.empty() && attr(textureSet.c_str()) >= 0,
               hasColor = attr("COLOR_0") >= 0;
    if (mi > 0 && (hasUv != anyUv || hasColor != anyColor))
      r.fail(what + " differs from the first part in TEXCOORD_0/COLOR_0");
    anyUv = hasUv;
    anyColor = hasColor;
    if (hasUv) {
      const auto uv = ar.exact<float>(attr("TEXCOORD_0"), 2, kFloat, n, what + " TEXCOORD_0");
      for (std::size_t v = 0; v < n; ++v) mesh.uvs.push_back({uv[2 * v], uv[2 * v + 1]});
    }
    if (!lightmapSet.empty()) {
      if (attr(lightmapSet.c_str()) < 0)
        r.fail(what + " has no " + lightmapSet + " (lightmapTexCoord names it)");
      const auto uv =
          ar.exact<float>(attr(lightmapSet.c_str()), 2, kFloat, n, what + " " + lightmapSet);
      requireFinite(uv, what + " " + lightmapSet, r);
      for (std::size_t v = 0; v < n; ++v) mesh.lightmapUvs.push_back({uv[2 * v], uv[2 * v + 1]});
    }
    if (hasColor) {
      const auto c = ar.exact<float>(attr("COLOR_0"), 3, kFloat, n, what + " COLOR_0");
      requireFinite(c, what + " COLOR_0", r);
      for (std::size_t v = 0; v < n; ++v)
        mesh.albedo.emplace_back(c[3 * v], c[3 * v + 1], c[3 * v + 2]);
    }
    const json& idxValue = r.member(p, "indices", what);
    if (!idxValue.is_number_integer() || idxValue.get<std::int64_t>() < 0 ||
        idxValue.get<std::int64_t>() > 2147483647)
      r.fail(what + " has no indices");
    const int indices = idxValue.get<int>();
    const std::size_t ni = ar.count(indices, what + " indices");
    if (ni == 0 || ni % 3 != 0)
      r.fail(what + ": index count " + std::to_string(ni) + " is not a positive multiple of 3");
    if (mesh.triangles.size() + ni / 3 > T)
      r.fail(what + " has more triangles than the bake's triangleCount");
    const auto idx = ar.exact<std::uint32_t>(indices, 1, kUint, ni, what + " indices");
    for (std::size_t t = 0; t < ni / 3; ++t) {
      std::array<std::uint32_t, 3> tri;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = idx[3 * t + k];
        if (i >= n)
          r.fail(what + ": triangle " + std::to_string(t) + " references vertex " +
                 std::to_string(i) + " (part has " + std::to_string(n) + ")");
        tri[k] = i + part.firstVertex;
      }
      mesh.triangles.push_back(tri);
    }
    part.triangleCount = static_cast<std::uint32_t>(ni / 3);
    mesh.parts.push_back(part);
  }
  if (mesh.positions.size() != V || mesh.triangles.size() != T)
    r.fail("the meshes hold " + std::to_string(mesh.positions.size()) + " vertices and " +
           std::to_string(mesh.triangles.size()) + " triangles, the bake says " +
           std::to_string(V) + " and " + std::to_string(T));
  return mesh;
}

}  // namespace prt::io
