// prt export: a bake file → other formats.
//
//   prt export bunny.glb --format games202 -o transport.txt      (the course's transport.txt)

#include <fmt/format.h>

#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/games202_transport.hpp"
#include "prt/relight/view_transfer.hpp"

namespace prt::cli {

namespace {

struct ExportArgs {
  std::string input;
  std::string format = "games202";
  std::string mode;
  std::string layout = "faces";
  std::string channel;
  std::string output;
};

void runExport(const ExportArgs& a) {
  if (a.format != "games202") throw Error("--format " + a.format + ": unknown (expected games202)");
  Games202Layout layout;
  if (a.layout == "faces")
    layout = Games202Layout::Faces;
  else if (a.layout == "vertices")
    layout = Games202Layout::Vertices;
  else
    throw Error("--layout " + a.layout + ": expected faces (the course's file) or vertices");
  std::optional<ChannelSelect> channel;
  if (!a.channel.empty()) channel = parseChannelSelect(a.channel);
  checkOutputs({{"-o", a.output}}, {{"input", a.input}});
  checkWritable(a.output);

  const BakeFile bake = readBake(a.input);
  bake.requireComplete(a.input);
  if (bake.transfers.empty()) throw Error(a.input, "holds no transfer");
  const BakedTransfer* t = nullptr;
  if (!a.mode.empty()) {
    // A vector of the mode before a matrix: transport.txt holds vectors.
    const TransferMode m = parseTransferMode(a.mode);
    t = bake.find(m, TransferLayout::Vector);
    if (!t) t = bake.find(m);
    if (!t) throw Error(a.input, "holds no " + a.mode + " transfer");
  } else if (bake.transfers.size() == 1) {
    t = &bake.transfers[0];
  } else {
    std::string list;
    for (const auto& x : bake.transfers)
      list += std::string(list.empty() ? "" : ", ") + x.describe();
    throw Error(a.input, "holds several transfers (" + list + "): choose one with --mode");
  }
  // transport.txt holds diffuse vectors: a compressed transfer exports its reconstruction, a
  // matrix its diffuse part t = Mᵀd(n) (what a diffuse surface relights with; never a row of M).
  Transfer field = t->transfer.toDense();
  if (field.isMatrix()) {
    field = relight::diffuseTransfer(field, bake.mesh.normals);
    info(
        fmt::format("{}: the {} transfer holds matrices; exporting their diffuse part "
                    "(transfer = Mᵀ d(n), the clamped cosine about each normal)",
                    a.input, toString(t->mode())));
  }
  if (field.channels() == 3) {
    if (!channel)
      throw Error(a.input,
                  std::string("the ") + toString(t->mode()) +
                      " transfer is RGB (coloured inter-reflection) and transport.txt holds one "
                      "value per coefficient: pick --channel luminance, r, g or b");
    field = selectChannel(field, *channel);
  }
  if (field.bands() != 3)
    warn(fmt::format("{} bands: the course's shaders expect 3 bands (9 coefficients per line)",
                     field.bands()));
  writeGames202Transport(a.output, field, bake.mesh, layout);
  info(fmt::format(
      "wrote {} ({} transfer, {} bands, header {} vertices, {} lines)", a.output,
      toString(t->mode()), field.bands(), bake.mesh.vertexCount(),
      layout == Games202Layout::Faces ? 3 * bake.mesh.triangleCount() : bake.mesh.vertexCount()));
}

}  // namespace

void addExportCommand(CLI::App& root) {
  auto args = std::make_shared<ExportArgs>();
  auto* cmd = root.add_subcommand("export",
                                  "Export a bake file to another format (GAMES202 transport.txt)");
  cmd->add_option("input", args->input, "Bake file (.glb)")->required();
  cmd->add_option("--format", args->format, "games202")->capture_default_str();
  cmd->add_option("--mode", args->mode, "Which transfer, if the file holds several");
  cmd->add_option(
         "--layout", args->layout,
         "faces (the course's file: 3 lines per triangle) | vertices (one line per vertex)")
      ->capture_default_str();
  cmd->add_option("--channel", args->channel, "For RGB transfer: luminance | r | g | b");
  cmd->add_option("-o,--output", args->output, "Output file")->required();
  cmd->callback([args] { runExport(*args); });
}

}  // namespace prt::cli
