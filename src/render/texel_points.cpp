#include "prt/render/texel_points.hpp"

#include "prt/core/error.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/transport/texel_validity.hpp"

namespace prt::render {

RowPoints texelRowPoints(const Mesh& mesh, const Occluder& occluder,
                         const TransferShape::LightmapSize& lightmap) {
  if (mesh.lightmapUvs.size() != mesh.vertexCount())
    throw Error(mesh.source, "per-texel transfer needs the mesh's lightmap UVs");
  const TexelSamples s = sampleTexels(mesh, mesh.lightmapUvs, lightmap.width, lightmap.height);
  RowPoints out;
  const std::size_t rows = s.texelCount();
  out.positions.assign(rows, Vec3f(0.0f));
  out.normals.assign(rows, Vec3f(0, 0, 1));
  if (mesh.hasAlbedo()) out.albedo.assign(rows, Rgb(1.0f));
  std::vector<Vec3f> p, n;
  for (const TexelSample& t : s.samples) {
    p.push_back(samplePosition(mesh, t));
    n.push_back(sampleNormal(mesh, t));
    out.positions[t.texel] = p.back();
    out.normals[t.texel] = n.back();
    if (mesh.hasAlbedo()) {
      const auto& tri = mesh.triangles[t.triangle];
      const Vec3f& w = t.barycentric;
      out.albedo[t.texel] =
          mesh.albedo[tri[0]] * w.x + mesh.albedo[tri[1]] * w.y + mesh.albedo[tri[2]] * w.z;
    }
  }
  const std::vector<std::uint8_t> inside = insideGeometry(mesh, occluder, p, n);
  for (std::size_t i = 0; i < s.samples.size(); ++i)
    if (!inside[i]) out.valid.push_back(s.samples[i].texel);
  return out;
}

}  // namespace prt::render
