// The README's "Using the library" example, verbatim between the markers: built and run by
// tests/install/check_find_package.sh against the installed package, and checked to be the
// README's text, so the example cannot rot.
// readme-begin
#include <prt/envmap/load.hpp>
#include <prt/envmap/project.hpp>
#include <prt/geometry/load.hpp>
#include <prt/raytrace/occluder.hpp>
#include <prt/relight/relight.hpp>
#include <prt/transport/bake.hpp>

int main() {
  prt::Mesh mesh = prt::loadMesh("builtin:cornell");  // or "bunny.obj", "scene.glb", ...
  auto occluder = prt::makeEmbreeOccluder(mesh);

  prt::BakeSettings s;  // diffuse (vector) transfer, shadowed, 3 bands
  s.mode = prt::TransferMode::Shadowed;
  s.bands = 3;
  s.samples = 256;
  prt::Transfer transfer = prt::bake(mesh, *occluder, s);

  prt::envmap::LoadedEnvironment sky = prt::envmap::loadEnvironment("builtin:sky");  // or .exr
  prt::sh::RgbSh light = prt::envmap::projectEnvironment(sky.env, 3);

  // Per-vertex exit radiance, the light turned 90° about +Y.
  std::vector<prt::Rgb> radiance = prt::relight::relight(
      transfer, light, prt::Material{}, {mesh.positions, mesh.normals, mesh.albedo},
      /*eye (glossy transfer only)*/ prt::Vec3f(0.0f), prt::rotationEulerXYZ(0, 90, 0));
  return radiance.size() == mesh.vertexCount() ? 0 : 1;
}
// readme-end
