// prt export: a bake file → other formats.
//
//   prt export bunny.glb --format games202 -o transport.txt      (the course's transport.txt)
//   prt export box.glb --format exr -o box-textures              (per-texel transfer: float
//                                                                 coefficient textures + JSON)
//   prt export box.glb --format png -o box-textures              (16-bit, scale and offset in
//                                                                 the JSON)
//   prt export bunny.glb -o transport.txt --json export.json      (what it wrote, as JSON)

#include <fmt/format.h>

#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/games202_transport.hpp"
#include "prt/io/lightmap_textures.hpp"
#include "prt/relight/view_transfer.hpp"
#include "report.hpp"

namespace prt::cli {

namespace {

struct ExportArgs {
  std::string input;
  std::string format = "games202";
  std::string mode;
  std::string layout = "faces";
  std::string channel;
  std::string output;
  std::string json;
};

/// --json's report of an export (nothing when not wanted), checked before any work: the
/// format, the transfer exported (as the bake file holds it, transferJson), what was written.
/// `folder`: -o is a folder written as a whole (coefficient textures).
Report exportReport(const ExportArgs& a, bool folder) {
  Report r("export", a.json);
  if (folder) r.checkOutsideFolder({"-o", a.output});
  r.check({{"-o", a.output}}, {{"input", a.input}});
  r.input(a.input);
  r["format"] = a.format;
  return r;
}

/// The one transfer to export: --mode's (a vector before a matrix), else the only one.
const BakedTransfer& exportedTransfer(const BakeFile& bake, const ExportArgs& a) {
  if (bake.transfers.empty()) throw Error(a.input, "holds no transfer");
  if (!a.mode.empty()) {
    const TransferMode m = parseTransferMode(a.mode);
    const BakedTransfer* t = bake.find(m, TransferLayout::Vector);
    if (!t) t = bake.find(m);
    if (!t) throw Error(a.input, "holds no " + a.mode + " transfer");
    return *t;
  }
  if (bake.transfers.size() == 1) return bake.transfers[0];
  std::string list;
  for (const auto& x : bake.transfers) list += std::string(list.empty() ? "" : ", ") + x.describe();
  throw Error(a.input, "holds several transfers (" + list + "): choose one with --mode");
}

/// --format exr | png: per-texel transfer as coefficient textures and transfer.json, in a
/// folder written as a whole (replacing only an earlier export).
void runExportTextures(const ExportArgs& a) {
  const io::TextureEncoding encoding = io::parseTextureEncoding(a.format);
  if (a.layout != "faces" || !a.channel.empty())
    throw Error(
        "--layout and --channel shape transport.txt (--format games202); coefficient "
        "textures keep every coefficient and colour");
  if (isStandardOutput(a.output))
    throw Error("-o: coefficient textures are a folder, not a stream");
  checkOutputs({{"-o", a.output}}, {{"input", a.input}});
  Report report = exportReport(a, true);
  const BakeFile bake = readBake(a.input);
  bake.requireComplete(a.input);
  bake.requireSurface(a.input, "coefficient textures lay out a surface's transfer");
  const BakedTransfer& t = exportedTransfer(bake, a);
  const io::CoefficientTextures tex =
      io::encodeCoefficientTextures(t, bake.mesh, encoding, a.input);
  FolderOutput folder(a.output, "prt export");
  for (const auto& [name, bytes] : tex.files) folder.write(name, bytes);
  folder.commit();
  const Json written = folderJson(a.output);
  report.outputFolder(written);
  report["folder"] = written;
  report["transfer"] = transferJson(t);
  // The encoding as transfer.json states it: per texture, which value each channel holds
  // (and, 16-bit, the offset and scale that decode it).
  report["encoding"] = tex.manifest.at("encoding").get<std::string>();
  report["maxQuantisationError"] = tex.maxQuantisationError;
  report["lightmap"] = Json(tex.manifest.at("lightmap"));
  report["textures"] = Json(tex.manifest.at("textures"));
  const TransferShape::LightmapSize lm = t.transfer.shape().lightmap;
  info(fmt::format(
      "wrote {} ({} {} textures of {}x{} for the {} transfer, {} bands x {} "
      "channel(s), and transfer.json{})",
      a.output, tex.files.size() - 1, a.format, lm.width, lm.height, toString(t.mode()),
      t.transfer.bands(), t.transfer.channels(),
      encoding == io::TextureEncoding::Unorm16Png
          ? fmt::format("; 16-bit quantisation error at most {:.3g}", tex.maxQuantisationError)
          : std::string()));
  report.write();
}

void runExport(const ExportArgs& a) {
  if (a.format == "exr" || a.format == "png") {
    runExportTextures(a);
    return;
  }
  if (a.format != "games202")
    throw Error("--format " + a.format + ": unknown (expected games202, exr or png)");
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
  Report report = exportReport(a, false);

  const BakeFile bake = readBake(a.input);
  bake.requireComplete(a.input);
  bake.requireVertices(a.input,
                       "transport.txt holds vertices: export it as coefficient "
                       "textures (--format exr or png)");
  // A vector of the mode before a matrix: transport.txt holds vectors.
  const BakedTransfer* t = &exportedTransfer(bake, a);
  // transport.txt holds diffuse vectors: a compressed transfer exports its reconstruction, a
  // matrix its diffuse part t = Mᵀd(n) (what a diffuse surface relights with; never a row of M).
  Transfer field = t->transfer.toDense();
  const bool diffusePart = field.isMatrix();
  if (diffusePart) {
    field = relight::diffuseTransfer(field, bake.mesh.normals);
    info(
        fmt::format("{}: the {} transfer holds matrices; exporting their diffuse part "
                    "(transfer = Mᵀ d(n), the clamped cosine about each normal)",
                    a.input, toString(t->mode())));
  }
  Json channelTaken = nullptr;  // the channel of an RGB transfer exported (--channel)
  if (field.channels() == 3) {
    if (!channel)
      throw Error(a.input,
                  std::string("the ") + toString(t->mode()) +
                      " transfer is RGB (coloured inter-reflection) and transport.txt holds one "
                      "value per coefficient: pick --channel luminance, r, g or b");
    field = selectChannel(field, *channel);
    channelTaken = a.channel;
  }
  if (field.bands() != 3)
    warn(fmt::format("{} bands: the course's shaders expect 3 bands (9 coefficients per line)",
                     field.bands()));
  writeGames202Transport(a.output, field, bake.mesh, layout);
  const std::size_t lines =
      layout == Games202Layout::Faces ? 3 * bake.mesh.triangleCount() : bake.mesh.vertexCount();
  info(fmt::format("wrote {} ({} transfer, {} bands, header {} vertices, {} lines)", a.output,
                   toString(t->mode()), field.bands(), bake.mesh.vertexCount(), lines));
  report.output(a.output);
  report["files"] = Json::array({fileJson(a.output)});
  report["transfer"] = transferJson(*t);
  // What was done to it on the way: a compressed transfer's reconstruction, a matrix's diffuse
  // part, an RGB transfer's one channel.
  report["games202"] = {{"layout", a.layout},
                        {"bands", field.bands()},
                        {"headerVertices", bake.mesh.vertexCount()},
                        {"lines", lines},
                        {"reconstructed", t->transfer.compressed()},
                        {"diffusePart", diffusePart},
                        {"channel", channelTaken}};
  report.write();
}

}  // namespace

void addExportCommand(CLI::App& root) {
  auto args = std::make_shared<ExportArgs>();
  auto* cmd = root.add_subcommand(
      "export",
      "Export a bake file to another format (GAMES202 transport.txt; coefficient textures of "
      "per-texel transfer)");
  cmd->add_option("input", args->input, "Bake file (.glb)")->required();
  cmd->add_option("--format", args->format,
                  "games202 (transport.txt) | exr (per-texel: float coefficient textures) | png "
                  "(per-texel: 16-bit, scale and offset in transfer.json)")
      ->capture_default_str();
  cmd->add_option("--mode", args->mode, "Which transfer, if the file holds several");
  cmd->add_option(
         "--layout", args->layout,
         "faces (the course's file: 3 lines per triangle) | vertices (one line per vertex)")
      ->capture_default_str();
  cmd->add_option("--channel", args->channel, "For RGB transfer: luminance | r | g | b");
  cmd->add_option("-o,--output", args->output,
                  "Output file (games202), or folder (exr, png: t0.., transfer.json)")
      ->required();
  addJsonOption(cmd, args->json);
  cmd->callback([args] { runExport(*args); });
}

}  // namespace prt::cli
