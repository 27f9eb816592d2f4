// A project outside prtkit: find_package(prtkit), link prt::prt, bake and relight the white
// furnace (a convex sphere of albedo 0.8 under a constant white sky relights to 0.8).
#include <cmath>
#include <cstdio>
#include <prt/envmap/builtin.hpp>
#include <prt/envmap/project.hpp>
#include <prt/geometry/builtin.hpp>
#include <prt/raytrace/occluder.hpp>
#include <prt/relight/relight.hpp>
#include <prt/transport/bake.hpp>
int main() {
  prt::Mesh mesh = prt::builtinScene("builtin:sphere?subdiv=2");
  auto occ = prt::makeEmbreeOccluder(mesh);
  prt::BakeSettings s;
  s.bands = 3;
  s.samples = 64;
  prt::Transfer t = prt::bake(mesh, *occ, s);
  auto light =
      prt::envmap::projectEnvironment(prt::envmap::builtinEnvironment("builtin:constant"), 3);
  auto r = prt::relight::relight(t, light, prt::Material{},
                                 {mesh.positions, mesh.normals, mesh.albedo}, prt::Vec3f(0.0f));
  std::printf("%zu vertices, radiance[0] = %.4f\n", r.size(), r[0].x);
  return r.size() == mesh.vertexCount() && std::abs(r[0].x - 0.8f) < 0.01f ? 0 : 1;
}
