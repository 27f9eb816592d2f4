#pragma once
// prt render of a probe bake (render_probes.cpp): the scene and an object placed in the grid,
// every vertex lit through the relit probes — what an engine does for a moving object.

#include <optional>
#include <string>

#include "prt/core/vec.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/render.hpp"
#include "report.hpp"

namespace prt::cli {

/// What prt render's options say, parsed and checked (render.cpp).
struct ProbeRenderArgs {
  std::string bake, light, camera, output;
  std::string object;  ///< --object: a mesh file or builtin:NAME ("": the scene alone)
  std::string at;      ///< --at x,y,z: where the object's centre goes ("": the grid's centre)
  float objectSize = 0;  ///< --object-size: the object's largest side (0: a fifth of the grid's)
  int bands = 0;
  render::FrameSettings frame;
  Mat3d rotation;
  render::Background background = render::Background::Env;
  Rgb backgroundColour;
  image::WriteOptions write;
  std::optional<float> exposure;  ///< none: auto
};

/// Relights the probe bake under the light, places the object, renders and writes -o; the
/// report gets what prt render reports.
void renderProbeBake(const BakeFile& bake, const ProbeRenderArgs& a, Report& report);

}  // namespace prt::cli
