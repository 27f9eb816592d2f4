#include "prt/render/probe_shading.hpp"

#include "prt/core/parallel.hpp"
#include "prt/relight/relight_probes.hpp"

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

}  // namespace prt::render
