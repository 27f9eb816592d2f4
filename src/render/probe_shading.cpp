#include "prt/render/probe_shading.hpp"

#include "prt/core/parallel.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/render/render.hpp"
#include "prt/sh/rotate.hpp"

namespace prt::render {

std::vector<Rgb> shadeThroughProbes(const relight::ProbeLighting& lighting, const Mesh& mesh) {
  const std::vector<Rgb> albedo = albedoAtVertices(mesh);
  std::vector<Rgb> out(mesh.vertexCount());
  parallelFor(mesh.vertexCount(), 256, [&](std::size_t b, std::size_t e) {
    std::vector<Rgb> sh(lighting.coeffs());
    for (std::size_t v = b; v < e; ++v) {
      relight::sampleProbes(lighting, mesh.positions[v], sh.data());
      out[v] = relight::shadeDiffuse(sh.data(), lighting.bands, mesh.normals[v], albedo[v]);
    }
  });
  return out;
}

FrameSurvey probeSurvey(const Mesh& mesh, const Transfer& transfer, const sh::RgbSh& light,
                        const Mat3d& rotation, const Camera& camera, int width, int height,
                        image::ToneMap op, int bands) {
  const Transfer cut = bands > 0 && bands < transfer.bands() ? transfer.cut(bands) : transfer;
  sh::RgbSh turned = light;
  sh::Rotation(light.bands, rotation).apply(light.c.data(), turned.c.data());
  Mesh scene = mesh;
  foldBaseColour(scene);
  const std::vector<Rgb> radiance = shadeThroughProbes(relight::relightProbes(cut, turned), scene);
  const auto occluder = makeEmbreeOccluder(scene);
  return surveyFrame(*occluder, vertexRadianceShader(scene, radiance), camera, width, height, op);
}

}  // namespace prt::render
