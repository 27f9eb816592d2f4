#include "reference_input.hpp"

#include <fmt/format.h>

#include <cmath>

#include "prt/core/error.hpp"
#include "prt/core/file.hpp"

namespace prt::cli {

ReferenceScene referenceScene(const Mesh& mesh, const envmap::Environment& environment,
                              const std::string& bakeName, const std::string& lightName,
                              const Mat3d& rotation, const BakedTransfer& baked,
                              const Material& material, const Vec3f& eye) {
  ReferenceScene s;
  s.mesh = &mesh;
  s.environment = &environment;
  s.bakeName = bakeName;
  s.lightName = lightName;
  s.rotation = rotation;
  s.mode = baked.mode();
  s.bounces = baked.recipe.effectiveBounces();
  s.material = render::referenceMaterial(material, baked.transfer.layout());
  if (baked.transfer.isMatrix() && s.material.glossy()) s.eye = eye;
  s.shape = baked.transfer.shape();
  return s;
}

io::ReferenceFile readMatchingReference(const std::string& path, const ReferenceScene& s) {
  if (fileExtension(path) != "json")
    throw Error(path, "--reference takes the .json of prt reference (a .bin holds no scene)");
  io::ReferenceFile ref = io::readReferenceJson(path);
  const auto differ = [&](const char* what, const std::string& theirs, const char* here,
                          const std::string& ours) {
    throw Error(path, fmt::format("was computed for {} '{}', not {} ({}): run prt reference again",
                                  what, theirs, here, ours));
  };
  if (ref.meshVertices != s.mesh->vertexCount() ||
      ref.meshFingerprint != meshFingerprint(*s.mesh))
    differ("the bake", ref.bakeFile, "this mesh", s.bakeName);
  io::ReferenceFile expected;
  expected.setRows(*s.mesh, s.shape);
  if (expected.domain() != ref.domain())
    throw Error(path, fmt::format("holds per-{} radiance; {} holds per-{} transfer: run prt "
                                  "reference on it",
                                  rowName(ref.domain()), s.bakeName, rowName(expected.domain())));
  if (ref.lightmapWidth != expected.lightmapWidth || ref.lightmapHeight != expected.lightmapHeight ||
      ref.lightmapUvFingerprint != expected.lightmapUvFingerprint)
    throw Error(path, fmt::format("was computed for a {} x {} lightmap over other lightmap UVs "
                                  "or of another size than {}'s {} x {}: run prt reference again",
                                  ref.lightmapWidth, ref.lightmapHeight, s.bakeName,
                                  expected.lightmapWidth, expected.lightmapHeight));
  if (ref.environmentFingerprint != io::environmentFingerprint(*s.environment))
    differ("the environment", ref.lightSource, "this one", s.lightName);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      if (std::abs(ref.rotation[3 * i + k] - s.rotation.m[i][k]) > 1e-9)
        throw Error(path, "was computed with another light rotation (--rotate): give the same "
                          "--rotate as prt reference had");
  if (ref.mode != toString(s.mode) || ref.bounces != s.bounces)
    throw Error(path, fmt::format("holds {} transport with {} bounce(s), not {} with {}", ref.mode,
                                  ref.bounces, toString(s.mode), s.bounces));
  if (ref.material != s.material.spec())
    throw Error(path, fmt::format("was computed for the material {}, not {}", ref.material,
                                  s.material.spec()));
  if (s.eye) {
    if (!ref.eye)
      throw Error(path, "holds diffuse radiance; a glossy material needs the eye it is seen from");
    const Vec3f d = *ref.eye - *s.eye;
    if (std::sqrt(dot(d, d)) > 1e-4f * (1.0f + std::sqrt(dot(*s.eye, *s.eye))))
      throw Error(path, fmt::format("sees the glossy vertices from ({:.4g}, {:.4g}, {:.4g}), "
                                    "this view from ({:.4g}, {:.4g}, {:.4g}): give prt reference "
                                    "--eye at this camera",
                                    ref.eye->x, ref.eye->y, ref.eye->z, s.eye->x, s.eye->y,
                                    s.eye->z));
  }
  return ref;
}

render::ReferenceResult toReferenceResult(const io::ReferenceFile& ref) {
  render::ReferenceResult r;
  r.vertices = ref.vertices;
  r.radiance = ref.radiance;
  r.stdError = ref.stdError;
  r.rays = ref.rays;
  r.seconds = ref.seconds;
  return r;
}

}  // namespace prt::cli
