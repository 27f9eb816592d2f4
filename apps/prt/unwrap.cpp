// prt unwrap: a mesh → the same mesh with a generated lightmap UV set (glTF TEXCOORD_1), for
// per-texel bakes (prt bake --domain texels) of meshes that come without one.
//
//   prt unwrap bunny.obj -o bunny-atlas.glb                       (512², 2 texels of padding)
//   prt unwrap scan.ply -o scan.glb --resolution 2048 --padding 4
//   prt bake bunny-atlas.glb --domain texels --resolution 512 -o bunny-texels.glb
//
// Charts grown by normal cone, flattened by least squares conformal maps, packed with a
// gutter (prt/unwrap/unwrap.hpp). The atlas's figures go to stderr.

#include <fmt/format.h>

#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/units.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/io/mesh_file.hpp"
#include "prt/unwrap/unwrap.hpp"
#include "report.hpp"

namespace prt::cli {

namespace {

struct UnwrapArgs {
  std::string input;
  std::string output;
  UnwrapSettings settings;
  std::string json;
};

void runUnwrap(const UnwrapArgs& a) {
  if (fileExtension(a.output) != "glb" && !isStandardOutput(a.output))
    throw Error(a.output + ": the unwrapped mesh is a glTF binary and must end in .glb");
  checkOutputs({{"-o", a.output}}, {{"input", a.input}});
  checkWritable(a.output);
  Report json("unwrap", a.json);
  json.check({{"-o", a.output}}, {{"input", a.input}});
  LoadReport report;
  const Mesh mesh = loadMesh(a.input, &report);
  for (const std::string& w : report.warnings) warn(w);
  if (!mesh.lightmapUvs.empty()) info(mesh.source + ": its lightmap UV set is replaced");
  // The footprint before the heavy work (issue 31), as the bake states its own; unwrap refuses
  // one above the machine's memory by the same policy.
  const auto statement = [](const UnwrapFootprint& f) { info(describe(f)); };
  const UnwrapResult r = unwrap(mesh, a.settings, progressBar("unwrap"), statement);
  writeMeshGlb(a.output, r.mesh);
  const AtlasStats& s = r.stats;
  info(fmt::format(
      "{}: {} charts ({} grown, {} cuts where the map folded or stretched), {} -> {} vertices, "
      "{:.2f} s",
      mesh.source, s.charts, r.grownCharts, r.splitCharts, mesh.vertexCount(), r.mesh.vertexCount(),
      s.seconds));
  info(fmt::format(
      "atlas {0}x{0}, padding {1}, packed by {6}: charts cover {2:.1f}% of the square ({3:.1f}% "
      "wasted), {4:.1f}% of the texels ({5:.1f}% wasted)",
      a.settings.resolution, a.settings.padding, 100 * s.chartArea, 100 * s.wastedArea,
      100 * s.texelsCovered, 100 * s.wastedTexels,
      r.packedByShape ? "shape"
                      : "bounding rectangle (the search by shape found no room or took too long)"));
  info(fmt::format(
      "texel density / mean: 5-95% {:.2f}-{:.2f} (min {:.2f}, max {:.2f}); L2 "
      "stretch {:.3f} (worst triangle {:.2f})",
      s.densityP05, s.densityP95, s.densityMin, s.densityMax, s.stretchL2, s.stretchL2Max));
  info("wrote " + a.output);
  json.input(a.input);
  json.output(a.output);
  json["mesh"] = meshJson(r.mesh);
  json["atlas"] = {{"resolution", a.settings.resolution},
                   {"padding", a.settings.padding},
                   {"maxConeDegrees", a.settings.maxConeDegrees},
                   {"maxChartTriangles", a.settings.maxChartTriangles},
                   {"charts", s.charts},
                   {"grownCharts", r.grownCharts},
                   {"splitCharts", r.splitCharts},
                   {"packedBy", r.packedByShape ? "shape" : "boundingRectangle"},
                   {"verticesBefore", mesh.vertexCount()},
                   {"verticesAfter", r.mesh.vertexCount()},
                   {"chartArea", s.chartArea},
                   {"wastedArea", s.wastedArea},
                   {"texelsCovered", s.texelsCovered},
                   {"wastedTexels", s.wastedTexels},
                   {"densityP05", s.densityP05},
                   {"densityP95", s.densityP95},
                   {"densityMin", s.densityMin},
                   {"densityMax", s.densityMax},
                   {"stretchL2", s.stretchL2},
                   {"stretchL2Max", s.stretchL2Max},
                   {"seconds", s.seconds}};
  json.write();
}

}  // namespace

void addUnwrapCommand(CLI::App& root) {
  auto args = std::make_shared<UnwrapArgs>();
  auto* cmd = root.add_subcommand(
      "unwrap",
      "Generate a lightmap UV set (TEXCOORD_1): charts by normal cone, least squares conformal "
      "maps, packed with a gutter; writes the mesh as a glTF binary");
  cmd->add_option("mesh", args->input, "Mesh file (.obj .ply .off .gltf .glb) or builtin:NAME")
      ->required();
  cmd->add_option("-o,--output", args->output, "Output mesh (.glb)")->required();
  cmd->add_option("--resolution", args->settings.resolution,
                  "Lightmap side in texels the gutter is sized for (default 512)")
      ->check(intRange(1, kMaxLightmapSide));
  cmd->add_option("--padding", args->settings.padding,
                  "Texels kept empty between charts and from the border (default 2)")
      ->check(intRange(0, kMaxLightmapPadding));
  cmd->add_option("--max-cone", args->settings.maxConeDegrees,
                  "Largest angle in degrees between a triangle's normal and its chart's mean "
                  "(default 60; smaller: more charts, less stretch)")
      ->check(finite(1, 89));
  cmd->add_option("--max-chart-triangles", args->settings.maxChartTriangles,
                  "Cut charts larger than this many triangles into compact parts before they "
                  "are flattened (default 100000; 0: unbounded, one solve per chart however "
                  "large)")
      ->check(intRange(0, 1000000000));
  addJsonOption(cmd, args->json);
  cmd->callback([args] { runUnwrap(*args); });
}

}  // namespace prt::cli
