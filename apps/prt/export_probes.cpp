#include "export_probes.hpp"

#include <fmt/format.h>

#include <cmath>

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/io/probe_grid_export.hpp"
#include "prt/relight/relight_probes.hpp"
#include "prt/sh/rotate.hpp"
#include "report.hpp"

namespace prt::cli {

void exportProbeGrid(const ProbeGridExportArgs& a) {
  // Everything cheap first, so a mistake costs nothing and writes nothing.
  const io::ProbeGridConvention convention =
      io::parseProbeGridConvention(a.engine.empty() ? "threejs" : a.engine);
  const std::array<double, 3> euler = parseEulerDegrees(a.rotate);
  const Mat3d rotation = parseRotation(a.rotate);
  const double stops = a.exposure.empty() ? 0.0 : std::stod(a.exposure);
  const std::string lightSpec = a.light.empty() ? "builtin:sky" : a.light;
  const std::string ext = fileExtension(a.output);
  if (ext != "json" && ext != "glb" && ext != "exr")
    throw Error(a.output, "--format probe-grid writes .json (the grid as JSON), .glb (glTF with "
                          "the PRTKIT_probe_grid extension) or .exr (an OpenEXR volume)");
  const std::vector<NamedPath> inputs = {{"input", a.input}, {"--light", lightSpec}};
  checkOutputs({{"-o", a.output}}, inputs);
  checkWritable(a.output);
  Report report("export", a.json);
  report.check({{"-o", a.output}}, inputs);

  const BakeFile bake = readBake(a.input);
  bake.requireComplete(a.input);
  if (bake.domain() != TransferDomain::Probes)
    throw Error(a.input, std::string("holds ") + toString(bake.domain()) +
                             " transfer: --format probe-grid relights a probe bake (prt probes)");
  const BakedTransfer* t = nullptr;
  for (const BakedTransfer& x : bake.transfers) {
    if (!a.mode.empty() && toString(x.mode()) != a.mode) continue;
    if (t) throw Error(a.input, "holds several probe transfers: choose one with --mode");
    t = &x;
  }
  if (!t) throw Error(a.input, "holds no " + a.mode + " probe transfer");

  const io::Lighting lighting =
      io::loadLighting(lightSpec, t->transfer.bands(), progressBar("projecting"));
  for (const std::string& w : lighting.warnings) warn(w);
  sh::RgbSh light = sh::Rotation(lighting.coefficients.bands, rotation).apply(lighting.coefficients);
  const float scale = static_cast<float>(std::exp2(stops));
  for (Rgb& c : light.c) c = c * scale;
  const relight::ProbeLighting lit = relight::relightProbes(t->transfer, light);

  io::ProbeGridExport g;
  g.grid = lit.grid;
  g.bands = lit.bands;
  g.radiance = lit.coefficients;
  g.source = a.input;
  g.light = lightSpec;
  g.rotateDegrees = euler;
  g.exposureStops = stops;
  if (ext == "glb")
    io::writeProbeGridGltf(a.output, g, convention);
  else if (ext == "exr")
    writeFileAtomically(a.output, io::encodeProbeGridExr(g, convention, a.output));
  else
    writeFileAtomically(a.output, io::formatProbeGrid(g, convention));
  info(fmt::format("wrote {} ({} under {}: {} probes, {} bands as {} SH)", a.output,
                   lit.grid.describe(), lightSpec, lit.grid.probes(),
                   convention.engine ? std::min(3, lit.bands) : lit.bands,
                   io::probeGridConventionName(convention)));
  report.input(a.input);
  report.input(lightSpec);
  report.output(a.output);
  report["format"] = "probe-grid";
  report["engine"] = io::probeGridConventionName(convention);
  report["files"] = Json::array({fileJson(a.output)});
  report["probes"] = lit.grid.probes();
  report.write();
}

}  // namespace prt::cli
