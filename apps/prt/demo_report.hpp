#pragma once
// prt demo --json: the figures the demo's page shows, as numbers (docs/formats-report.md).

#include <string>
#include <vector>

#include "demo_haar.hpp"
#include "demo_page.hpp"
#include "demo_texels.hpp"
#include "prt/io/bake_file.hpp"
#include "report.hpp"

namespace prt::cli {

/// One environment as the page shows it: its light, pictures and each mode's validation table.
Json environmentJson(const LightResult& light, const sh::RgbSh& coefficients);

/// What a finished demo made, for its report.
struct DemoOutcome {
  const DemoScene& scene;
  const BakeFile& bake;
  const GlossyBake* glossy;  ///< null without the glossy row
  Json environments;         ///< environmentJson of each
  const TexelRow& texels;
  const HaarRow* haar;       ///< null without a shadowed bake
  Json web;                  ///< the live viewer's web report
  std::string webMissing;    ///< why there is no live viewer ("" when there is)
  double bakeSeconds = 0;
  double totalSeconds = 0;
};

/// Fills and writes `report` (inputs, the folder `output` as written, the figures).
void writeDemoReport(Report& report, DemoOutcome outcome, const std::string& output,
                     const std::vector<std::string>& environments);

}  // namespace prt::cli
