// Wavefront OBJ through tinyobjloader, with our own vertex numbering.
//
// Vertex order (relied on by the GAMES202 course's transport.txt, whose rows are per vertex):
// one vertex per distinct (position, texcoord, normal) index triple, numbered in order of first
// appearance as the faces are read in file order, each face's corners in order. This is what the
// course's Nori-based OBJ loader does (an unordered_map from the triple to its index, filled while
// walking the faces). Triples are compared by index, never by value: only exact duplicates are
// welded, so a position used with two normals or two UVs stays two vertices. Polygons are
// fan-triangulated (0,1,2), (0,2,3), ..., which does not change the order of first appearance.
//
// Albedo: the face's material Kd, multiplied by map_Kd (decoded from sRGB by the image module),
// as the MTL specification states. A vertex takes the material of the first face that uses it.
// A file without materials leaves the albedo empty (uniform).
//
// The texture: when every face has a material whose map_Kd is the same image file, and a
// texture coordinate at every corner, it is kept as the mesh's base-colour texture
// (geometry/base_colour.hpp, stored bottom row first since OBJ's v runs up) and the albedo is
// Kd alone, so images multiply the texture per pixel. Otherwise each map_Kd is sampled
// bilinearly at the vertices into the albedo, with a warning. A map_Kd that is missing or
// cannot be decoded is not used, with a warning naming the file (as a missing .mtl is).

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>

#include "loaders.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/base_colour.hpp"
#include "prt/image/image_io.hpp"

namespace prt::detail {

namespace {

/// tinyobjloader silently reads a malformed number ("nan", "1e999") as 0 or inf, and an index
/// too large for an int wraps to some valid vertex; scan the lines ourselves so such a file is
/// rejected with its line number. Checked: every number on v, vn and vt lines (finite, within
/// float range) and every index on f, l and p lines (an integer that fits in 32 bits).
void checkObjText(const std::string& label, std::string_view text) {
  const char* s = text.data();
  const char* end = s + text.size();
  std::size_t line = 1;
  const auto isBlank = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  };
  const auto fail = [&](const std::string& msg) {
    throw Error(label, "line " + std::to_string(line) + ": " + msg);
  };
  while (s < end) {
    const char* eol = static_cast<const char*>(std::memchr(s, '\n', end - s));
    if (!eol) eol = end;
    const char* p = s;
    while (p < eol && isBlank(*p)) ++p;
    const char* kw = p;
    while (p < eol && !isBlank(*p)) ++p;
    const std::string_view key(kw, p - kw);
    const bool vertex = key == "v" || key == "vn" || key == "vt";
    const bool element = key == "f" || key == "l" || key == "p";
    if (vertex || element) {
      int count = 0;
      while (true) {
        while (p < eol && isBlank(*p)) ++p;
        if (p >= eol || *p == '#') break;
        const char* tok = p;
        while (p < eol && !isBlank(*p)) ++p;
        const std::string_view t(tok, p - tok);
        ++count;
        if (vertex) {
          double x = 0;
          const char* num = (!t.empty() && t[0] == '+') ? tok + 1 : tok;  // from_chars rejects '+'
          const auto [ptr, ec] = std::from_chars(num, p, x);
          if (ec != std::errc() || ptr != p || !std::isfinite(x) || std::fabs(x) > 3.4e38)
            fail(std::string(key == "v"    ? "vertex coordinate"
                             : key == "vn" ? "normal component"
                                           : "texture coordinate") +
                 " '" + std::string(t.substr(0, 40)) + "' is not a finite number");
        } else {
          // i, i/j, i//k, i/j/k; each present index an integer that fits in an int.
          std::size_t b = 0;
          while (b <= t.size()) {
            std::size_t e = t.find('/', b);
            if (e == std::string_view::npos) e = t.size();
            if (e > b) {
              long long x = 0;
              const auto [ptr, ec] = std::from_chars(t.data() + b, t.data() + e, x);
              if (ec != std::errc() || ptr != t.data() + e || x > 2147483647LL || x < -2147483647LL)
                fail("index '" + std::string(t.substr(b, std::min<std::size_t>(e - b, 40))) +
                     "' is not an integer in the 32-bit range");
            }
            b = e + 1;
          }
        }
      }
      if (key == "v" && count < 3) fail("vertex has fewer than 3 coordinates");
      if (key == "vn" && count < 3) fail("normal has fewer than 3 components");
    }
    s = eol + 1;
    ++line;
  }
}

/// tinyobjloader reads "Kd nan" as black, "Ns nan" as exponent 0 and "Kd 0.5" as (0.5, 0, 0),
/// without a word; scan the material library ourselves first, so such a file is refused with
/// its line. Colour lines (Ka Kd Ks Ke Kt Tf) hold three finite numbers, scalar lines (Ns Ni d
/// Tr illum Pr Pm Ps Pc Pcr aniso anisor) one, after any "-option" words ("d -halo 0.5").
void checkMtlText(const std::string& label, std::string_view text) {
  static const std::set<std::string_view> colours = {"Ka", "Kd", "Ks", "Ke", "Kt", "Tf"};
  static const std::set<std::string_view> scalars = {"Ns", "Ni", "d",  "Tr",  "illum", "Pr",
                                                     "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};
  const auto isBlank = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  };
  std::size_t line = 1;
  for (std::size_t pos = 0; pos < text.size(); ++line) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view l = text.substr(pos, eol - pos);
    pos = eol + 1;
    if (const std::size_t hash = l.find('#'); hash != std::string_view::npos) l = l.substr(0, hash);
    std::vector<std::string_view> tok;
    for (std::size_t i = 0; i < l.size();) {
      while (i < l.size() && isBlank(l[i])) ++i;
      const std::size_t b = i;
      while (i < l.size() && !isBlank(l[i])) ++i;
      if (i > b) tok.push_back(l.substr(b, i - b));
    }
    if (tok.empty()) continue;
    const bool colour = colours.count(tok[0]) != 0;
    if (!colour && !scalars.count(tok[0])) continue;
    std::size_t first = 1;
    while (first < tok.size() && tok[first].size() > 1 && tok[first][0] == '-' &&
           std::isalpha(static_cast<unsigned char>(tok[first][1])))
      ++first;
    const std::size_t want = colour ? 3 : 1, got = tok.size() - first;
    const std::string key(tok[0]);
    const std::string where = "line " + std::to_string(line) + ": " + key;
    for (std::size_t k = first; k < tok.size(); ++k) {
      double x = 0;
      const char* b = tok[k].data() + (tok[k][0] == '+' ? 1 : 0);
      const char* e = tok[k].data() + tok[k].size();
      const auto [ptr, ec] = std::from_chars(b, e, x);
      if (ec != std::errc() || ptr != e || !std::isfinite(x) || std::fabs(x) > 3.4e38)
        throw Error(label,
                    where + " '" + std::string(tok[k].substr(0, 40)) + "' is not a finite number");
    }
    if (got != want)
      throw Error(label, where + " needs " + (colour ? "three numbers r g b" : "one number") +
                             ", found " + std::to_string(got));
  }
}

/// Resolves mtllib names: files beside the OBJ (regular files only, read through readFileBytes
/// and so under the file-size cap), or one text in memory that every name resolves to.
class MtlReader : public tinyobj::MaterialReader {
 public:
  MtlReader(std::filesystem::path dir, const std::string* memory, std::string objLabel)
      : dir_(std::move(dir)), memory_(memory), objLabel_(std::move(objLabel)) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* matMap, std::string* warn,
                  std::string* err) override {
    std::string text, label = objLabel_ + " (material library " + name.substr(0, 80) + ")";
    if (memory_) {
      text = *memory_;
    } else {
      const std::filesystem::path file = dir_ / name;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(file, ec)) {
        if (warn) *warn += "material file " + name + " not found\n";
        return false;
      }
      label = file.string();
      try {
        const std::vector<unsigned char> bytes = readFileBytes(file.string());
        text.assign(bytes.begin(), bytes.end());
      } catch (const Error& e) {
        if (!error_) error_ = e.what();
        return false;
      }
    }
    try {
      checkMtlText(label, text);
    } catch (const Error& e) {
      if (!error_) error_ = e.what();
      return false;
    }
    std::istringstream in(text);
    tinyobj::LoadMtl(matMap, materials, &in, warn, err);
    return true;
  }
  /// A cap or read error met while loading an MTL (rethrown after parsing).
  const std::optional<std::string>& error() const { return error_; }

 private:
  std::filesystem::path dir_;
  const std::string* memory_;
  std::string objLabel_;
  std::optional<std::string> error_;
};

std::string colourText(const tinyobj::real_t* c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", double(c[0]), double(c[1]), double(c[2]));
  return buf;
}

struct TripleHash {
  std::size_t operator()(const std::array<int, 3>& t) const {
    std::size_t h = static_cast<std::size_t>(t[0]) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::size_t>(t[1]) + 0x7F4A7C15ull + (h << 6) + (h >> 2);
    h ^= static_cast<std::size_t>(t[2]) + 0x85EBCA6Bull + (h << 6) + (h >> 2);
    return h;
  }
};

}  // namespace

Mesh readObj(const std::string& path, LoadReport& report) {
  const std::vector<unsigned char> bytes = readFileBytes(path);
  return readObjText(path,
                     std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                     std::filesystem::path(path).parent_path().string(), nullptr, report);
}

namespace {

/// Every material's Kd, Ks and Ns checked; the glossy part of the mesh: the first material with
/// a specular colour (Ks > 0), Phong exponent Ns.
std::optional<SurfaceGloss> checkMaterials(const std::string& path,
                                           const std::vector<tinyobj::material_t>& materials) {
  for (const tinyobj::material_t& m : materials)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(m.diffuse[k]) || m.diffuse[k] > kMaxAlbedo || m.diffuse[k] < 0)
        throw Error(path, "material '" + m.name.substr(0, 80) + "': Kd " + colourText(m.diffuse) +
                              " is not a colour (each component finite, in [0, 100])");
  std::optional<SurfaceGloss> gloss;
  for (const tinyobj::material_t& m : materials) {
    const bool finite = std::isfinite(m.specular[0]) && std::isfinite(m.specular[1]) &&
                        std::isfinite(m.specular[2]) && std::isfinite(m.shininess);
    if (!finite || m.specular[0] < 0 || m.specular[1] < 0 || m.specular[2] < 0 || m.shininess < 0)
      throw Error(path, "material '" + m.name.substr(0, 80) + "': Ks " + colourText(m.specular) +
                            " / Ns " + std::to_string(m.shininess) +
                            " is not a specular colour and exponent (finite, >= 0)");
    if (!gloss && (m.specular[0] > 0 || m.specular[1] > 0 || m.specular[2] > 0)) {
      SurfaceGloss g;
      g.model = SurfaceGloss::Model::Phong;
      g.specular = Rgb(m.specular[0], m.specular[1], m.specular[2]);
      g.exponent = m.shininess;
      g.material = m.name.substr(0, 80);
      gloss = g;
    }
  }
  return gloss;
}

/// The diffuse textures (map_Kd), each file decoded once, relative to `baseDir`, stored as
/// base_colour.hpp wants them: row 0 at v = 0, which in OBJ is the image's bottom row.
struct ObjTextures {
  std::vector<BaseColourTexture> images;
  std::vector<int> ofMaterial;  ///< per material, its image, or −1 (none, or not readable)
};

ObjTextures loadTextures(const std::string& path, const std::string& baseDir,
                         const std::vector<tinyobj::material_t>& materials, LoadReport& report) {
  const std::filesystem::path dir = baseDir;
  ObjTextures out;
  out.ofMaterial.assign(materials.size(), -1);
  std::map<std::string, int> byFile;  // a file several materials share is read once
  for (std::size_t m = 0; m < materials.size(); ++m) {
    std::string name = materials[m].diffuse_texname;
    if (name.empty()) continue;
    std::replace(name.begin(), name.end(), '\\', '/');
    const std::string file = (dir / name).string();
    if (const auto it = byFile.find(file); it != byFile.end()) {
      out.ofMaterial[m] = it->second;
      continue;
    }
    int& index = byFile[file] = -1;
    try {
      image::Srgb8Image img = image::readSrgb8Image(file);
      // Flip the rows: OBJ's v = 0 is the image's bottom row.
      const std::size_t row = std::size_t(img.width) * 3;
      for (int y = 0; y < img.height / 2; ++y)
        std::swap_ranges(img.rgb.begin() + std::ptrdiff_t(y * row),
                         img.rgb.begin() + std::ptrdiff_t((y + 1) * row),
                         img.rgb.begin() + std::ptrdiff_t((img.height - 1 - y) * row));
      index = int(out.images.size());
      out.images.push_back({std::move(img), name.substr(0, 120)});
    } catch (const Error& e) {
      report.warnings.push_back(path + ": material '" + materials[m].name.substr(0, 80) +
                                "': texture not used: " + e.what());
    }
    out.ofMaterial[m] = index;
  }
  return out;
}

}  // namespace

Mesh readObjText(const std::string& path, std::string_view text, const std::string& baseDir,
                 const std::string* mtlText, LoadReport& report) {
  checkObjText(path, text);
  checkLimit(path, "file size", text.size(), limits().maxFileBytes, "PRT_MAX_FILE_BYTES");
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapesStore;
  std::vector<tinyobj::material_t> materialsStore;
  std::string warnText, errText;
  MtlReader mtl(baseDir, mtlText, path);
  // Read straight from memory (no copy of a possibly large file into a stringstream).
  struct ViewBuf : std::streambuf {
    explicit ViewBuf(std::string_view v) {
      char* b = const_cast<char*>(v.data());
      setg(b, b, b + v.size());
    }
  } buf(text);
  std::istream in(&buf);
  // No triangulation (we fan-triangulate, keeping the corner order), no default vertex colours.
  const bool ok = tinyobj::LoadObj(&attrib, &shapesStore, &materialsStore, &warnText, &errText, &in,
                                   &mtl, false, false);
  if (mtl.error()) throw Error(*mtl.error());
  if (!ok) {
    std::string msg = errText;
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
    if (const auto nl = msg.find('\n'); nl != std::string::npos) msg.resize(nl);
    throw Error(path, msg.empty() ? "cannot parse OBJ" : msg);
  }
  if (!warnText.empty()) {
    std::string w = warnText;
    std::size_t pos = 0;
    while (pos < w.size()) {
      auto nl = w.find('\n', pos);
      if (nl == std::string::npos) nl = w.size();
      if (nl > pos) report.warnings.push_back(path + ": " + w.substr(pos, nl - pos));
      pos = nl + 1;
    }
  }
  const auto& shapes = shapesStore;
  const auto& materials = materialsStore;
  const std::optional<SurfaceGloss> gloss = checkMaterials(path, materials);
  const std::size_t np = attrib.vertices.size() / 3, nt = attrib.texcoords.size() / 2,
                    nn = attrib.normals.size() / 3;

  ObjTextures textures;
  if (mtlText)
    textures.ofMaterial.assign(materials.size(), -1);
  else
    textures = loadTextures(path, baseDir, materials, report);
  // The texture of a face (its material's, −1 for none or no UV at some corner): one for every
  // face is the scene's base-colour texture.
  int sharedTexture = -2;  // no face yet
  bool oneTexture = true, anyTexture = false;

  Mesh mesh;
  std::unordered_map<std::array<int, 3>, std::uint32_t, TripleHash> index;
  std::vector<int> vertexMaterial;  // material of the first face using each vertex
  bool anyNormal = false, anyUv = false;
  std::vector<std::array<int, 3>> triples;
  std::size_t face = 0;
  std::vector<std::uint32_t> corners;
  for (const auto& shape : shapes) {
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
      const std::size_t n = shape.mesh.num_face_vertices[f];
      const int material = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      corners.clear();
      for (std::size_t k = 0; k < n; ++k) {
        const tinyobj::index_t& id = shape.mesh.indices[offset + k];
        // Messages number faces and indices from 1, as the OBJ file does.
        if (id.vertex_index < 0 || std::size_t(id.vertex_index) >= np)
          throwBadIndex(path, face + 1, id.vertex_index + 1LL, np);
        if (id.texcoord_index >= 0 && std::size_t(id.texcoord_index) >= nt)
          throwBadIndex(path, face + 1, id.texcoord_index + 1LL, nt, "texture coordinate");
        if (id.normal_index >= 0 && std::size_t(id.normal_index) >= nn)
          throwBadIndex(path, face + 1, id.normal_index + 1LL, nn, "normal");
        const std::array<int, 3> key{id.vertex_index, id.texcoord_index, id.normal_index};
        auto [it, inserted] = index.try_emplace(key, static_cast<std::uint32_t>(triples.size()));
        if (inserted) {
          triples.push_back(key);
          vertexMaterial.push_back(material);
          anyNormal |= key[2] >= 0;
          anyUv |= key[1] >= 0;
        }
        corners.push_back(it->second);
      }
      offset += n;
      if (n < 3) continue;  // points and lines carry no surface
      int texture = material >= 0 && std::size_t(material) < materials.size()
                        ? textures.ofMaterial[std::size_t(material)]
                        : -1;
      anyTexture |= texture >= 0;
      for (std::size_t k = 0; k < n; ++k)
        if (shape.mesh.indices[offset - n + k].texcoord_index < 0) texture = -1;
      if (sharedTexture == -2) sharedTexture = texture;
      oneTexture &= texture == sharedTexture;
      if (n > 3) ++report.polygonsTriangulated;
      for (std::size_t k = 1; k + 1 < n; ++k)
        mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
    }
  }
  if (triples.empty() && np > 0)
    throw Error(path, "has no faces (" + std::to_string(np) +
                          " vertices but no triangles; a point cloud cannot be baked)");

  const bool keepTexture = oneTexture && sharedTexture >= 0;
  if (anyTexture && !keepTexture)
    report.warnings.push_back(
        path +
        ": the faces do not all use one map_Kd with texture coordinates, so each texture is "
        "sampled at the vertices only (prtkit applies one texture per scene per pixel)");
  const std::size_t nv = triples.size();
  mesh.positions.resize(nv);
  if (anyNormal) mesh.normals.assign(nv, Vec3f(0.0f));  // zero marks "no normal" for repair
  if (anyUv) mesh.uvs.assign(nv, Vec2f{});
  if (!materials.empty()) mesh.albedo.assign(nv, Rgb(kDefaultAlbedo));
  for (std::size_t v = 0; v < nv; ++v) {
    const auto& [pi, ti, ni] = triples[v];
    mesh.positions[v] = {attrib.vertices[3 * pi], attrib.vertices[3 * pi + 1],
                         attrib.vertices[3 * pi + 2]};
    if (ni >= 0)
      mesh.normals[v] = {attrib.normals[3 * ni], attrib.normals[3 * ni + 1],
                         attrib.normals[3 * ni + 2]};
    if (ti >= 0) mesh.uvs[v] = {attrib.texcoords[2 * ti], attrib.texcoords[2 * ti + 1]};
    const int m = vertexMaterial[v];
    if (m >= 0 && std::size_t(m) < materials.size()) {
      const auto& d = materials[m].diffuse;
      Rgb a{float(d[0]), float(d[1]), float(d[2])};
      const int t = textures.ofMaterial[std::size_t(m)];
      if (!keepTexture && t >= 0 && ti >= 0)
        a *= sampleBaseColour(textures.images[std::size_t(t)], mesh.uvs[v]);
      mesh.albedo[v] = a;
    }
  }
  mesh.gloss = gloss;
  if (keepTexture) mesh.baseColour = std::move(textures.images[std::size_t(sharedTexture)]);
  return mesh;
}

}  // namespace prt::detail
