#include "prt/geometry/mesh.hpp"

#include "prt/core/hash.hpp"

namespace prt {

Bounds computeBounds(const Mesh& mesh) {
  Bounds b;
  if (mesh.positions.empty()) return b;
  b.lo = b.hi = mesh.positions[0];
  for (const Vec3f& p : mesh.positions) {
    b.lo = min(b.lo, p);
    b.hi = max(b.hi, p);
  }
  return b;
}

std::vector<Rgb> albedoAtVertices(const Mesh& mesh) {
  if (!mesh.baseColour) return mesh.albedo;
  std::vector<Rgb> out(mesh.vertexCount(), Rgb(1.0f));
  for (std::size_t v = 0; v < out.size(); ++v) {
    if (v < mesh.albedo.size()) out[v] = mesh.albedo[v];
    if (v < mesh.uvs.size()) out[v] *= sampleBaseColour(*mesh.baseColour, mesh.uvs[v]);
  }
  return out;
}

void foldBaseColour(Mesh& mesh) {
  if (!mesh.baseColour) return;
  mesh.albedo = albedoAtVertices(mesh);
  mesh.baseColour.reset();
}

std::string meshFingerprint(const Mesh& mesh) {
  Fnv1a h;
  h.addAll(mesh.positions);
  h.addAll(mesh.normals);
  h.addAll(mesh.triangles);
  h.addAll(mesh.albedo);
  if (mesh.baseColour) {  // only when there is one: untextured meshes keep their fingerprints
    const image::Srgb8Image& t = mesh.baseColour->image;
    const int size[2] = {t.width, t.height};
    h.add(size, sizeof size);
    h.addAll(t.rgb);
    h.addAll(mesh.uvs);
  }
  return h.hex();
}

}  // namespace prt
