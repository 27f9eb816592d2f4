// prt denoise: a per-texel bake → the same bake with its lightmap's noise filtered.
//
//   prt bake scene.glb --domain texels --samples 256 -o scene-texels.glb
//   prt denoise scene-texels.glb -o scene-denoised.glb             (3 levels, strength 2)
//   prt denoise scene-texels.glb --iterations 5 --strength 1.5 -o out.glb --json denoise.json
//
// Every transfer of the bake is filtered by the edge-avoiding à-trous filter of
// transport/denoise_texels.hpp within its UV charts; a seam-fixed bake has its seams fixed again
// after. `prt bake --denoise` does the same at the end of a bake. docs/validation.md says what it
// gains and how to see it (prt validate's noise term).

#include "denoise.hpp"

#include <fmt/format.h>

#include <memory>
#include <string>

#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "report.hpp"

namespace prt::cli {

Json denoiseBake(BakeFile& file, const std::string& name, const DenoiseSettings& settings) {
  checkDenoiseSettings(settings);
  if (file.domain() != TransferDomain::Texels)
    throw Error(name, std::string("holds ") + toString(file.domain()) +
                          " transfer: prt denoise filters a lightmap (bake with --domain texels)");
  file.requireComplete(name);
  file.requireSh(name, "prt denoise filters SH lightmaps");
  for (const BakedTransfer& t : file.transfers)
    if (t.transfer.compressed())
      throw Error(name, "holds compressed transfer (" + t.describe() +
                            "): denoise before compressing");
  const auto occluder = makeEmbreeOccluder(file.mesh);
  Json out = Json::array();
  for (BakedTransfer& t : file.transfers) {
    DenoiseStats st;
    t.transfer = denoiseTexels(file.mesh, *occluder, t.transfer, settings, &st);
    info(fmt::format(
        "{}: a-trous filter, {} levels, strength {:g}, over {} texels in {} charts (texel {:.3g} "
        "wide): estimated noise per row {:.3g} -> {:.3g} ({:.2f} s)",
        t.describe(), settings.iterations, settings.strength, st.texels, st.charts, st.texelSize,
        st.noiseBefore, st.noiseAfter, st.seconds));
    out.push_back({{"transfer", t.describe()},
                   {"texels", st.texels},
                   {"charts", st.charts},
                   {"texelSize", st.texelSize},
                   {"noiseBefore", st.noiseBefore},
                   {"noiseAfter", st.noiseAfter},
                   {"seconds", st.seconds}});
  }
  return out;
}

namespace {

struct DenoiseArgs {
  std::string input, output, json;
  DenoiseSettings settings;
};

void runDenoise(const DenoiseArgs& a) {
  if (fileExtension(a.output) != "glb" && !isStandardOutput(a.output))
    throw Error(a.output + ": the bake file must end in .glb");
  checkDenoiseSettings(a.settings);
  checkOutputs({{"-o", a.output}}, {{"input", a.input}});
  checkWritable(a.output);
  Report report("denoise", a.json);
  report.check({{"-o", a.output}}, {{"input", a.input}});
  report.input(a.input);
  BakeFile bake = readBake(a.input);
  const Json done = denoiseBake(bake, a.input, a.settings);
  writeBake(a.output, bake);
  info(fmt::format("wrote {}", a.output));
  report.output(a.output);
  report["iterations"] = a.settings.iterations;
  report["strength"] = a.settings.strength;
  report["denoise"] = done;
  report.write();
}

}  // namespace

void addDenoiseCommand(CLI::App& root) {
  auto args = std::make_shared<DenoiseArgs>();
  auto* cmd = root.add_subcommand(
      "denoise",
      "Filter the noise of a per-texel bake's lightmap (edge-avoiding a-trous, within charts)");
  cmd->add_option("bake", args->input, "Per-texel bake file (.glb)")->required();
  cmd->add_option("-o,--output", args->output, "The filtered bake (.glb)")->required();
  cmd->add_option("--iterations", args->settings.iterations,
                  "Levels of the filter: taps 1, 2, 4 ... texels apart")
      ->check(intRange(1, 8))
      ->capture_default_str();
  cmd->add_option("--strength", args->settings.strength,
                  "How many standard deviations of the estimated noise a difference between two "
                  "texels may span and still be averaged (larger: smoother, edges kept less)")
      ->check(CLI::Range(1e-3, 100.0))
      ->capture_default_str();
  addJsonOption(cmd, args->json);
  cmd->callback([args] { runDenoise(*args); });
}

}  // namespace prt::cli
