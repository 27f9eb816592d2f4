#pragma once
// prt demo's all-frequency row (issue 33): the demo's shadowed SH bake beside a Haar bake of the
// same scene at the same bytes per vertex (docs/haar.md), under each environment (up to two):
// both validated against the Monte Carlo reference at the same vertices and drawn, so the sun's
// shadow shows sharp where SH blurs it and the table says what each costs.

#include <string>
#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/primary.hpp"

namespace prt::cli {

struct DemoArgs;

/// One basis under one environment.
struct HaarRowEntry {
  std::string label;  ///< "SH, 5 bands"
  std::string image;  ///< relative to the demo folder
  std::size_t bytesPerVertex = 0;
  double relRmse = 0, energyRel = 0;
};

struct HaarRowLight {
  std::string environment;
  HaarRowEntry sh, haar;
  double refStdErr = 0;
};

struct HaarRow {
  int bands = 0;                           ///< the SH bake's
  int resolution = 0, terms = 0;           ///< the Haar bake's cube and terms per vertex
  int lightTerms = 0;                      ///< the Haar light's
  int vertices = 0, referenceSamples = 0;  ///< validated
  double bakeSeconds = 0, seconds = 0;
  std::vector<HaarRowLight> lights;
};

/// Bakes the Haar transfer of `mesh` at the bytes of `shadowed` (the demo's SH bake), validates
/// and draws both under each of `envs` (named by `envNames`; the first two), writing
/// img/haar_*.png into `folder`.
HaarRow demoHaarRow(const Mesh& mesh, const Occluder& occluder, const BakedTransfer& shadowed,
                    const std::vector<const envmap::Environment*>& envs,
                    const std::vector<std::string>& envNames, const DemoArgs& a,
                    const render::FrameSettings& frame, const render::Camera& camera,
                    const std::string& folder);

}  // namespace prt::cli
