#include "prt/render/base_colour.hpp"

#include <utility>

#include "prt/core/error.hpp"

namespace prt::render {

const BaseColourTexture* pixelTexture(const Mesh& mesh, const Material& material) {
  return mesh.baseColour && !material.diffuse ? &*mesh.baseColour : nullptr;
}

TextureSplit splitForTexture(const Material& material, const BaseColourTexture* texture,
                             const Transfer& transfer) {
  TextureSplit split{material, std::nullopt};
  if (!texture || !transfer.isMatrix() || !material.glossy()) return split;
  // e = kd ⊙ diffuse + ks ⊙ glossy is linear in (kd, ks): each half relights with the other's
  // colour at zero, and the two add up to the whole.
  split.diffuse.specular = Rgb(0.0f);
  split.glossy = material;
  split.glossy->diffuse = Rgb(0.0f);
  return split;
}

ShadeFn texturedShader(const Mesh& mesh, const BaseColourTexture& texture, ShadeFn diffuse,
                       ShadeFn glossy) {
  if (mesh.uvs.size() != mesh.vertexCount())
    throw Error("render: the base colour texture needs a texture UV per vertex (the mesh has " +
                std::to_string(mesh.uvs.size()) + " for " + std::to_string(mesh.vertexCount()) +
                " vertices)");
  return [&mesh, &texture, diffuse = std::move(diffuse), glossy = std::move(glossy)](const Ray& ray,
                                                                                     const Hit& h) {
    const auto& t = mesh.triangles[h.triangle];
    const float w0 = 1.0f - h.u - h.v;
    const Vec2f* uv = mesh.uvs.data();
    const Vec2f at{uv[t[0]].x * w0 + uv[t[1]].x * h.u + uv[t[2]].x * h.v,
                   uv[t[0]].y * w0 + uv[t[1]].y * h.u + uv[t[2]].y * h.v};
    Rgb r = diffuse(ray, h) * sampleBaseColour(texture, at);
    if (glossy) r += glossy(ray, h);
    return r;
  };
}

}  // namespace prt::render
