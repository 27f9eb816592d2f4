#include "prt/render/texel_points.hpp"

#include <algorithm>

#include "prt/core/error.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/render/render.hpp"
#include "prt/transfer/row_dilation.hpp"
#include "prt/transport/texel_validity.hpp"

namespace prt::render {

namespace {

/// The diffuse colour at the vertices that the samples' albedo blends (the texture folded in, as
/// the bake's bounces and the reference see it; without `withTexture` the mesh's albedo alone),
/// or empty when the mesh has none: white.
std::vector<Rgb> vertexAlbedoOf(const Mesh& mesh, bool withTexture) {
  const bool coloured = mesh.hasAlbedo() || (withTexture && mesh.baseColour.has_value());
  return !coloured ? std::vector<Rgb>() : withTexture ? albedoAtVertices(mesh) : mesh.albedo;
}

/// That colour interpolated at a sample point.
Rgb sampleAlbedo(const Mesh& mesh, const std::vector<Rgb>& vertexAlbedo, const TexelSample& t) {
  const auto& tri = mesh.triangles[t.triangle];
  const Vec3f& w = t.barycentric;
  return vertexAlbedo[tri[0]] * w.x + vertexAlbedo[tri[1]] * w.y + vertexAlbedo[tri[2]] * w.z;
}

void requireLightmapUvs(const Mesh& mesh) {
  if (mesh.lightmapUvs.size() != mesh.vertexCount())
    throw Error(mesh.source, "per-texel transfer needs the mesh's lightmap UVs");
}

}  // namespace

RowPoints texelRowPoints(const Mesh& mesh, const Occluder& occluder,
                         const TransferShape::LightmapSize& lightmap, bool withTexture,
                         TexelDilation how) {
  requireLightmapUvs(mesh);
  const TexelSamples s = sampleTexels(mesh, mesh.lightmapUvs, lightmap.width, lightmap.height);
  RowPoints out;
  const std::size_t rows = s.texelCount();
  out.positions.assign(rows, Vec3f(0.0f));
  out.normals.assign(rows, Vec3f(0, 0, 1));
  const std::vector<Rgb> vertexAlbedo = vertexAlbedoOf(mesh, withTexture);
  const bool coloured = !vertexAlbedo.empty();
  if (coloured) out.albedo.assign(rows, Rgb(1.0f));
  std::vector<Vec3f> p, n;
  for (const TexelSample& t : s.samples) {
    p.push_back(samplePosition(mesh, t));
    n.push_back(sampleNormal(mesh, t));
    out.positions[t.texel] = p.back();
    out.normals[t.texel] = n.back();
    if (coloured) out.albedo[t.texel] = sampleAlbedo(mesh, vertexAlbedo, t);
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
  dilateTexels(v, kStride, filled, lightmap.width, lightmap.height, std::max(lightmap.padding, 1),
               how);
  for (std::size_t t = 0; t < rows; ++t) {
    if (valid[t] || !filled[t]) continue;
    const float* r = v.data() + t * kStride;
    out.positions[t] = {r[0], r[1], r[2]};
    const Vec3f m{r[3], r[4], r[5]};
    const float len = length(m);
    // A copied normal is a neighbour's own, bit for bit; a mean is normalised again.
    out.normals[t] = how == TexelDilation::CopyFirst ? m : len > 0 ? m / len : Vec3f(0, 0, 1);
    if (coloured) out.albedo[t] = {r[6], r[7], r[8]};
  }
  return out;
}

RowPoints texelSamplePoints(const Mesh& mesh, const Occluder& occluder,
                            const TransferShape::LightmapSize& lightmap,
                            std::span<const std::uint32_t> texels) {
  requireLightmapUvs(mesh);
  const std::vector<TexelSample> samples =
      sampleTexelsAt(mesh, mesh.lightmapUvs, lightmap.width, lightmap.height, texels);
  RowPoints out;
  out.rows.assign(texels.begin(), texels.end());
  out.positions.assign(texels.size(), Vec3f(0.0f));
  out.normals.assign(texels.size(), Vec3f(0, 0, 1));
  const std::vector<Rgb> vertexAlbedo = vertexAlbedoOf(mesh, true);
  if (!vertexAlbedo.empty()) out.albedo.assign(texels.size(), Rgb(1.0f));
  // The samples are the covered texels among `texels`, in the same order: walk both.
  std::vector<Vec3f> p, n;
  std::vector<std::size_t> entryOf;
  std::size_t e = 0;
  for (const TexelSample& t : samples) {
    while (texels[e] != t.texel) ++e;
    entryOf.push_back(e);
    p.push_back(out.positions[e] = samplePosition(mesh, t));
    n.push_back(out.normals[e] = sampleNormal(mesh, t));
    if (!vertexAlbedo.empty()) out.albedo[e] = sampleAlbedo(mesh, vertexAlbedo, t);
  }
  const std::vector<std::uint8_t> inside = insideGeometry(mesh, occluder, p, n);
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (!inside[i]) out.valid.push_back(samples[i].texel);
  return out;
}

RowPoints texelRowPointsAt(const Mesh& mesh, const Occluder& occluder,
                           const TransferShape::LightmapSize& lightmap,
                           std::span<const std::uint32_t> texels, TexelDilation how) {
  RowPoints own = texelSamplePoints(mesh, occluder, lightmap, texels);
  if (own.valid.size() == texels.size()) return own;  // every point its own sample's
  // Some are the gutter or inside geometry: their points are dilated from their valid
  // neighbours', which takes the whole lightmap's.
  const RowPoints all = texelRowPoints(mesh, occluder, lightmap, true, how);
  RowPoints out;
  out.rows = std::move(own.rows);
  out.valid = std::move(own.valid);
  for (std::uint32_t t : out.rows) {
    out.positions.push_back(all.positions[t]);
    out.normals.push_back(all.normals[t]);
    if (!all.albedo.empty()) out.albedo.push_back(all.albedo[t]);
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
    if (transfer.isHaar())
      r.points = texelRowPoints(mesh, occluder, transfer.shape().lightmap, false,
                                rowDilation(transfer.shape().basis));
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

std::vector<float> shadingPoints(const Mesh& mesh, const Transfer& transfer,
                                 const Material& material, const Occluder* occluder) {
  if (transfer.domain() != TransferDomain::Texels || (!transfer.isMatrix() && !transfer.isHaar()))
    return {};
  std::unique_ptr<Occluder> own;
  if (!occluder) occluder = (own = makeEmbreeOccluder(mesh)).get();
  return packTexelPoints(texelRelight(mesh, *occluder, transfer, material).points);
}

}  // namespace prt::render
