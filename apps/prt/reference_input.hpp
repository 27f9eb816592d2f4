#pragma once
// `--reference FILE` (validate, render): a `prt reference` JSON read back instead of computing
// the brute-force radiance again, refused in one line unless it was computed for this scene.

#include <optional>
#include <string>

#include "prt/core/vec.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/reference_file.hpp"
#include "prt/render/reference.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/material.hpp"

namespace prt::cli {

/// What the reference must have been computed for: the mesh and environment (by fingerprint),
/// the light's rotation, the transport (mode, bounces, material) and, for a glossy material,
/// the eye the vertices were seen from; for per-texel transfer the lightmap.
struct ReferenceScene {
  const Mesh* mesh = nullptr;
  const envmap::Environment* environment = nullptr;
  std::string bakeName, lightName;
  Mat3d rotation;
  TransferMode mode = TransferMode::Shadowed;
  int bounces = 0;
  Material material;
  std::optional<Vec3f> eye;  ///< set when the material is glossy
  /// The transfer's rows (io::ReferenceFile::setRows): per texel the lightmap they are texels
  /// of (the reference's must be the same, over the same lightmap UVs).
  TransferShape shape;
};

/// The scene of a verb that relights `baked` with `material` under `environment` turned by
/// `rotation`, glossy vertices seen from `eye`: what the reference integrates for it
/// (render::referenceMaterial; the eye only for a glossy matrix transfer).
ReferenceScene referenceScene(const Mesh& mesh, const envmap::Environment& environment,
                              const std::string& bakeName, const std::string& lightName,
                              const Mat3d& rotation, const BakedTransfer& baked,
                              const Material& material, const Vec3f& eye);

/// Reads `path` (io::readReferenceJson) and checks it against `scene`: throws prt::Error naming
/// the file and the first thing that differs.
io::ReferenceFile readMatchingReference(const std::string& path, const ReferenceScene& scene);

/// The estimates of a reference file as the validator takes them.
render::ReferenceResult toReferenceResult(const io::ReferenceFile& ref);

}  // namespace prt::cli
