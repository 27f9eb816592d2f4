#include "probe_view.hpp"

#include <algorithm>

#include "prt/geometry/load.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/render/probe_shading.hpp"
#include "prt/render/render.hpp"

namespace prt::viewer {

namespace {

/// A regular octahedron of circumradius r at c: six vertices, eight faces, normals outward.
void appendOctahedron(Mesh& m, const Vec3f& c, float r) {
  static const Vec3f axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // Faces by their axes (x±, y±, z±), counter-clockwise seen from outside.
  static const std::uint32_t faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                            {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (const Vec3f& a : axes) {
    m.positions.push_back(c + a * r);
    m.normals.push_back(a);
    m.albedo.push_back(Rgb(1.0f));
  }
  for (const auto& f : faces) m.triangles.push_back({base + f[0], base + f[1], base + f[2]});
}

}  // namespace

Mesh probeSceneMesh(const BakeFile& bake, const MovingObject* object, bool showProbes) {
  Mesh drawn = bake.mesh;
  foldBaseColour(drawn);
  if (object) {
    Mesh placed = object->placed();
    foldBaseColour(placed);
    appendMesh(drawn, placed);
  }
  if (showProbes) {
    const ProbeGrid grid = bake.probeGrid();
    Mesh markers;
    markers.source = "probes";
    const float r =
        0.1f * std::min({grid.spacing.x, grid.spacing.y, grid.spacing.z});
    for (std::size_t p = 0; p < grid.probes(); ++p) appendOctahedron(markers, grid.position(p), r);
    markers.parts.push_back({"probes", 0, std::uint32_t(markers.positions.size()), 0,
                             std::uint32_t(markers.triangles.size())});
    appendMesh(drawn, markers);
  }
  // Nothing here is drawn through a lightmap or a texture: the radiance arrives per vertex.
  drawn.uvs.clear();
  drawn.lightmapUvs.clear();
  return drawn;
}

std::vector<Rgb> shadeProbeScene(const Transfer& transfer, int bands,
                                 std::span<const Rgb> rotatedLight, const Mesh& mesh) {
  sh::RgbSh light(bands);
  std::copy_n(rotatedLight.begin(), light.c.size(), light.c.begin());
  const Transfer cut = bands < transfer.bands() ? transfer.cut(bands) : transfer;
  return render::shadeThroughProbes(relight::relightProbes(cut, light), mesh);
}

render::FrameSurvey vertexRadianceSurvey(const Mesh& mesh, std::span<const Rgb> radiance,
                                         const render::Camera& camera, int width, int height,
                                         image::ToneMap op) {
  const auto occluder = makeEmbreeOccluder(mesh);
  return render::surveyFrame(*occluder, render::vertexRadianceShader(mesh, radiance), camera,
                             width, height, op);
}

}  // namespace prt::viewer
