// prt export: a bake file → other formats.
//
//   prt export bunny.glb --format games202 -o transport.txt      (the course's transport.txt)
//   prt export box.glb --format exr -o box-textures              (per-texel transfer: float
//                                                                 coefficient textures + JSON)
//   prt export box.glb --format png -o box-textures              (16-bit, scale and offset in
//                                                                 the JSON)
//   prt export bunny.glb -o transport.txt --json export.json      (what it wrote, as JSON)
//   prt export box.glb --format lightmap --light builtin:sky -o lm    (per-texel bake relit:
//                                                                 E/π per texel, RGB EXR)
//   prt export boxm.glb --format lightmap-sh --encoding l1 -o lm      (a per-texel matrix bake
//                                                                 relit: irradiance SH in
//                                                                 Godot's and Bakery's layouts)

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "args.hpp"
#include "cli.hpp"
#include "export_probes.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/engine_lightmaps.hpp"
#include "prt/io/games202_transport.hpp"
#include "prt/io/lighting.hpp"
#include "prt/io/lightmap_gltf.hpp"
#include "prt/io/lightmap_textures.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/incident_light.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/view_transfer.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/sh/irradiance_encoding.hpp"
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
  // --format lightmap | lightmap-sh: the light the bake is relit under, and how it is written.
  std::string light;     ///< "" = builtin:sky
  std::string rotate;    ///< X,Y,Z degrees
  std::string exposure;  ///< stops ("" = 0)
  std::string encoding;  ///< lightmap-sh: "" = l1
  std::string engine;    ///< lightmap-sh: "" = godot,bakery
};

bool isLightmapFormat(const std::string& f) {
  return f == "lightmap" || f == "lightmap-sh";
}

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
  bake.requireSh(a.input, "prt export writes SH coefficients");
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

/// --format lightmap-sh reads the light arriving at each texel: a matrix transfer (--mode's, or
/// the only one).
const BakedTransfer& matrixTransfer(const BakeFile& bake, const ExportArgs& a) {
  const char* why =
      "--format lightmap-sh needs the light arriving at each texel, which a matrix bake holds "
      "(prt bake --transfer matrix); vector (diffuse) transfer has already integrated it "
      "against the normal";
  if (!a.mode.empty()) {
    const BakedTransfer* t = bake.find(parseTransferMode(a.mode), TransferLayout::Matrix);
    if (!t) throw Error(a.input, "holds no " + a.mode + " matrix transfer: " + why);
    return *t;
  }
  const BakedTransfer* found = nullptr;
  std::string list;
  for (const auto& x : bake.transfers)
    if (x.transfer.isMatrix()) {
      list += std::string(list.empty() ? "" : ", ") + x.describe();
      if (found)
        throw Error(a.input,
                    "holds several matrix transfers (" + list + "...): choose one with --mode");
      found = &x;
    }
  if (!found) throw Error(a.input, std::string("holds no matrix transfer: ") + why);
  return *found;
}

/// The layers' names, comma-separated.
std::string layerNames(const io::LightmapLayers& layers) {
  std::string list;
  for (const io::LightmapLayer& l : layers.layers)
    list += std::string(list.empty() ? "" : ", ") + l.name;
  return list;
}

/// -o NAME.glb of --format lightmap | lightmap-sh: the mesh and PRTKIT_lightmap, one file
/// (io/lightmap_gltf.hpp); the report names it and its layers.
void writeLightmapGltfFile(const ExportArgs& a, const io::LightmapLayers& layers,
                           const Mesh& mesh, Report& report) {
  io::writeLightmapGltf(a.output, layers, mesh);
  report.output(a.output);
  report["lightmap"] = Json(layers.manifest.at("lightmap"));
  Json names = Json::array();
  for (const io::LightmapLayer& l : layers.layers) names.push_back(l.name);
  report["layers"] = std::move(names);
}

/// --format lightmap | lightmap-sh: a per-texel bake relit under --light (rotated by --rotate,
/// scaled by 2^--exposure), written as the textures engines' lightmap shaders sample
/// (io/engine_lightmaps.hpp; docs/lightmaps.md), in a folder written as a whole.
void runExportLightmap(const ExportArgs& a) {
  const bool sh = a.format == "lightmap-sh";
  // Everything cheap first, so a mistake costs nothing and writes nothing.
  if (a.layout != "faces" || !a.channel.empty())
    throw Error("--layout and --channel shape transport.txt (--format games202), not a lightmap");
  if (!sh && !a.encoding.empty())
    throw Error(
        "--encoding picks the SH form of --format lightmap-sh; --format lightmap writes "
        "plain RGB");
  if (!sh && !a.engine.empty())
    throw Error(
        "--engine picks the layouts of --format lightmap-sh; --format lightmap writes "
        "one RGB lightmap every engine reads");
  const sh::IrradianceEncoding encoding =
      sh::parseIrradianceEncoding(a.encoding.empty() ? "l1" : a.encoding);
  // -o NAME.glb: one glTF file (the mesh and PRTKIT_lightmap's unpacked layers), else a folder
  // of engines' textures.
  const bool gltf = fileExtension(a.output) == "glb";
  if (gltf && !a.engine.empty())
    throw Error(
        "--engine picks the engines' packed layouts of a lightmap folder; -o " + a.output +
        " (glTF) keeps the encoding's own numbers, unpacked (PRTKIT_lightmap)");
  const std::vector<io::LightmapEngine> engines =
      io::parseLightmapEngines(a.engine.empty() ? "godot,bakery" : a.engine);
  const std::array<double, 3> euler = parseEulerDegrees(a.rotate);
  const Mat3d rotation = parseRotation(a.rotate);
  const double stops = a.exposure.empty() ? 0.0 : std::stod(a.exposure);
  const std::string lightSpec = a.light.empty() ? "builtin:sky" : a.light;
  if (isStandardOutput(a.output))
    throw Error("-o: an engine lightmap is a folder or a .glb file, not a stream");
  const std::vector<NamedPath> inputs = {{"input", a.input}, {"--light", lightSpec}};
  checkOutputs({{"-o", a.output}}, inputs);
  if (gltf) checkWritable(a.output);
  Report report = exportReport(a, !gltf);
  report.check({{"-o", a.output}}, inputs);

  const BakeFile bake = readBake(a.input);
  bake.requireComplete(a.input);
  bake.requireSurface(a.input, "engine lightmaps lay out a surface's light");
  bake.requireSh(a.input, "prt export writes SH coefficients");
  if (bake.domain() != TransferDomain::Texels)
    throw Error(a.input,
                "holds per-vertex transfer: engine lightmaps are per texel (prt bake "
                "--domain texels)");
  const BakedTransfer& t = sh ? matrixTransfer(bake, a) : exportedTransfer(bake, a);
  const TransferShape::LightmapSize lm = t.transfer.shape().lightmap;

  const io::Lighting lighting =
      io::loadLighting(lightSpec, t.transfer.bands(), progressBar("projecting"));
  for (const std::string& w : lighting.warnings) warn(w);
  relight::RelightInfo relit;
  io::LightmapDescription d;
  d.source = a.input;
  d.lightmap = lm;
  d.exposureStops = stops;
  io::EngineLightmaps out;
  io::LightmapLayers layers;
  if (sh) {
    const int bands = std::min(3, t.transfer.bands());
    const std::vector<Rgb> incident =
        relight::incidentLight(t.transfer, lighting.coefficients, bands, rotation, &relit);
    d.light = {{"spec", lightSpec}, {"bands", relit.bands}, {"rotateDegrees", euler}};
    d.transfer = {{"mode", toString(t.mode())},
                  {"layout", toString(t.transfer.layout())},
                  {"bands", t.transfer.bands()},
                  {"relit", "L'_p = M_p L: the SH of the light arriving at each texel"}};
    if (gltf)
      layers = io::irradianceLayers(incident, bands, encoding, bake.mesh, d);
    else
      out = io::encodeIrradianceLightmaps(incident, bands, encoding, engines, bake.mesh, d);
  } else {
    // f = E(n_p)/π: a vector's Σ T_i L_i (relit white), or a matrix's diffuse part d(n_p)·L'_p
    // at each texel's normal (as the bake placed its samples: render/texel_points.hpp).
    Transfer field = t.transfer.toDense();
    if (field.isMatrix()) {
      const auto occluder = makeEmbreeOccluder(bake.mesh);
      const render::RowPoints points = render::texelRowPoints(bake.mesh, *occluder, lm, false);
      field = relight::diffuseTransfer(field, points.normals);
    }
    const std::vector<Rgb> radiance =
        relight::relight(field, lighting.coefficients, Material{}, relight::Surface{}, Vec3f(0.0f),
                         rotation, &relit);
    d.light = {{"spec", lightSpec}, {"bands", relit.bands}, {"rotateDegrees", euler}};
    d.transfer = {{"mode", toString(t.mode())},
                  {"layout", toString(t.transfer.layout())},
                  {"bands", t.transfer.bands()},
                  {"relit", t.transfer.isMatrix()
                                ? "the diffuse part d(n_p).(M_p L) at each texel's normal"
                                : "sum_i T_i L_i, white (the albedo at the texel left out)"}};
    if (gltf)
      layers = io::radianceLayers(radiance, bake.mesh, d);
    else
      out = io::encodeRadianceLightmap(radiance, bake.mesh, d);
  }
  if (!relit.warning().empty()) warn(a.input + ": " + relit.warning());
  if (gltf) {
    writeLightmapGltfFile(a, layers, bake.mesh, report);
    info(fmt::format("wrote {} ({}x{} texels: {} of the {} transfer under {}{}: layers {})",
                     a.output, lm.width, lm.height,
                     sh ? std::string(sh::toString(encoding)) + " irradiance SH"
                        : std::string("E/pi (RGB)"),
                     t.describe(), lightSpec,
                     stops != 0 ? fmt::format(", exposure {:+g} stops", stops) : std::string(),
                     layerNames(layers)));
    report["transfer"] = transferJson(t);
    report["light"] = Json(d.light);
    report["exposureStops"] = stops;
    if (sh) report["encoding"] = sh::toString(encoding);
    report.write();
    return;
  }
  if (out.clampedTexels > 0)
    warn(
        fmt::format("{}: {} of {} texels hold more band-1 light than an engine's packed L1 "
                    "can (|L1| > 2 L0 for bakery, 4 L0 for godot, or L0 <= 0: a light that "
                    "rings below zero at {} bands, or Monte Carlo noise); their L1 is scaled "
                    "down to fit, its direction kept (lightmap.json: clampedTexels)",
                    a.input, out.clampedTexels, lm.texels(), relit.bands));
  FolderOutput folder(a.output, "prt export");
  for (const auto& [name, bytes] : out.files) folder.write(name, bytes);
  folder.commit();
  const Json written = folderJson(a.output);
  report.input(lightSpec);
  report.outputFolder(written);
  report["folder"] = written;
  report["transfer"] = transferJson(t);
  report["light"] = Json(d.light);
  report["exposureStops"] = stops;
  report["lightmap"] = Json(out.manifest.at("lightmap"));
  report["manifest"] = Json(out.manifest.at("files"));
  if (sh) {
    report["encoding"] = sh::toString(encoding);
    Json names = Json::array();
    for (const io::LightmapEngine e : engines) names.push_back(io::toString(e));
    report["engines"] = std::move(names);
    report["clampedTexels"] = Json(out.manifest.at("clampedTexels"));
  }
  std::string list;
  for (const auto& f : out.files) list += std::string(list.empty() ? "" : ", ") + f.first;
  info(fmt::format(
      "wrote {} ({}x{} texels: {} of the {} transfer under {}{}: {})", a.output, lm.width,
      lm.height,
      sh ? std::string(sh::toString(encoding)) + " irradiance SH" : std::string("E/pi (RGB)"),
      t.describe(), lightSpec,
      stops != 0 ? fmt::format(", exposure {:+g} stops", stops) : std::string(), list));
  report.write();
}

void runExport(const ExportArgs& a) {
  if (a.format == "probe-grid") {
    if (a.layout != "faces" || !a.channel.empty() || !a.encoding.empty())
      throw Error(
          "--layout, --channel and --encoding shape a surface's export; --format probe-grid "
          "writes each probe's SH in --engine's convention");
    exportProbeGrid({a.input, a.output, a.json, a.mode, a.light, a.rotate, a.exposure, a.engine});
    return;
  }
  if (!isLightmapFormat(a.format) &&
      (!a.light.empty() || !a.rotate.empty() || !a.exposure.empty() || !a.encoding.empty() ||
       !a.engine.empty()))
    throw Error(
        "--light, --rotate, --exposure, --encoding and --engine relight a lightmap "
        "(--format lightmap or lightmap-sh) or a probe grid (--format probe-grid)");
  if (isLightmapFormat(a.format)) {
    runExportLightmap(a);
    return;
  }
  if (a.format == "exr" || a.format == "png") {
    runExportTextures(a);
    return;
  }
  if (a.format != "games202")
    throw Error("--format " + a.format +
                ": unknown (expected games202, exr, png, lightmap, lightmap-sh or probe-grid)");
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
  bake.requireSh(a.input, "prt export writes SH coefficients");
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
      "per-texel transfer; relit lightmaps for engines)");
  cmd->add_option("input", args->input, "Bake file (.glb)")->required();
  cmd->add_option("--format", args->format,
                  "games202 (transport.txt) | exr (per-texel: float coefficient textures) | png "
                  "(per-texel: 16-bit, scale and offset in transfer.json) | lightmap (per-texel, "
                  "relit under --light: E/pi per texel, float EXR + PNG preview) | lightmap-sh "
                  "(per-texel matrix bake relit under --light: irradiance SH per texel in "
                  "engines' layouts, --encoding, --engine; docs/lightmaps.md) | probe-grid "
                  "(a probe bake relit under --light: each probe's SH as --engine reads it, "
                  ".json, .glb or .exr volume; docs/probes.md)")
      ->capture_default_str();
  cmd->add_option("--mode", args->mode, "Which transfer, if the file holds several");
  cmd->add_option(
         "--layout", args->layout,
         "faces (the course's file: 3 lines per triangle) | vertices (one line per vertex)")
      ->capture_default_str();
  cmd->add_option("--channel", args->channel, "For RGB transfer: luminance | r | g | b");
  cmd->add_option("-o,--output", args->output,
                  "Output file (games202), or folder (exr, png: t0.., transfer.json; lightmap, "
                  "lightmap-sh: textures and lightmap.json, or NAME.glb: the mesh and the "
                  "PRTKIT_lightmap extension)")
      ->required();
  cmd->add_option("--light", args->light,
                  "lightmap, lightmap-sh, probe-grid: environment image, face folder, builtin:NAME, or SH "
                  "light (.json/.txt) to relight under (default builtin:sky)");
  cmd->add_option("--rotate", args->rotate,
                  "lightmap, lightmap-sh, probe-grid: rotate the environment: X,Y,Z degrees (X, then Y, then "
                  "Z)");
  cmd->add_option("--exposure", args->exposure,
                  "lightmap, lightmap-sh, probe-grid: scale every value by 2^STOPS (default 0: the light's "
                  "own units)")
      ->check(exposureStops());
  cmd->add_option("--encoding", args->encoding,
                  "lightmap-sh: l1 | l1-windowed | l1-geomerics | zh3 | zh3-shared | zh3-optimal | "
                  "zh3-hallucinated | l2 | l2-deringed (default l1; docs/formats-light.md)");
  cmd->add_option("--engine", args->engine,
                  "lightmap-sh: the L1 layouts to write, comma-separated: godot (4.4+), "
                  "godot-4.3 (4.0-4.3), bakery (Unity) (default godot,bakery); probe-grid: "
                  "threejs | unity | gltf-ibl | prtkit (default threejs)");
  addJsonOption(cmd, args->json);
  cmd->callback([args] { runExport(*args); });
}

}  // namespace prt::cli
