#include "prt/render/haar_shader.hpp"

#include "prt/relight/relight_haar.hpp"
#include "prt/render/base_colour.hpp"
#include "prt/render/render.hpp"
#include "prt/render/texel_points.hpp"

namespace prt::render {

std::vector<Rgb> haarRadiance(const Mesh& mesh, const Transfer& transfer, const Material& material,
                              const haar::HaarLight& light, std::span<const Vec3f> texelNormals) {
  if (transfer.domain() == TransferDomain::Texels)
    return relight::relightHaar(transfer, light, texelNormals, material.diffuseOr({}));
  const std::vector<Rgb> albedoAtRows = albedoAtVertices(mesh);
  return relight::relightHaar(transfer, light, mesh.normals, material.diffuseOr(albedoAtRows));
}

ShadeFn haarShader(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                   const Material& material, const haar::HaarLight& light,
                   std::vector<Rgb>& radiance, const std::string& label) {
  if (transfer.domain() != TransferDomain::Texels) {
    radiance = haarRadiance(mesh, transfer, material, light);
    checkFiniteRadiance(radiance, label);
    return vertexRadianceShader(mesh, radiance);
  }
  const TexelRelight texels = texelRelight(mesh, occluder, transfer, material);
  radiance = haarRadiance(mesh, transfer, material, light, texels.points.normals);
  checkFiniteRadiance(radiance, label, "texel");
  const TransferShape::LightmapSize& lm = transfer.shape().lightmap;
  ShadeFn shade = texelRadianceShader(mesh, radiance, lm.width, lm.height, texels.pixelAlbedo);
  if (const BaseColourTexture* texture = pixelTexture(mesh, material))
    shade = texturedShader(mesh, *texture, std::move(shade));
  return shade;
}

}  // namespace prt::render
