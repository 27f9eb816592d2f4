#include "prt/render/relit_view.hpp"

#include "prt/core/error.hpp"
#include "prt/render/base_colour.hpp"
#include "prt/render/exposure.hpp"

namespace prt::render {

namespace {

bool perTexel(const Transfer& t) {
  return t.domain() == TransferDomain::Texels;
}

}  // namespace

RelitView::RelitView(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                     const Material& material)
    : mesh_(mesh), occluder_(occluder), transfer_(transfer), material_(material) {
  if (perTexel(transfer)) texels_ = texelRelight(mesh, occluder, transfer, material);
  const relight::Surface surface =
      perTexel(transfer) ? texels_.surface()
                         : relight::Surface{mesh.positions, mesh.normals, mesh.albedo};
  texture_ = pixelTexture(mesh, material);
  const TextureSplit split = splitForTexture(material, texture_, transfer);
  relighter_ = relight::Relighter(transfer, surface);
  relighter_.setMaterial(split.diffuse);
  if (split.glossy) {
    glossy_.emplace(transfer, surface);
    glossy_->setMaterial(*split.glossy);
  }
}

void RelitView::setBands(int bands) {
  relighter_.setBands(bands);
  if (glossy_) glossy_->setBands(bands);
}

const char* RelitView::rowNoun() const {
  return rowName(transfer_.domain());
}

std::span<const Rgb> RelitView::relight(const sh::RgbSh& light, const Mat3d& rotation,
                                        const Vec3f& eye, const std::string& name,
                                        relight::RelightInfo* info) {
  const std::span<const Rgb> radiance = relighter_.relight(light, rotation, eye, info);
  checkFiniteRadiance(radiance, name, rowNoun());
  if (texture_ && glossy_) {
    highlight_ = glossy_->relight(light, rotation, eye);
    checkFiniteRadiance(highlight_, name, rowNoun());
  }
  return radiance;
}

ShadeFn RelitView::shader() const {
  const auto rows = [&](std::span<const Rgb> values, std::span<const Rgb> pixelAlbedo) {
    if (!perTexel(transfer_)) return vertexRadianceShader(mesh_, values);
    const TransferShape::LightmapSize lm = transfer_.shape().lightmap;
    return texelRadianceShader(mesh_, values, lm.width, lm.height, pixelAlbedo);
  };
  ShadeFn shade = rows(relighter_.radiance(), texels_.pixelAlbedo);
  if (!texture_) return shade;
  return texturedShader(mesh_, *texture_, std::move(shade),
                        glossy_ ? rows(highlight_, {}) : ShadeFn());
}

ShadeFn RelitView::shader(std::span<const Rgb> rowRadiance) const {
  PRT_CHECK(!perTexel(transfer_), "other radiance is drawn per vertex");
  return vertexRadianceShader(mesh_, rowRadiance);
}

float RelitView::autoExposure(const Camera& camera, int width, int height,
                              image::ToneMap op) const {
  return render::autoExposure(occluder_, shader(), camera, width, height, op);
}

}  // namespace prt::render
