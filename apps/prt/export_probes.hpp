#pragma once
// prt export --format probe-grid: a probe bake relit under one light, written for engines
// (io/probe_grid_export.hpp; docs/probes.md, "Exports").

#include <string>

namespace prt::cli {

struct ProbeGridExportArgs {
  std::string input, output, json;
  std::string mode;      ///< --mode: which transfer, if the file holds several
  std::string light;     ///< "" = builtin:sky
  std::string rotate;    ///< X,Y,Z degrees
  std::string exposure;  ///< stops ("" = 0)
  std::string engine;    ///< "" = threejs
};

void exportProbeGrid(const ProbeGridExportArgs& a);

}  // namespace prt::cli
