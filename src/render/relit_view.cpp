#include "prt/render/relit_view.hpp"

#include "prt/core/error.hpp"
#include "prt/relight/encoded_diffuse.hpp"
#include "prt/render/base_colour.hpp"

namespace prt::render {

namespace {

bool perTexel(const Transfer& t) {
  return t.domain() == TransferDomain::Texels;
}

}  // namespace

RelitView::RelitView(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                     const Material& material)
    : mesh_(mesh), occluder_(&occluder), transfer_(transfer), material_(material) {
  if (perTexel(transfer)) texels_ = texelRelight(mesh, occluder, transfer, material);
  relighter_ = relight::Relighter(transfer, surface());
  setMaterial(material);
}

RelitView::RelitView(const Mesh& mesh, const Transfer& transfer, const Material& material)
    : mesh_(mesh), occluder_(nullptr), transfer_(transfer), material_(material) {
  if (perTexel(transfer))
    throw Error(mesh.source,
                "per-texel transfer is relit at its texels' sample points, which "
                "need the mesh's occluder");
  relighter_ = relight::Relighter(transfer, surface());
  setMaterial(material);
}

relight::Surface RelitView::surface() const {
  return perTexel(transfer_) ? texels_.surface()
                             : relight::Surface{mesh_.positions, mesh_.normals, mesh_.albedo};
}

void RelitView::setMaterial(const Material& material) {
  if (encoding_ && material.glossy())
    throw Error(mesh_.source, "the material " + material.spec() +
                                  " has a glossy lobe; an irradiance encoding shades the diffuse "
                                  "part only");
  material_ = material;
  texture_ = pixelTexture(mesh_, material);
  const TextureSplit split = splitForTexture(material, texture_, transfer_);
  relighter_.setMaterial(split.diffuse);
  if (!split.glossy) {
    glossy_.reset();
    return;
  }
  if (!glossy_) {
    glossy_.emplace(transfer_, surface());
    glossy_->setBands(relighter_.bands());
  }
  glossy_->setMaterial(*split.glossy);
}

void RelitView::setBands(int bands) {
  relighter_.setBands(bands);
  if (glossy_) glossy_->setBands(bands);
}

void RelitView::setEncoding(std::optional<sh::IrradianceEncoding> encoding) {
  if (encoding && !transfer_.isMatrix())
    throw Error(mesh_.source,
                "an irradiance encoding is made from the light arriving at each row, which a "
                "matrix transfer holds; vector (diffuse) transfer has already integrated it "
                "against the normal");
  if (encoding && material_.glossy())
    throw Error(mesh_.source, "the material " + material_.spec() +
                                  " has a glossy lobe; an irradiance encoding shades the diffuse "
                                  "part only");
  encoding_ = encoding;
  encoded_.clear();
}

const char* RelitView::rowNoun() const {
  return rowName(transfer_.domain());
}

std::span<const Rgb> RelitView::relight(const sh::RgbSh& light, const Mat3d& rotation,
                                        const Vec3f& eye, const std::string& name,
                                        relight::RelightInfo* info) {
  if (encoding_) {
    // The diffuse material of the split (the texture, if any, multiplies per pixel as ever).
    encoded_ = relight::encodedDiffuse(relighter_.shown(), light, *encoding_, relighter_.material(),
                                       surface(), rotation, info);
    checkFiniteRadiance(encoded_, name, rowNoun());
    return encoded_;
  }
  const std::span<const Rgb> radiance = relighter_.relight(light, rotation, eye, info);
  checkFiniteRadiance(radiance, name, rowNoun());
  if (texture_ && glossy_) {
    highlight_ = glossy_->relight(light, rotation, eye);
    checkFiniteRadiance(highlight_, name, rowNoun());
  }
  return radiance;
}

bool RelitView::relightRotated(std::span<const Rgb> rotatedLight, int lightBands,
                               const Vec3f& eye) {
  PRT_CHECK(!encoding_, "RelitView::relightRotated with an irradiance encoding");
  const int before = relighter_.frames() + (glossy_ ? glossy_->frames() : 0);
  relighter_.relightRotated(rotatedLight, lightBands, eye);
  if (glossy_) highlight_ = glossy_->relightRotated(rotatedLight, lightBands, eye);
  return relighter_.frames() + (glossy_ ? glossy_->frames() : 0) != before;
}

ShadeFn RelitView::shader() const {
  PRT_CHECK(occluder_, "RelitView::shader of a view without an occluder");
  const auto rows = [&](std::span<const Rgb> values, std::span<const Rgb> pixelAlbedo) {
    if (!perTexel(transfer_)) return vertexRadianceShader(mesh_, values);
    const TransferShape::LightmapSize lm = transfer_.shape().lightmap;
    return texelRadianceShader(mesh_, values, lm.width, lm.height, pixelAlbedo);
  };
  ShadeFn shade = rows(radiance(), texels_.pixelAlbedo);
  if (!texture_) return shade;
  return texturedShader(mesh_, *texture_, std::move(shade),
                        glossy_ ? rows(highlight_, {}) : ShadeFn());
}

ShadeFn RelitView::shader(std::span<const Rgb> rowRadiance) const {
  PRT_CHECK(!perTexel(transfer_), "other radiance is drawn per vertex");
  return vertexRadianceShader(mesh_, rowRadiance);
}

}  // namespace prt::render
