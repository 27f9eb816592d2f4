#pragma once
// The light a verb or viewer relights with, from anything a user names — an environment (image,
// face folder, builtin:NAME) or an SH light file (.json, the course's light.txt) — under one set
// of rules, so prt render, view and web answer the same input the same way (validate, reference
// and the demo need the environment's texels themselves, for the Monte Carlo reference, and
// load environments only, through envmap::loadEnvironment):
//
//   * an environment is projected to the bands asked for (exactly: the transfer's);
//   * a light file keeps its coefficients; with more bands than asked it is cut (exact: bands
//     are orthogonal); with fewer it is used as it is and `warnings` says that the transfer's
//     upper bands see no light (relighting uses the light's bands);
//   * pixels an image reader repaired (non-finite or negative set to 0) are reported once per
//     file, with the reason.

#include <optional>
#include <string>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/sh/sh.hpp"

namespace prt::io {

struct Lighting {
  std::string name;                          ///< as given
  std::optional<envmap::Environment> image;  ///< the environment, unless a light file
  sh::RgbSh coefficients;                    ///< at min(bands asked, the file's bands)
  int sourceBands = 0;                       ///< a light file's own bands (0 for environments)
  std::vector<std::string> warnings;         ///< one line each, naming the file
  bool isShFile() const { return !image.has_value(); }
};

/// Loads `spec` for a transfer of `bands` bands. Throws prt::Error naming the file.
Lighting loadLighting(const std::string& spec, int bands, const ProgressFn& progress = {});

/// The light's coefficients padded with zeros to `bands` (for shaders that always read the
/// transfer's bands; the zeros are what "the upper bands see no light" means).
sh::RgbSh padded(const sh::RgbSh& light, int bands);

}  // namespace prt::io
