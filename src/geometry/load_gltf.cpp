// glTF 2.0 (.gltf with external or embedded buffers, .glb) through tinygltf.
//
// Every primitive of mode TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN reachable from the default
// scene (scene 0 if none is marked; every mesh untransformed if the file has no scenes) is
// appended in scene-graph order (depth first, children in order), one MeshPart per node that
// holds a mesh. Vertices keep the file's order within each primitive; nothing is welded.
//
// Transforms: a node's world matrix is its parent's times its local matrix, the local matrix
// being `matrix` or T·R·S (glTF 2.0 §3.5.2). Positions take the world matrix M; normals the
// inverse transpose of its upper 3×3 (then renormalised); a mirroring matrix (det < 0) reverses
// the triangles' winding so counter-clockwise stays front.
//
// Albedo (§3.9.2): baseColorFactor (linear) × baseColorTexture (sRGB-encoded, decoded to linear;
// (0,0) is the image's top left corner) × COLOR_0 (linear). Primitives without a material use
// the default material (white). A file whose primitives have neither materials nor COLOR_0
// leaves the albedo empty.
//
// The texture: when every triangle primitive uses the same image as its baseColorTexture, on
// TEXCOORD_0, it is kept as the mesh's base-colour texture (geometry/base_colour.hpp) and the
// albedo holds baseColorFactor × COLOR_0 alone, so images multiply the texture per pixel.
// Otherwise (textures that differ between primitives, a primitive without one, another UV set)
// each texture is sampled bilinearly at the vertices into the albedo, with a warning. Images
// are decoded by image::readSrgb8Bytes (PNG and JPEG, sizes checked before any allocation); one
// that is missing or cannot be decoded is not used, with a warning naming it.

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>

#include "loaders.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/base_colour.hpp"
#include "prt/gltf/accessor.hpp"
#include "prt/image/image_io.hpp"

namespace prt::detail {

namespace {

/// Column-major 4x4 matrix, as glTF stores it: m[c * 4 + r].
struct Mat4 {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  Mat4 operator*(const Mat4& o) const {
    Mat4 r;
    for (int c = 0; c < 4; ++c)
      for (int row = 0; row < 4; ++row) {
        double s = 0;
        for (int k = 0; k < 4; ++k) s += m[k * 4 + row] * o.m[c * 4 + k];
        r.m[c * 4 + row] = s;
      }
    return r;
  }
  Vec3d point(const Vec3d& p) const {
    return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
            m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
            m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
  }
  Mat3d upper() const {
    Mat3d r;
    for (int row = 0; row < 3; ++row)
      for (int c = 0; c < 3; ++c) r.m[row][c] = m[c * 4 + row];
    return r;
  }
};

double det(const Mat3d& a) {
  const auto& m = a.m;
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/// Inverse transpose by cofactors (the adjugate's transpose is the cofactor matrix; the 1/det
/// scale does not matter for normals, except its sign, which we keep).
Mat3d normalMatrix(const Mat3d& a) {
  const auto& m = a.m;
  Mat3d c;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      c.m[r][k] = m[r1][k1] * m[r2][k2] - m[r1][k2] * m[r2][k1];
    }
  const double d = det(a);
  if (d < 0)
    for (auto& row : c.m)
      for (double& x : row) x = -x;
  return c;
}

Mat4 localMatrix(const tinygltf::Node& n) {
  Mat4 out;
  if (n.matrix.size() == 16) {
    for (int k = 0; k < 16; ++k) out.m[k] = n.matrix[k];
    return out;
  }
  Mat4 t, r, s;
  if (n.translation.size() == 3)
    for (int k = 0; k < 3; ++k) t.m[12 + k] = n.translation[k];
  if (n.rotation.size() == 4) {
    double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    const double len = std::sqrt(x * x + y * y + z * z + w * w);
    if (len > 0) x /= len, y /= len, z /= len, w /= len;
    // Unit quaternion to rotation matrix, column-major.
    r.m = {1 - 2 * (y * y + z * z),
           2 * (x * y + z * w),
           2 * (x * z - y * w),
           0,
           2 * (x * y - z * w),
           1 - 2 * (x * x + z * z),
           2 * (y * z + x * w),
           0,
           2 * (x * z + y * w),
           2 * (y * z - x * w),
           1 - 2 * (x * x + y * y),
           0,
           0,
           0,
           0,
           1};
  }
  if (n.scale.size() == 3)
    for (int k = 0; k < 3; ++k) s.m[k * 5] = n.scale[k];
  return t * r * s;
}

/// Why an image could not be decoded, by image index (filled by loadImage while tinygltf parses).
using ImageFailures = std::map<int, std::string>;

/// The model's accessors (through the one checked reader, prt/gltf/accessor.hpp) and its base
/// colour textures.
class Reader {
 public:
  Reader(const std::string& label, const tinygltf::Model& model, const ImageFailures& failures,
         LoadReport& report)
      : label_(label),
        model_(model),
        failures_(failures),
        report_(report),
        accessors_(label, gltf::documentOf(model)) {}

  /// Accessor `index` as `count` × `comps` floats (normalised integers mapped per §3.11).
  std::vector<float> floats(int index, int comps, const char* what) {
    return accessors_.floats(index, comps, what);
  }
  /// COLOR_0: RGB or RGBA (the alpha is read and ignored).
  std::vector<float> colours(int index, int& comps) {
    comps = accessors_.components(index, "COLOR_0") == 4 ? 4 : 3;
    return accessors_.floats(index, comps, "COLOR_0");
  }
  std::vector<std::uint32_t> indices(int index) { return accessors_.indices(index, "indices"); }
  std::size_t count(int index, const char* what) { return accessors_.count(index, what); }

  /// The image texture `tex` shows, or −1.
  int imageOf(int tex) const {
    if (tex < 0 || tex >= int(model_.textures.size())) return -1;
    const int src = model_.textures[tex].source;
    return src >= 0 && src < int(model_.images.size()) ? src : -1;
  }
  /// Image `src` as a base colour texture, converted once; nullptr (and one warning) when it
  /// could not be read.
  const BaseColourTexture* texture(int src) {
    if (src < 0 || src >= int(model_.images.size())) return nullptr;
    auto it = textures_.find(src);
    if (it != textures_.end()) return it->second ? &*it->second : nullptr;
    std::optional<BaseColourTexture>& out = textures_[src];
    const tinygltf::Image& im = model_.images[src];
    std::string name = "image " + std::to_string(src);
    if (!im.uri.empty() && im.uri.rfind("data:", 0) != 0)
      name += " (" + im.uri.substr(0, 80) + ")";
    else if (!im.name.empty())
      name += " ('" + im.name.substr(0, 60) + "')";
    // loadImage stores what it decoded as 8-bit RGB codes; anything else is a failure.
    if (im.component == 3 && im.bits == 8 && im.width > 0 && im.height > 0 &&
        im.image.size() == std::size_t(im.width) * std::size_t(im.height) * 3) {
      out = BaseColourTexture{{im.width, im.height, im.image}, name};
      return &*out;
    }
    const auto why = failures_.find(src);
    report_.warnings.push_back(label_ + ": " + name + ": base colour texture not used: " +
                               (why != failures_.end() ? why->second
                                : !im.uri.empty()
                                    ? std::string("the file cannot be read (missing, or not a "
                                                  "regular file beside the glTF)")
                                    : std::string("no image data")));
    return nullptr;
  }

  [[noreturn]] void fail(const std::string& msg) const { throw Error(label_, msg); }

 private:
  const std::string& label_;
  const tinygltf::Model& model_;
  const ImageFailures& failures_;
  LoadReport& report_;
  gltf::AccessorReader accessors_;
  std::map<int, std::optional<BaseColourTexture>> textures_;
};

}  // namespace

namespace {

// File access for tinygltf (external buffers and images): regular files only, read through
// readFileBytes (so under the file-size cap), never a device or a pipe. In memory mode (fuzzing,
// decodeBake-like callers) nothing outside the bytes given is read.
struct FsContext {
  bool allowFiles = true;
};

bool fsExists(const std::string& path, void* user) {
  if (!static_cast<FsContext*>(user)->allowFiles) return false;
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}
std::string fsExpand(const std::string& path, void*) {
  return path;
}
bool fsRead(std::vector<unsigned char>* out, std::string* err, const std::string& path,
            void* user) {
  if (!fsExists(path, user)) {
    if (err) *err += "external file " + path + " not found\n";
    return false;
  }
  try {
    *out = readFileBytes(path);
    return true;
  } catch (const Error& e) {
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}
bool fsWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed\n";
  return false;
}

/// tinygltf hands every image's bytes (embedded, data: URI, or an external file read through
/// fsRead) to this callback while parsing. Decoded by the image module's checked reader (PNG and
/// JPEG, the declared size against the limits before anything is allocated, so a 100-byte PNG
/// header cannot ask for gigabytes) into 8-bit RGB codes. An image that fails is not fatal for
/// the mesh: its reason is kept for Reader::texture's warning and the image left empty.
bool loadImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
  try {
    image::Srgb8Image img = image::readSrgb8Bytes(
        "", std::span<const unsigned char>(bytes, std::size_t(std::max(size, 0))));
    image->width = img.width;
    image->height = img.height;
    image->component = 3;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(img.rgb);
  } catch (const Error& e) {
    (*static_cast<ImageFailures*>(user))[index] = e.what();
    image->image.clear();
  }
  return true;
}

}  // namespace

Mesh readGltf(const std::string& path, LoadReport& report) {
  {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
      throw Error(path, "cannot open (does it exist and is it readable?)");
  }
  const std::vector<unsigned char> bytes = readFileBytes(path);
  const std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  const bool binary = ext == ".glb" || ext == ".GLB";
  return readGltfBytes(path, bytes, binary, std::filesystem::path(path).parent_path().string(),
                       true, report);
}

namespace {

/// The mesh a glTF scene makes: every triangle primitive of every mesh instance, transformed to
/// world space, with its normals, its first UV set, and an albedo from the base colour factor,
/// texture and COLOR_0 (all white where one primitive has an albedo and another has none); the
/// texture kept apart when every primitive shares one (see the file comment).
class GltfMeshBuilder {
 public:
  GltfMeshBuilder(const std::string& path, const tinygltf::Model& model,
                  const ImageFailures& failures, LoadReport& report)
      : path_(path), model_(model), report_(report), rd_(path, model, failures, report) {}

  /// Mesh `meshIndex` instanced with `world` as one part.
  void addMesh(int meshIndex, const Mat4& world, const std::string& partName);
  /// The default scene's node tree (or, without scenes, every mesh once).
  void addScene();
  Mesh finish();

 private:
  /// Base colour factor and texture of a primitive's material (and its UVs for the texture);
  /// records the first material's metallic-roughness as the mesh's gloss.
  struct Surface {
    bool hasMaterial = false;
    Rgb factor{1.0f};
    const BaseColourTexture* texture = nullptr;
    int image = -1;     ///< the texture's image
    int texCoord = -1;  ///< the UV set it reads
    std::vector<float> uv;
  };
  Surface surfaceOf(const tinygltf::Primitive& prim);
  void addPrimitive(const tinygltf::Mesh& gm, std::size_t pi, const Mat4& world);
  void addTriangles(int mode, const std::vector<std::uint32_t>& idx, std::uint32_t base,
                    bool mirror);

  const std::string& path_;
  const tinygltf::Model& model_;
  LoadReport& report_;
  Reader rd_;
  Mesh mesh_;
  bool anyAlbedo_ = false, anyNormals_ = false;
  bool noLightmap_ = false;  // some primitive lacks TEXCOORD_1: the mesh has no lightmap set
  // Per vertex: the albedo with the texture sampled at the vertex, and without it (factor ×
  // COLOR_0); finish() keeps one.
  std::vector<Rgb> albedo_, untextured_;
  // The image every primitive so far shows on TEXCOORD_0 (−1: none), until two differ.
  int sharedImage_ = -1;
  bool firstPrimitive_ = true, oneTexture_ = true, anyTexture_ = false;
};

void GltfMeshBuilder::addMesh(int meshIndex, const Mat4& world, const std::string& partName) {
  if (meshIndex < 0 || meshIndex >= int(model_.meshes.size()))
    rd_.fail("node refers to mesh " + std::to_string(meshIndex) + " (file has " +
             std::to_string(model_.meshes.size()) + ")");
  const tinygltf::Mesh& gm = model_.meshes[meshIndex];
  MeshPart part;
  part.name = partName.empty() ? (gm.name.empty() ? "mesh " + std::to_string(meshIndex) : gm.name)
                               : partName;
  part.firstVertex = std::uint32_t(mesh_.positions.size());
  part.firstTriangle = std::uint32_t(mesh_.triangles.size());
  for (std::size_t pi = 0; pi < gm.primitives.size(); ++pi) addPrimitive(gm, pi, world);
  part.vertexCount = std::uint32_t(mesh_.positions.size()) - part.firstVertex;
  part.triangleCount = std::uint32_t(mesh_.triangles.size()) - part.firstTriangle;
  if (part.vertexCount) mesh_.parts.push_back(part);
}

GltfMeshBuilder::Surface GltfMeshBuilder::surfaceOf(const tinygltf::Primitive& prim) {
  Surface out;
  if (prim.material < 0 || prim.material >= int(model_.materials.size())) return out;
  const tinygltf::Material& mat = model_.materials[prim.material];
  out.hasMaterial = true;
  const auto& f = mat.pbrMetallicRoughness.baseColorFactor;
  if (f.size() >= 3) out.factor = Rgb{float(f[0]), float(f[1]), float(f[2])};
  if (!mesh_.gloss) {
    // glTF §3.9.2: F0 = mix(0.04, baseColor, metallic); the lobe's roughness is
    // roughnessFactor (textures of either are not sampled here).
    const double m = mat.pbrMetallicRoughness.metallicFactor;
    const double r = mat.pbrMetallicRoughness.roughnessFactor;
    if (!(std::isfinite(m) && std::isfinite(r) && m >= 0 && m <= 1 && r >= 0 && r <= 1))
      rd_.fail("material '" + mat.name.substr(0, 80) +
               "': metallicFactor and roughnessFactor must lie in [0, 1]");
    SurfaceGloss g;
    g.model = SurfaceGloss::Model::MetallicRoughness;
    g.metallic = float(m);
    g.roughness = float(r);
    g.specular = Rgb(0.04f * float(1 - m)) + out.factor * float(m);
    g.material = mat.name.substr(0, 80);
    mesh_.gloss = g;
  }
  const auto& bt = mat.pbrMetallicRoughness.baseColorTexture;
  if (bt.index >= 0) {
    const std::string set = "TEXCOORD_" + std::to_string(std::max(0, bt.texCoord));
    const auto it = prim.attributes.find(set);
    if (it != prim.attributes.end()) {
      out.image = rd_.imageOf(bt.index);
      out.texture = rd_.texture(out.image);
      if (out.texture) {
        out.texCoord = std::max(0, bt.texCoord);
        out.uv = rd_.floats(it->second, 2, set.c_str());
      }
    }
  }
  return out;
}

void GltfMeshBuilder::addPrimitive(const tinygltf::Mesh& gm, std::size_t pi, const Mat4& world) {
  const tinygltf::Primitive& prim = gm.primitives[pi];
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    report_.warnings.push_back(path_ + ": mesh '" + gm.name + "' primitive " + std::to_string(pi) +
                               " is points or lines; skipped");
    return;
  }
  const auto attr = [&](const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const int posAcc = attr("POSITION");
  if (posAcc < 0)
    rd_.fail("mesh '" + gm.name + "' primitive " + std::to_string(pi) + " has no POSITION");
  // A mesh instanced by many nodes is copied per instance: cap the total as it grows.
  checkLimit(path_, "vertex count", mesh_.positions.size() + rd_.count(posAcc, "POSITION"),
             limits().maxVertices, "PRT_MAX_VERTICES");
  const std::vector<float> pos = rd_.floats(posAcc, 3, "POSITION");
  const std::size_t n = pos.size() / 3;
  const std::uint32_t base = std::uint32_t(mesh_.positions.size());
  std::vector<float> nrm, col, uv0, uv1;
  if (attr("NORMAL") >= 0) {
    nrm = rd_.floats(attr("NORMAL"), 3, "NORMAL");
    anyNormals_ = true;
  }
  int colComps = 0;
  if (attr("COLOR_0") >= 0) col = rd_.colours(attr("COLOR_0"), colComps);
  const Surface surface = surfaceOf(prim);
  if (attr("TEXCOORD_0") >= 0) uv0 = rd_.floats(attr("TEXCOORD_0"), 2, "TEXCOORD_0");
  if (attr("TEXCOORD_1") >= 0) uv1 = rd_.floats(attr("TEXCOORD_1"), 2, "TEXCOORD_1");
  if ((!nrm.empty() && nrm.size() != pos.size()) ||
      (!surface.uv.empty() && surface.uv.size() != 2 * n) ||
      (!uv0.empty() && uv0.size() != 2 * n) || (!uv1.empty() && uv1.size() != 2 * n) ||
      (!col.empty() && col.size() != n * colComps))
    rd_.fail("mesh '" + gm.name + "' primitive " + std::to_string(pi) +
             ": attributes have different counts");
  if ((surface.hasMaterial || !col.empty()) && !anyAlbedo_) {
    anyAlbedo_ = true;
    albedo_.assign(mesh_.positions.size(), Rgb(1.0f));  // earlier primitives: default material
    untextured_ = albedo_;
  }
  // One texture for the scene: the same image on TEXCOORD_0 in every primitive.
  const int image = surface.texture && surface.texCoord == 0 ? surface.image : -1;
  anyTexture_ |= surface.texture != nullptr;
  if (firstPrimitive_) sharedImage_ = image;
  oneTexture_ &= image == sharedImage_;
  firstPrimitive_ = false;
  if (!uv0.empty() && mesh_.uvs.size() < mesh_.positions.size())
    mesh_.uvs.resize(mesh_.positions.size());
  // TEXCOORD_1, the lightmap set engines read: kept only when every primitive has one.
  if (uv1.empty() || (!mesh_.positions.empty() && mesh_.lightmapUvs.empty())) {
    mesh_.lightmapUvs.clear();
    noLightmap_ = true;
  }
  const Mat3d nm = normalMatrix(world.upper());
  for (std::size_t i = 0; i < n; ++i) {
    mesh_.positions.push_back(Vec3f(world.point({pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]})));
    if (nrm.empty()) {
      mesh_.normals.push_back(Vec3f(0.0f));  // marks "compute"
    } else {
      const Vec3d nn = nm * Vec3d{nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]};
      const double len = length(nn);
      mesh_.normals.push_back(len > 0 ? Vec3f(nn / len) : Vec3f(0.0f));
    }
    if (!uv0.empty())
      mesh_.uvs.push_back({uv0[2 * i], uv0[2 * i + 1]});
    else if (!mesh_.uvs.empty())
      mesh_.uvs.push_back({});
    if (!noLightmap_) mesh_.lightmapUvs.push_back({uv1[2 * i], uv1[2 * i + 1]});
    if (anyAlbedo_) {
      Rgb a = surface.factor, plain = surface.factor;
      if (surface.texture)
        a *= sampleBaseColour(*surface.texture, {surface.uv[2 * i], surface.uv[2 * i + 1]});
      if (!col.empty()) {
        const Rgb c{col[colComps * i], col[colComps * i + 1], col[colComps * i + 2]};
        a *= c;
        plain *= c;
      }
      albedo_.push_back(a);
      untextured_.push_back(plain);
    }
  }
  std::vector<std::uint32_t> idx;
  if (prim.indices >= 0) {
    idx = rd_.indices(prim.indices);
  } else {
    idx.resize(n);
    for (std::size_t i = 0; i < n; ++i) idx[i] = std::uint32_t(i);
  }
  for (std::size_t k = 0; k < idx.size(); ++k)
    if (idx[k] >= n) throwBadIndex(path_, k / 3, idx[k], n);
  addTriangles(mode, idx, base, det(world.upper()) < 0);
}

void GltfMeshBuilder::addTriangles(int mode, const std::vector<std::uint32_t>& idx,
                                   std::uint32_t base, bool mirror) {
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (mirror) std::swap(b, c);
    mesh_.triangles.push_back({base + a, base + b, base + c});
  };
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (std::size_t k = 0; k + 2 < idx.size(); k += 3) add(idx[k], idx[k + 1], idx[k + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t k = 0; k + 2 < idx.size(); ++k)
      k % 2 == 0 ? add(idx[k], idx[k + 1], idx[k + 2]) : add(idx[k + 1], idx[k], idx[k + 2]);
  } else {
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) add(idx[0], idx[k], idx[k + 1]);
  }
}

void GltfMeshBuilder::addScene() {
  if (model_.scenes.empty()) {
    for (int m = 0; m < int(model_.meshes.size()); ++m) addMesh(m, Mat4{}, "");
    return;
  }
  const int s = model_.defaultScene >= 0 && model_.defaultScene < int(model_.scenes.size())
                    ? model_.defaultScene
                    : 0;
  // Depth first, children in order, without recursion (a chain of 10^5 nodes must not overflow
  // the stack); a node on the current path again is a cycle, a path deeper than the nesting
  // limit is refused.
  const std::uint64_t maxDepth = limits().maxNesting;
  std::vector<char> onPath(model_.nodes.size(), 0);
  struct Frame {
    int node;
    Mat4 world;
    std::size_t next = 0;  // next child to visit
  };
  std::vector<Frame> stack;
  std::size_t instances = 0;
  const std::size_t maxInstances = std::max<std::size_t>(1000000, 4 * model_.nodes.size());
  const auto enter = [&](int node, const Mat4& parent) {
    if (node < 0 || node >= int(model_.nodes.size()))
      rd_.fail("scene refers to node " + std::to_string(node) + " (file has " +
               std::to_string(model_.nodes.size()) + ")");
    if (onPath[node])
      rd_.fail("node " + std::to_string(node) + " is its own ancestor (cycle in the scene graph)");
    // A node shared by several parents is visited once per path: a chain of nodes each
    // listing the next twice makes 2^depth paths. Cap the instances.
    if (++instances > maxInstances)
      rd_.fail("scene graph instantiates more than " + std::to_string(maxInstances) +
               " nodes (shared subtrees)");
    if (stack.size() >= maxDepth)
      rd_.fail("scene graph deeper than " + std::to_string(maxDepth) + " levels (PRT_MAX_NESTING)");
    onPath[node] = 1;
    const tinygltf::Node& nd = model_.nodes[node];
    stack.push_back(Frame{node, parent * localMatrix(nd)});
    if (nd.mesh >= 0) addMesh(nd.mesh, stack.back().world, nd.name);
  };
  for (int root : model_.scenes[s].nodes) {
    enter(root, Mat4{});
    while (!stack.empty()) {
      Frame& f = stack.back();
      const tinygltf::Node& nd = model_.nodes[f.node];
      if (f.next < nd.children.size()) {
        const int child = nd.children[f.next++];
        const Mat4 world = f.world;  // `f` may move when the stack grows
        enter(child, world);
      } else {
        onPath[f.node] = 0;
        stack.pop_back();
      }
    }
  }
}

Mesh GltfMeshBuilder::finish() {
  if (mesh_.positions.empty()) throw Error(path_, "has no triangle meshes in its scene");
  const bool keepTexture = oneTexture_ && sharedImage_ >= 0 && anyAlbedo_;
  if (keepTexture) {
    mesh_.baseColour = *rd_.texture(sharedImage_);
    mesh_.albedo = std::move(untextured_);
  } else if (anyAlbedo_) {
    mesh_.albedo = std::move(albedo_);
    if (anyTexture_)
      report_.warnings.push_back(
          path_ +
          ": the primitives do not all use one base colour texture on TEXCOORD_0, so each "
          "texture is sampled at the vertices only (prtkit applies one texture per scene per "
          "pixel)");
  }
  if (!anyNormals_) mesh_.normals.clear();  // all computed, no warning
  if (!mesh_.uvs.empty() && mesh_.uvs.size() != mesh_.positions.size())
    mesh_.uvs.resize(mesh_.positions.size());
  return std::move(mesh_);
}

}  // namespace

Mesh readGltfBytes(const std::string& path, std::span<const unsigned char> bytes, bool binary,
                   const std::string& baseDir, bool allowFiles, LoadReport& report) {
  // tinygltf parses with nlohmann::json and then walks the tree recursively (extras, extensions):
  // refuse deep nesting before either sees the bytes.
  checkGltfNesting(path, bytes);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  FsContext fsContext{allowFiles};
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&fsExists, &fsExpand, &fsRead, &fsWrite, &fsContext});
  ImageFailures imageFailures;
  loader.SetImageLoader(&loadImage, &imageFailures);
  std::string err, warn;
  if (bytes.size() > std::numeric_limits<unsigned int>::max())
    throw Error(path, "file too large for a glTF");
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                           static_cast<unsigned int>(bytes.size()), baseDir)
             : loader.LoadASCIIFromString(&model, &err, &warn,
                                          reinterpret_cast<const char*>(bytes.data()),
                                          static_cast<unsigned int>(bytes.size()), baseDir);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    if (const auto nl = err.find('\n'); nl != std::string::npos) err.resize(nl);
    if (err.size() > 200) err = err.substr(0, 200) + "...";
    throw Error(path, err.empty() ? "cannot parse glTF" : err);
  }
  GltfMeshBuilder builder(path, model, imageFailures, report);
  builder.addScene();
  return builder.finish();
}

}  // namespace prt::detail
