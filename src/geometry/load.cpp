#include "prt/geometry/load.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "loaders.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
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

namespace detail {

void throwBadIndex(const std::string& label, std::size_t face, long long index, std::size_t count,
                   const char* what) {
  throw Error(label, "face " + std::to_string(face) + " references " + what + " " +
                         std::to_string(index) + " (mesh has " + std::to_string(count) + ")");
}

std::vector<unsigned char> gunzip(const std::string& label, std::span<const unsigned char> bytes) {
  z_stream zs{};
  // 15 window bits + 32: accept both gzip and zlib headers.
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw Error(label, "cannot initialise zlib");
  std::vector<unsigned char> out;
  out.resize(std::max<std::size_t>(bytes.size() * 4, 1 << 16));
  zs.next_in = const_cast<unsigned char*>(bytes.data());
  zs.avail_in = static_cast<uInt>(bytes.size());
  int rc = Z_OK;
  while (true) {
    if (zs.total_out == out.size()) out.resize(out.size() * 2);
    zs.next_out = out.data() + zs.total_out;
    zs.avail_out = static_cast<uInt>(std::min<std::size_t>(out.size() - zs.total_out, 1u << 30));
    rc = inflate(&zs, Z_NO_FLUSH);
    if (rc == Z_STREAM_END) break;
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      const std::string msg = zs.msg ? zs.msg : "corrupt data";
      inflateEnd(&zs);
      throw Error(label, "gzip: " + msg);
    }
    if (rc == Z_BUF_ERROR && zs.avail_in == 0) {
      inflateEnd(&zs);
      throw Error(label, "gzip: truncated data");
    }
  }
  out.resize(zs.total_out);
  inflateEnd(&zs);
  return out;
}

Rgb sampleTexture(const image::Image& img, Vec2f uv, bool vUp) {
  if (img.empty() || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return Rgb(1.0f);
  const double u = uv.x - std::floor(uv.x);
  double v = uv.y - std::floor(uv.y);
  if (vUp) v = 1.0 - v;
  // Continuous pixel coordinates: u = 0 is the left edge of the image, u = 1 its right edge.
  return image::sampleBilinear(img, u * img.width, v * img.height, true);
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

/// Validates a freshly read mesh and brings it to the invariants stated in load.hpp.
void finishMesh(Mesh& m, const std::string& label, LoadReport& report) {
  if (m.positions.empty()) throw Error(label, "has no vertices");
  if (m.triangles.empty())
    throw Error(label, "has no faces (" + std::to_string(m.positions.size()) +
                           " vertices but no triangles; a point cloud cannot be baked)");
  for (std::size_t v = 0; v < m.positions.size(); ++v)
    if (!isFinite(m.positions[v]))
      throw Error(label, "vertex " + std::to_string(v) + " has a non-finite coordinate (" +
                             std::to_string(m.positions[v].x) + ", " +
                             std::to_string(m.positions[v].y) + ", " +
                             std::to_string(m.positions[v].z) + ")");
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (std::uint32_t i : m.triangles[t])
      if (i >= m.positions.size()) detail::throwBadIndex(label, t, i, m.positions.size());
  if (!m.albedo.empty() && m.albedo.size() != m.positions.size())
    throw Error(label, "internal: albedo count differs from vertex count");
  for (Rgb& a : m.albedo)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(a[k]) || a[k] < 0) a[k] = 0;
  if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) m.uvs.clear();
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

Mesh loadFile(const std::string& path, LoadReport& report) {
  std::string ext = fileExtension(path);
  bool gz = false;
  std::string inner = path;
  if (ext == "gz") {
    gz = true;
    inner = path.substr(0, path.size() - 3);
    ext = fileExtension(inner);
  }
  const auto bytesOf = [&]() {
    std::vector<unsigned char> bytes = readFileBytes(path);
    return gz ? detail::gunzip(path, bytes) : bytes;
  };
  if (ext == "ply") {
    const auto bytes = bytesOf();
    return detail::readPly(path, bytes, report);
  }
  if (ext == "off") {
    const auto bytes = bytesOf();
    return detail::readOff(
        path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), report);
  }
  if (gz && (ext == "obj" || ext == "gltf" || ext == "glb"))
    throw Error(path, "compressed ." + ext + " is not supported (only .ply.gz and .off.gz)");
  if (ext == "obj") return detail::readObj(path, report);
  if (ext == "gltf" || ext == "glb") return detail::readGltf(path, report);
  std::string list;
  for (const auto& e : meshExtensions()) list += (list.empty() ? "." : ", .") + e;
  throw Error(path, (ext.empty() ? std::string("has no extension") : "unknown extension ." + ext) +
                        " (mesh formats: " + list + ", .ply.gz, .off.gz, builtin:NAME)");
}

}  // namespace

Mesh loadMesh(const std::string& path, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  if (isBuiltinScene(path)) return builtinScene(path);
  Mesh m = loadFile(path, r);
  finishMesh(m, path, r);
  m.source = path;
  return m;
}

void appendMesh(Mesh& scene, const Mesh& part) {
  const std::uint32_t v0 = static_cast<std::uint32_t>(scene.positions.size());
  const std::uint32_t t0 = static_cast<std::uint32_t>(scene.triangles.size());
  if (scene.albedo.empty() != part.albedo.empty()) {
    if (scene.albedo.empty()) scene.albedo.assign(scene.positions.size(), Rgb(kDefaultAlbedo));
  }
  const bool wantAlbedo = !scene.albedo.empty() || !part.albedo.empty();
  const bool wantUvs = !scene.uvs.empty() || !part.uvs.empty();
  if (wantUvs && scene.uvs.empty()) scene.uvs.assign(scene.positions.size(), Vec2f{});
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
