#pragma once
// prt render of a Haar bake (render_haar.cpp): the environment projected into the bake's cube
// and cut to its K largest terms (haar/project_light.hpp), the rows relit as sparse products
// (relight/relight_haar.hpp) and drawn per vertex. Rotation resamples the environment.

#include <optional>
#include <string>

#include "prt/core/vec.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/render.hpp"
#include "prt/transfer/material.hpp"
#include "report.hpp"

namespace prt::cli {

/// The light's terms when --terms is not given: Ng et al.'s "a few hundred" (their figures use
/// 100–200 of a 6 × 64² cube).
inline constexpr int kDefaultHaarLightTerms = int(haar::kDefaultLightTerms);

struct HaarRenderArgs {
  std::string bake, light, camera, output;
  int lightTerms = kDefaultHaarLightTerms;
  render::FrameSettings frame;
  Mat3d rotation;
  render::Background background = render::Background::Env;
  Rgb backgroundColour;
  image::WriteOptions write;
  std::optional<float> exposure;  ///< none: auto
};

/// Relights `baked` (a Haar transfer of `bake`) under the environment and writes -o; the report
/// gets what prt render reports.
void renderHaarBake(const BakeFile& bake, const BakedTransfer& baked, const Material& material,
                    const HaarRenderArgs& a, Report& report);

}  // namespace prt::cli
