#include "prt/render/texel_points.hpp"

#include <algorithm>

#include "prt/core/error.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/render/render.hpp"
#include "prt/transport/texel_validity.hpp"

namespace prt::render {

RowPoints texelRowPoints(const Mesh& mesh, const Occluder& occluder,
                         const TransferShape::LightmapSize& lightmap, bool withTexture) {
  if (mesh.lightmapUvs.size() != mesh.vertexCount())
    throw Error(mesh.source, "per-texel transfer needs the mesh's lightmap UVs");
  const TexelSamples s = sampleTexels(mesh, mesh.lightmapUvs, lightmap.width, lightmap.height);
  RowPoints out;
  const std::size_t rows = s.texelCount();
  out.positions.assign(rows, Vec3f(0.0f));
  out.normals.assign(rows, Vec3f(0, 0, 1));
  // The diffuse colour at the vertices (the texture folded in, as the bake's bounces and the
  // reference see it), interpolated at each sample point.
  const bool coloured = mesh.hasAlbedo() || (withTexture && mesh.baseColour.has_value());
  const std::vector<Rgb> vertexAlbedo = !coloured     ? std::vector<Rgb>()
                                        : withTexture ? albedoAtVertices(mesh)
                                                      : mesh.albedo;
  if (coloured) out.albedo.assign(rows, Rgb(1.0f));
  std::vector<Vec3f> p, n;
  for (const TexelSample& t : s.samples) {
    p.push_back(samplePosition(mesh, t));
    n.push_back(sampleNormal(mesh, t));
    out.positions[t.texel] = p.back();
    out.normals[t.texel] = n.back();
    if (coloured) {
      const auto& tri = mesh.triangles[t.triangle];
      const Vec3f& w = t.barycentric;
      out.albedo[t.texel] =
          vertexAlbedo[tri[0]] * w.x + vertexAlbedo[tri[1]] * w.y + vertexAlbedo[tri[2]] * w.z;
    }
  }
  const std::vector<std::uint8_t> inside = insideGeometry(mesh, occluder, p, n);
  for (std::size_t i = 0; i < s.samples.size(); ++i)
    if (!inside[i]) out.valid.push_back(s.samples[i].texel);

  // The rows that are not valid, dilated from the valid ones (9 floats: point, normal, albedo).
  constexpr int kStride = 9;
  std::vector<float> v(rows * kStride, 0.0f);
  std::vector<std::uint8_t> filled(rows, 0);
  for (std::uint32_t t : out.valid) {
    float* r = v.data() + std::size_t(t) * kStride;
    const Vec3f& q = out.positions[t];
    const Vec3f& m = out.normals[t];
    const Rgb a = coloured ? out.albedo[t] : Rgb(1.0f);
    const float row[kStride] = {q.x, q.y, q.z, m.x, m.y, m.z, a.x, a.y, a.z};
    std::copy(row, row + kStride, r);
    filled[t] = 1;
  }
  std::vector<std::uint8_t> valid = filled;
  dilateTexels(v, kStride, filled, lightmap.width, lightmap.height, std::max(lightmap.padding, 1));
  for (std::size_t t = 0; t < rows; ++t) {
    if (valid[t] || !filled[t]) continue;
    const float* r = v.data() + t * kStride;
    out.positions[t] = {r[0], r[1], r[2]};
    const Vec3f m{r[3], r[4], r[5]};
    const float len = length(m);
    out.normals[t] = len > 0 ? m / len : Vec3f(0, 0, 1);
    if (coloured) out.albedo[t] = {r[6], r[7], r[8]};
  }
  return out;
}

std::vector<float> packTexelPoints(const RowPoints& points) {
  const std::size_t rows = points.positions.size();
  std::vector<float> out(rows * 12, 0.0f);
  for (std::size_t r = 0; r < rows; ++r) {
    float* t = out.data() + r * 12;
    const Vec3f& p = points.positions[r];
    const Vec3f& n = points.normals[r];
    const Rgb a = points.albedo.empty() ? Rgb(1.0f) : points.albedo[r];
    t[0] = p.x, t[1] = p.y, t[2] = p.z;
    t[4] = n.x, t[5] = n.y, t[6] = n.z;
    t[8] = a.x, t[9] = a.y, t[10] = a.z;
  }
  return out;
}

TexelRelight texelRelight(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                          const Material& material) {
  TexelRelight r;
  if (!transfer.isMatrix()) {
    r.pixelAlbedo = texelAlbedo(mesh, material);
    return r;
  }
  r.points = texelRowPoints(mesh, occluder, transfer.shape().lightmap, false);
  return r;
}

}  // namespace prt::render

namespace prt::render {

void requireWholeDomain(const Mesh& mesh, const Transfer& transfer, const std::string& verb) {
  const bool perTexel = transfer.domain() == TransferDomain::Texels;
  if (perTexel && mesh.lightmapUvs.size() != mesh.vertexCount())
    throw Error("the transfer is per texel: the mesh needs its lightmap UVs");
  const std::size_t n = transfer.shape().domainRows(mesh.vertexCount());
  if (transfer.rows().first != 0 || transfer.rowCount() != n)
    throw Error(verb + " needs the transfer of every " + rowName(transfer.domain()) + " (" +
                std::to_string(n) + "), it holds " + std::to_string(transfer.rowCount()) +
                " rows from " + std::to_string(transfer.rows().first));
}

std::shared_ptr<const RowPoints> transferRowPoints(const Mesh& mesh, const Occluder& occluder,
                                                   const Transfer& transfer) {
  if (transfer.domain() != TransferDomain::Texels) return nullptr;
  return std::make_shared<const RowPoints>(
      texelRowPoints(mesh, occluder, transfer.shape().lightmap));
}

std::vector<float> shadingPoints(const Mesh& mesh, const Transfer& transfer,
                                 const Material& material, const Occluder* occluder) {
  if (transfer.domain() != TransferDomain::Texels || !transfer.isMatrix()) return {};
  std::unique_ptr<Occluder> own;
  if (!occluder) occluder = (own = makeEmbreeOccluder(mesh)).get();
  return packTexelPoints(texelRelight(mesh, *occluder, transfer, material).points);
}

}  // namespace prt::render
