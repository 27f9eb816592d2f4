#include "prt/geometry/load.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "loaders.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/normals.hpp"

namespace prt {

void LoadReport::merge(const LoadReport& o) {
  degenerateTriangles += o.degenerateTriangles;
  computedNormals += o.computedNormals;
  unusedVertices += o.unusedVertices;
  polygonsTriangulated += o.polygonsTriangulated;
  warnings.insert(warnings.end(), o.warnings.begin(), o.warnings.end());
}

std::vector<std::string> meshExtensions() {
  return {"obj", "ply", "off", "gltf", "glb"};
}

namespace {

std::string triple(float a, float b, float c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", double(a), double(b), double(c));
  return buf;
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

void checkMeshExtent(const Mesh& m, const std::string& label) {
  const double maxCoord = limits().maxCoordinate;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3f& p = m.positions[v];
    if (!isFinite(p))
      throw Error(label, "vertex " + std::to_string(v) + " has a non-finite coordinate " +
                             triple(p.x, p.y, p.z));
    for (int k = 0; k < 3; ++k)
      if (std::fabs(double(p[k])) > maxCoord)
        throw Error(label, "vertex " + std::to_string(v) + " at " + triple(p.x, p.y, p.z) +
                               " lies outside the extent the ray tracer handles (|coordinate| <= " +
                               number(maxCoord) + ", PRT_MAX_COORDINATE); rescale the scene");
  }
}

void checkMeshValues(const Mesh& m, const std::string& label) {
  checkMeshExtent(m, label);
  for (std::size_t v = 0; v < m.normals.size(); ++v)
    if (!isFinite(m.normals[v]))
      throw Error(label, "vertex " + std::to_string(v) + " has a non-finite normal " +
                             triple(m.normals[v].x, m.normals[v].y, m.normals[v].z));
  for (std::size_t v = 0; v < m.uvs.size(); ++v)
    if (!std::isfinite(m.uvs[v].x) || !std::isfinite(m.uvs[v].y))
      throw Error(label, "vertex " + std::to_string(v) + " has a non-finite texture coordinate");
  for (std::size_t v = 0; v < m.lightmapUvs.size(); ++v)
    if (!std::isfinite(m.lightmapUvs[v].x) || !std::isfinite(m.lightmapUvs[v].y))
      throw Error(label, "vertex " + std::to_string(v) + " has a non-finite lightmap coordinate");
  for (std::size_t v = 0; v < m.albedo.size(); ++v) {
    const Rgb& a = m.albedo[v];
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(a[k]) || a[k] > kMaxAlbedo)
        throw Error(label, "vertex " + std::to_string(v) + " has albedo " + triple(a.x, a.y, a.z) +
                               " (each component must be finite and at most " +
                               std::to_string(int(kMaxAlbedo)) + ")");
  }
}

namespace detail {

void throwBadIndex(const std::string& label, std::size_t face, long long index, std::size_t count,
                   const char* what) {
  throw Error(label, "face " + std::to_string(face) + " references " + what + " " +
                         std::to_string(index) + " (mesh has " + std::to_string(count) + ")");
}

namespace {

enum class Head { Yes, No, More };

/// Whether `s`, the first bytes of a decompressed stream, begins like a `format` file.
Head headerVerdict(std::string_view format, std::string_view s) {
  if (format == "ply")
    return s.size() < 3 ? Head::More : s.substr(0, 3) == "ply" ? Head::Yes : Head::No;
  // OFF: blank space and '#' comment lines, then the header keyword (readOff's tokens).
  std::size_t i = 0;
  while (true) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i < s.size() && s[i] == '#') {
      while (i < s.size() && s[i] != '\n') ++i;
      continue;
    }
    break;
  }
  const std::size_t b = i;
  while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i])) && s[i] != '#') ++i;
  if (i == s.size()) return i - b > 16 ? Head::No : Head::More;  // the keyword may go on
  return isOffKeyword(s.substr(b, i - b)) ? Head::Yes : Head::No;
}

}  // namespace

std::vector<unsigned char> gunzip(const std::string& label, std::span<const unsigned char> bytes,
                                  std::string_view format) {
  // Streamed in chunks with the output capped at limits().maxDecompressedBytes, so a gzip bomb
  // (a few MB inflating to many GB) stops at the cap instead of exhausting memory.
  const std::uint64_t cap = limits().maxDecompressedBytes;
  z_stream zs{};
  // 15 window bits + 32: accept both gzip and zlib headers.
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw Error(label, "cannot initialise zlib");
  struct End {
    z_stream* z;
    ~End() { inflateEnd(z); }
  } end{&zs};
  std::vector<unsigned char> out;
  std::vector<unsigned char> chunk(1 << 16);
  std::size_t inPos = 0;
  constexpr std::size_t kDecideWithin = 1 << 16;  // the header must show within 64 KiB
  bool decided = format.empty();
  while (true) {
    if (zs.avail_in == 0 && inPos < bytes.size()) {
      const std::size_t n = std::min<std::size_t>(bytes.size() - inPos, 1u << 30);
      zs.next_in = const_cast<unsigned char*>(bytes.data() + inPos);
      zs.avail_in = static_cast<uInt>(n);
      inPos += n;
    }
    zs.next_out = chunk.data();
    zs.avail_out = static_cast<uInt>(chunk.size());
    const int rc = inflate(&zs, Z_NO_FLUSH);
    const std::size_t produced = chunk.size() - zs.avail_out;
    if (out.size() + produced > cap)
      throw Error(label, "gzip: decompresses to more than " + std::to_string(cap) +
                             " bytes (PRT_MAX_DECOMPRESSED_BYTES)");
    out.insert(out.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(produced));
    // Stop at once, not after gigabytes, when what comes out is not the expected format.
    if (!decided && produced > 0) {
      const Head h = headerVerdict(
          format, std::string_view(reinterpret_cast<const char*>(out.data()), out.size()));
      if (h == Head::No)
        throw Error(label,
                    format == "ply"
                        ? std::string("gzip: the decompressed data does not start with 'ply'")
                        : "gzip: the decompressed data does not start with an OFF header "
                          "(OFF, COFF, NOFF, CNOFF)");
      if (h == Head::More && out.size() >= kDecideWithin)
        throw Error(label, "gzip: no " + std::string(format) +
                               " header in the first 64 KiB of the decompressed data");
      decided = h == Head::Yes;
    }
    if (rc == Z_STREAM_END) break;
    if (rc == Z_NEED_DICT || (rc != Z_OK && rc != Z_BUF_ERROR))
      throw Error(label, "gzip: " + std::string(zs.msg ? zs.msg : "corrupt data"));
    if (zs.avail_in == 0 && inPos >= bytes.size() && produced == 0)
      throw Error(label, "gzip: truncated data");
  }
  return out;
}

}  // namespace detail

namespace {

std::string stem(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  for (const char* ext : {".gz", ".obj", ".ply", ".off", ".gltf", ".glb"}) {
    const std::string e = ext;
    if (name.size() > e.size()) {
      std::string tail = name.substr(name.size() - e.size());
      std::transform(tail.begin(), tail.end(), tail.begin(), ::tolower);
      if (tail == e) name.resize(name.size() - e.size());
    }
  }
  return name;
}

}  // namespace

namespace detail {

/// Validates a freshly read mesh and brings it to the invariants stated in load.hpp.
void finishMesh(Mesh& m, const std::string& label, LoadReport& report) {
  if (m.positions.empty()) throw Error(label, "has no vertices");
  if (m.triangles.empty())
    throw Error(label, "has no faces (" + std::to_string(m.positions.size()) +
                           " vertices but no triangles; a point cloud cannot be baked)");
  checkLimit(label, "vertex count", m.positions.size(), limits().maxVertices, "PRT_MAX_VERTICES");
  checkLimit(label, "triangle count", m.triangles.size(), limits().maxTriangles,
             "PRT_MAX_TRIANGLES");
  checkMeshValues(m, label);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (std::uint32_t i : m.triangles[t])
      if (i >= m.positions.size()) detail::throwBadIndex(label, t, i, m.positions.size());
  if (!m.albedo.empty() && m.albedo.size() != m.positions.size())
    throw Error(label, "internal: albedo count differs from vertex count");
  for (Rgb& a : m.albedo)
    for (int k = 0; k < 3; ++k)
      if (a[k] < 0) a[k] = 0;
  if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) m.uvs.clear();
  if (m.baseColour && m.uvs.size() != m.positions.size())
    throw Error(label, "internal: a base colour texture without a UV per vertex");
  if (!m.lightmapUvs.empty() && m.lightmapUvs.size() != m.positions.size()) m.lightmapUvs.clear();
  if (m.parts.empty()) m.parts.push_back(MeshPart{stem(label), 0, 0, 0, 0});
  if (m.parts.size() == 1) {
    m.parts[0].vertexCount = static_cast<std::uint32_t>(m.positions.size());
    m.parts[0].triangleCount = static_cast<std::uint32_t>(m.triangles.size());
  }

  const std::size_t total = m.triangles.size();
  const std::size_t degenerate = removeDegenerateTriangles(m);
  if (m.triangles.empty())
    throw Error(label, "all " + std::to_string(total) + " triangles have zero area");
  report.degenerateTriangles += degenerate;
  if (degenerate)
    report.warnings.push_back(label + ": skipped " + std::to_string(degenerate) +
                              " zero-area triangle" + (degenerate == 1 ? "" : "s"));

  std::vector<std::uint8_t> used(m.positions.size(), 0);
  for (const auto& t : m.triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  const std::size_t unused = std::count(used.begin(), used.end(), 0);
  report.unusedVertices += unused;
  if (unused)
    report.warnings.push_back(label + ": " + std::to_string(unused) +
                              " vertices are on no triangle (kept, normal +Y)");

  const bool fileNormals = m.normals.size() == m.positions.size();
  const std::size_t computed = repairNormals(m);
  report.computedNormals += computed;
  if (fileNormals && computed)
    report.warnings.push_back(label + ": " + std::to_string(computed) +
                              " missing or invalid normals replaced by computed ones");
}

}  // namespace detail

namespace {

std::string extensionList() {
  std::string list;
  for (const auto& e : meshExtensions()) list += (list.empty() ? "." : ", .") + e;
  return list;
}

/// Splits "x.ply.gz" into ("ply", gz = true).
std::string meshFormat(const std::string& path, bool& gz) {
  std::string ext = fileExtension(path);
  gz = ext == "gz";
  if (gz) ext = fileExtension(path.substr(0, path.size() - 3));
  if (gz && (ext == "obj" || ext == "gltf" || ext == "glb"))
    throw Error(path, "compressed ." + ext + " is not supported (only .ply.gz and .off.gz)");
  if (ext != "ply" && ext != "off" && ext != "obj" && ext != "gltf" && ext != "glb")
    throw Error(path,
                (ext.empty() ? std::string("has no extension") : "unknown extension ." + ext) +
                    " (mesh formats: " + extensionList() + ", .ply.gz, .off.gz, builtin:NAME)");
  return ext;
}

Mesh readBytes(const std::string& label, const std::string& ext, bool gz,
               std::span<const unsigned char> raw, LoadReport& report) {
  std::vector<unsigned char> inflated;
  if (gz) inflated = detail::gunzip(label, raw, ext);
  const std::span<const unsigned char> bytes = gz ? std::span<const unsigned char>(inflated) : raw;
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (ext == "ply") return detail::readPly(label, bytes, report);
  if (ext == "off") return detail::readOff(label, text, report);
  if (ext == "obj") {
    static const std::string noMaterials;  // every mtllib reads as empty: nothing from disk
    return detail::readObjText(label, text, "", &noMaterials, report);
  }
  return detail::readGltfBytes(label, bytes, ext == "glb", "", false, report);
}

Mesh loadFile(const std::string& path, LoadReport& report) {
  bool gz = false;
  const std::string ext = meshFormat(path, gz);
  // OBJ and glTF may refer to other files (materials, textures, buffers) beside them.
  if (ext == "obj") return detail::readObj(path, report);
  if (ext == "gltf" || ext == "glb") return detail::readGltf(path, report);
  const std::vector<unsigned char> bytes = readFileBytes(path);
  return readBytes(path, ext, gz, bytes, report);
}

}  // namespace

Mesh loadMesh(const std::string& path, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  if (isBuiltinScene(path)) return builtinScene(path);
  Mesh m = loadFile(path, r);
  detail::finishMesh(m, path, r);
  m.source = path;
  return m;
}

Mesh loadMeshBytes(const std::string& name, std::span<const unsigned char> bytes,
                   LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  bool gz = false;
  const std::string ext = meshFormat(name, gz);
  Mesh m = readBytes(name, ext, gz, bytes, r);
  detail::finishMesh(m, name, r);
  m.source = name;
  return m;
}

void appendMesh(Mesh& scene, const Mesh& part) {
  // A base-colour texture survives for a scene of one file only (one texture per scene): the
  // second file folds the first's into its albedo, and its own is folded too.
  if (!scene.positions.empty() && (scene.baseColour || part.baseColour)) {
    foldBaseColour(scene);
    if (part.baseColour) {
      Mesh folded = part;
      foldBaseColour(folded);
      appendMesh(scene, folded);
      return;
    }
  }
  if (scene.positions.empty()) scene.baseColour = part.baseColour;
  if (!scene.gloss) scene.gloss = part.gloss;  // the first file's glossy surface
  const std::uint32_t v0 = static_cast<std::uint32_t>(scene.positions.size());
  const std::uint32_t t0 = static_cast<std::uint32_t>(scene.triangles.size());
  if (scene.albedo.empty() != part.albedo.empty()) {
    if (scene.albedo.empty()) scene.albedo.assign(scene.positions.size(), Rgb(kDefaultAlbedo));
  }
  const bool wantAlbedo = !scene.albedo.empty() || !part.albedo.empty();
  const bool wantUvs = !scene.uvs.empty() || !part.uvs.empty();
  if (wantUvs && scene.uvs.empty()) scene.uvs.assign(scene.positions.size(), Vec2f{});
  // Lightmap UVs survive for a scene of one file only: each file packs its own [0, 1]², so a
  // second file's charts would overlap the first's (prt unwrap makes one atlas for them all).
  const bool keepLightmap = scene.positions.empty() && !part.lightmapUvs.empty();
  scene.positions.insert(scene.positions.end(), part.positions.begin(), part.positions.end());
  scene.normals.insert(scene.normals.end(), part.normals.begin(), part.normals.end());
  if (wantAlbedo) {
    if (part.albedo.empty())
      scene.albedo.resize(scene.positions.size(), Rgb(kDefaultAlbedo));
    else
      scene.albedo.insert(scene.albedo.end(), part.albedo.begin(), part.albedo.end());
  }
  if (wantUvs) {
    if (part.uvs.empty())
      scene.uvs.resize(scene.positions.size(), Vec2f{});
    else
      scene.uvs.insert(scene.uvs.end(), part.uvs.begin(), part.uvs.end());
  }
  if (keepLightmap)
    scene.lightmapUvs = part.lightmapUvs;
  else
    scene.lightmapUvs.clear();
  for (const auto& t : part.triangles) scene.triangles.push_back({t[0] + v0, t[1] + v0, t[2] + v0});
  for (MeshPart p : part.parts) {
    p.firstVertex += v0;
    p.firstTriangle += t0;
    scene.parts.push_back(p);
  }
}

Mesh loadScene(const std::vector<std::string>& inputs, LoadReport* report) {
  if (inputs.empty()) throw Error("no input meshes given");
  if (inputs.size() == 1) return loadMesh(inputs[0], report);
  Mesh scene;
  for (const std::string& in : inputs) {
    const Mesh m = loadMesh(in, report);
    if (scene.positions.size() + m.positions.size() > 0xffffffffull)
      throw Error(in, "the merged scene has too many vertices for 32-bit indices");
    appendMesh(scene, m);
    scene.source += (scene.source.empty() ? "" : "+") + in;
  }
  return scene;
}

}  // namespace prt
