// prt validate: compare a bake's PRT relighting against the brute-force Monte Carlo reference,
// per band count (render/validate.hpp; docs/validation.md).
//
//   prt validate BAKE.glb --light ENV [--mode M] [--reference-samples N] [--bands-list 1,2,..]
//                [--rotate X,Y,Z] [--vertices N] [--seed S] [--mis power|balance] [--window W]
//                [--json REPORT.json] [--image error.png] [--image-size WxH]

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "mpi_verb.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/project.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/metrics.hpp"
#include "prt/render/probe_points.hpp"
#include "prt/render/render.hpp"
#include "prt/render/validate.hpp"
#include "prt/render/validate_haar.hpp"
#include "prt/sh/irradiance_encoding.hpp"
#include "reference_input.hpp"
#include "report.hpp"
#include "transfer_options.hpp"

namespace prt::cli {

namespace {

/// --encoding: "" (none), "all" (every encoding), or names separated by commas.
std::vector<sh::IrradianceEncoding> parseEncodingList(const std::string& list) {
  std::vector<sh::IrradianceEncoding> out;
  if (list.empty()) return out;
  if (list == "all") return {sh::kIrradianceEncodings.begin(), sh::kIrradianceEncodings.end()};
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const sh::IrradianceEncoding e = sh::parseIrradianceEncoding(list.substr(start, comma - start));
    if (std::find(out.begin(), out.end(), e) != out.end())
      throw Error("--encoding names " + std::string(sh::toString(e)) + " twice");
    out.push_back(e);
    start = comma + 1;
  }
  return out;
}

struct ValidateArgs {
  std::string bake, light, json, image, imageSize = "640x480", mis = "power", window = "none";
  std::string encoding;  ///< --encoding: a list of names, or all
  std::string reference;  ///< --reference FILE: prt reference's JSON instead of computing it
  /// The reference options given on the command line (refused beside --reference: the file's).
  std::vector<std::string> referenceOptionsGiven;
  int samples = 1024;
  std::string bandsList, rotate, material;
  TransferChoice transfer;
  std::size_t vertices = 0;
  std::uint64_t seed = 0;
  std::string terms;  ///< --terms: a Haar bake's light budgets, comma-separated
};

/// A Haar bake (render/validate_haar.hpp): per light budget K, the relighting under the
/// environment's K largest wavelet terms against the reference, ending with the whole cube.
void validateHaarBake(const ValidateArgs& a, MpiVerb& mpi, const BakeFile& file,
                      const BakedTransfer& bt, const BakeRecipe& recipe, const Mat3d& rotation,
                      Report& report) {
  if (!a.bandsList.empty() || a.window != "none" || !a.encoding.empty() || !a.image.empty())
    throw Error(a.bake, "holds Haar transfer: --bands-list, --window, --encoding and --image "
                        "measure SH transfer (--terms lists the Haar light's budgets)");
  render::HaarValidateSettings hs;
  hs.lightTerms.clear();
  for (double k : parseNumberList(
           a.terms.empty() ? std::to_string(haar::kDefaultLightTerms) : a.terms, "--terms")) {
    if (k != std::floor(k) || k < 1 || k > 1e7)
      throw Error("--terms: light budgets are positive integers");
    hs.lightTerms.push_back(static_cast<std::size_t>(k));
  }
  hs.reference.samples = a.samples;
  hs.reference.seed = a.seed;
  hs.reference.rotation = rotation;
  hs.reference.heuristic = parseMis(a.mis);
  hs.maxVertices = a.vertices;
  hs.bakeName = a.bake;
  const envmap::LoadedEnvironment env = envmap::loadEnvironment(a.light);
  for (const std::string& w : envmap::repairWarnings(env)) warn(w);
  auto occluder = makeEmbreeOccluder(file.mesh);
  if (mpi.active())
    hs.runReference = [&](const render::ReferenceSettings& rs, const ProgressFn& p) {
      return mpi.reference(file.mesh, *occluder, env.env, rs, p);
    };
  render::ReferenceResult stored;
  if (!a.reference.empty()) {
    const io::ReferenceFile ref = readMatchingReference(
        a.reference, referenceScene(file.mesh, env.env, a.bake, a.light, rotation, bt,
                                    recipe.material, render::frameMesh(file.mesh, 640, 480).eye));
    stored = toReferenceResult(ref);
    hs.precomputed = &stored;
    hs.reference.samples = ref.samples;
  }
  info("validating " + bt.describe() + " transfer (" + bt.transfer.shape().describe() + ") of " +
       a.bake + " under " + a.light);
  const render::HaarValidationReport rep = render::validateHaar(
      file.mesh, *occluder, bt.transfer, recipe, env.env, hs, progressBar("reference"));
  if (!mpi.root()) return;
  for (const std::string& w : rep.warnings) warn(w);
  info(fmt::format("reference: {} vertices x {} samples, {} rays, {:.2f} s; mode {}",
                   rep.reference.vertices.size(), hs.reference.samples, rep.reference.rays,
                   rep.reference.seconds, toString(rep.mode)));
  (report.toStandardOutput() ? std::cerr : std::cout) << render::formatHaarTable(rep)
                                                      << std::flush;
  if (report.wanted()) {
    report.input(a.bake);
    report.input(a.light);
    if (!a.reference.empty()) report.input(a.reference);
    report["basis"] = "haar";
    report["resolution"] = rep.resolution;
    report["transferTerms"] = rep.transferTerms;
    report["vertices"] = rep.reference.vertices.size();
    report["refStdErr"] = rep.refStdErr;
    Json rows = Json::array();
    for (const render::HaarRow& r : rep.rows)
      rows.push_back({{"lightTerms", r.lightTerms},
                      {"energyKept", r.energyKept},
                      {"relRmse", r.relRmse},
                      {"energyWeightedRelErr", r.energyRel},
                      {"meanRel", r.meanRel},
                      {"maxRel", r.maxRel},
                      {"negativeShare", r.negativeShare}});
    report["rows"] = std::move(rows);
    report.write();
  }
}

void validateBody(const ValidateArgs& a, MpiVerb& mpi) {
  if (a.samples < 1) throw Error("--reference-samples must be at least 1");
  std::vector<int> bands;
  if (!a.bandsList.empty())
    for (double b : parseNumberList(a.bandsList, "--bands-list")) {
      if (b != static_cast<int>(b) || b < 1 || b > bands::kMaxLibrary)
        throw Error(
            fmt::format("--bands-list: band counts are integers in 1..{}", bands::kMaxLibrary));
      bands.push_back(static_cast<int>(b));
    }
  const Mat3d rotation = parseRotation(a.rotate);
  int iw = 0, ih = 0;
  if (!a.image.empty()) {
    parseSize(a.imageSize, iw, ih, "--image-size");
    if (fileExtension(a.image) != "png" && fileExtension(a.image) != "exr")
      throw Error(a.image, "--image must be .png or .exr");
    checkWritable(a.image);
  }
  refuseShLight(a.light, "validate");
  if (!a.reference.empty() && !a.referenceOptionsGiven.empty())
    throw Error(a.referenceOptionsGiven.front() +
                ": the reference file's setting is used with --reference (its samples, seed, "
                "vertices and MIS heuristic)");
  Report report("validate", a.json);
  const std::vector<NamedPath> inputs = {
      {"input", a.bake}, {"--light", a.light}, {"--reference", a.reference}};
  checkOutputs({{"--image", a.image}}, inputs);
  report.check({{"--image", a.image}}, inputs);

  // Mapped: validation reads the mesh and its validated rows alone (render::validate), so
  // nothing of the size of the transfer is read, checked or held.
  const BakeFile file = mapBake(a.bake);
  const BakedTransfer& bt = pickTransfer(file, a.transfer, a.bake);
  // The material: the bake's, or --material (keeping the bake's kd unless it names one).
  BakeRecipe recipe = bt.recipe;
  recipe.material = materialOption(a.material, bt, a.bake,
                                   "the reference's bounces follow --material, so the two "
                                   "differ by more than error");
  // A probe grid: each probe seen by six axis normals, white diffuse surfaces placed there
  // (render/probe_points.hpp); no lobe, no eye, no image of a surface.
  const bool probes = bt.transfer.domain() == TransferDomain::Probes;
  if (probes && !a.image.empty())
    throw Error(a.bake, "--image draws a surface's error; this file holds a probe grid (" +
                            bt.transfer.shape().probes.describe() + ")");
  if (probes && !a.reference.empty())
    throw Error(a.reference, "a probe grid is validated against a reference computed here (prt "
                             "reference integrates a surface's light)");
  if (bt.transfer.isMatrix() && !probes)
    warnLobeEnergyLoss(recipe.material, bt.transfer.bands(), a.bake);
  if (!probes)
    warnLobeOnVectors(recipe.material, bt, a.bake,
                      "validating its diffuse part (the reference drops the lobe, and its "
                      "bounces are diffuse too)");
  file.requireComplete(a.bake);
  if (bt.transfer.isHaar()) {
    validateHaarBake(a, mpi, file, bt, recipe, rotation, report);
    return;
  }
  if (!a.terms.empty())
    throw Error(a.bake, "--terms lists a Haar light's budgets; this bake holds " +
                            bt.describe() + " (SH) transfer");
  const envmap::LoadedEnvironment env = envmap::loadEnvironment(a.light);
  for (const std::string& w : envmap::repairWarnings(env)) warn(w);
  const sh::RgbSh light = envmap::projectEnvironment(env.env, bt.transfer.bands());
  auto occluder = makeEmbreeOccluder(file.mesh);
  // Per-texel transfer: the rows are the texels' sample points; a subset of the valid ones is
  // validated (--vertices counts texels then), their points placed by render::validate.
  render::ValidateSettings vs;
  vs.reference.samples = a.samples;
  vs.reference.seed = a.seed;
  vs.reference.rotation = rotation;
  vs.reference.heuristic = parseMis(a.mis);
  // Glossy: PRT and reference see each vertex from the eye of prt render's default camera.
  vs.reference.eye = render::frameMesh(file.mesh, 640, 480).eye;
  vs.bandsList = bands;
  vs.maxVertices = a.vertices;
  vs.window = parseWindow(a.window);
  vs.bakeName = a.bake;
  vs.encodings = parseEncodingList(a.encoding);
  info("validating " + bt.describe() + " transfer (" + std::to_string(bt.transfer.bands()) +
       " bands) of " + a.bake + " under " + a.light +
       (probes ? fmt::format(": at each probe, a white diffuse surface facing each of the {} "
                             "axes",
                             render::kProbeNormals)
               : std::string()));
  // A compressed transfer is validated as relit, in the compressed space (the compression's own
  // error against the uncompressed rows is reported from the file beside the truncation error).
  if (bt.transfer.compressed())
    info(
        fmt::format("compressed transfer: K {} N {}, relative RMS error {:.3e} against the "
                    "uncompressed transfer (SNR {:.2f} dB)",
                    bt.transfer.cpca().clusters, bt.transfer.cpca().basisCount,
                    bt.compression.stats.relativeRms, bt.compression.stats.snrDb));
  if (mpi.active())
    vs.runReference = [&](const render::ReferenceSettings& rs, const ProgressFn& p) {
      return mpi.reference(file.mesh, *occluder, env.env, rs, p);
    };
  // --reference: the file's estimates, if they are of this scene (the reference drops the lobe
  // of a vector bake's material, as validate does).
  render::ReferenceResult stored;
  if (!a.reference.empty()) {
    const io::ReferenceFile ref = readMatchingReference(
        a.reference, referenceScene(file.mesh, env.env, a.bake, a.light, rotation, bt,
                                    recipe.material, *vs.reference.eye));
    stored = toReferenceResult(ref);
    vs.precomputed = &stored;
    vs.reference.samples = ref.samples;
    vs.reference.seed = ref.seed;
    vs.reference.heuristic = parseMis(ref.mis);
    info(fmt::format("reference from {}: {} {} x {} samples", a.reference, ref.vertices.size(),
                     toString(bt.transfer.domain()), ref.samples));
  }
  const render::ValidationReport rep = render::validate(
      file.mesh, *occluder, bt.transfer, recipe, env.env, light, vs, progressBar("reference"));
  if (!mpi.root()) return;
  for (const std::string& w : rep.warnings) warn(w);
  char line[200];
  info(fmt::format("reference: {} x {} samples, {} rays{}; mode {}, {} bounce(s)",
                   probes ? fmt::format("{} probes x {} normals",
                                        rep.reference.vertices.size() / render::kProbeNormals,
                                        render::kProbeNormals)
                          : fmt::format("{} {}", rep.reference.vertices.size(),
                                        toString(bt.transfer.domain())),
                   vs.reference.samples, rep.reference.rays,
                   a.reference.empty() ? fmt::format(", {:.2f} s", rep.reference.seconds)
                                       : " (from " + a.reference + ")",
                   toString(rep.mode), rep.bounces));
  std::snprintf(line, sizeof line,
                "truncation floor: %s from the reference's samples, %zu %s x %d samples, "
                "%llu rays, %.2f s",
                rep.floorMethod.c_str(), rep.floorVertices,
                probes ? "probe normals" : "vertices", vs.reference.samples,
                static_cast<unsigned long long>(rep.floorRays), rep.floorSeconds);
  info(line);
  // The table on standard output, unless the report is (--json -): then on stderr.
  (report.toStandardOutput() ? std::cerr : std::cout) << render::formatTable(rep) << std::flush;
  for (const render::BandRow& r : rep.rows)
    if (r.negativeShare > render::kNegativeShareWarning)
      warn(
          fmt::format("{} bands: {:.1f}% of {} validated {} relight to negative radiance "
                      "(SH ringing); {}",
                      r.bands, 100 * r.negativeShare, rep.negativeVertices,
                      probes ? "probe normals"
                      : bt.transfer.layout() == TransferLayout::Matrix
                          ? "vertices facing the eye"
                          : "vertices",
                      a.window == "none" ? "window the light: --window hanning|lanczos|dering "
                                           "(prt light --window for light files)"
                                         : "the light is windowed (" + a.window +
                                               "): the rest rings in the transfer and the "
                                               "lobe, which more bands hold"));

  if (!a.image.empty()) {
    // The relative error at the largest band count through the false-colour ramp, scaled to
    // its 99th percentile: per vertex on the mesh, per texel the lightmap itself.
    float scale = 1.0f;
    const image::Image img = render::errorImage(file.mesh, *occluder, bt.transfer, rep, iw, ih,
                                                &scale, progressBar("error image"));
    image::WriteOptions wo;
    wo.toneMap = image::ToneMap::Clamp;
    image::writeImage(a.image, img, wo);
    info(
        fmt::format("error image {}: relative error per validated {} at {} bands, black 0% .. "
                    "white {:.2f}%",
                    a.image, rowName(bt.transfer.domain()), rep.rows.back().bands, 100.0 * scale));
  }
  if (report.wanted()) {
    report.input(a.bake);
    report.input(a.light);
    if (!a.reference.empty()) report.input(a.reference);
    if (!a.image.empty()) report.output(a.image);
    // The members of render::reportJson (the table with its settings and timings), after ours.
    const Json table = Json::parse(render::reportJson(rep));
    for (const auto& [key, value] : table.items()) report[key.c_str()] = value;
    report.write();
  }
}

void runValidate(const ValidateArgs& a) {
  MpiVerb mpi("prt validate");
  mpi.run([&] { validateBody(a, mpi); });
}

}  // namespace

void addValidateCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "validate",
      "Compare PRT relighting with a brute-force Monte Carlo reference, per band count");
  auto a = std::make_shared<ValidateArgs>();
  cmd->add_option("bake", a->bake, "Bake file (.glb)")->required();
  cmd->add_option("--light", a->light, "Environment: image, face folder or builtin:NAME")
      ->required();
  addTransferChoice(cmd, a->transfer, "to validate");
  addMaterialOption(cmd, a->material,
                    "for both PRT and the reference (glossy surfaces are seen from the eye of "
                    "prt render's default camera)");
  cmd->add_option("--reference", a->reference,
                  "Read the reference from prt reference's .json (computed for this bake, light "
                  "and --rotate) instead of computing it");
  cmd->add_option("--reference-samples", a->samples, "Reference samples per vertex")
      ->check(intRange(1, 1 << 24))
      ->capture_default_str();
  cmd->add_option("--bands-list", a->bandsList,
                  "Band counts to tabulate, e.g. 1,2,3 (default 1..B)");
  cmd->add_option("--rotate", a->rotate, "Rotate the environment: Euler X,Y,Z degrees");
  cmd->add_option("--vertices", a->vertices,
                  "Validate a deterministic random subset of N vertices (0: all); of a per-texel "
                  "bake, N of its valid texels; of a probe grid, N probes outside geometry "
                  "(six normals each)")
      ->check(unsignedInt(UINT32_MAX));
  cmd->add_option("--seed", a->seed, "Reference seed")->check(unsignedInt())->capture_default_str();
  cmd->add_option("--mis", a->mis, "MIS heuristic: power | balance")->capture_default_str();
  cmd->add_option("--terms", a->terms,
                  "A Haar bake: the light's wavelet budgets to tabulate, e.g. 50,200,1000 "
                  "(default 200; the whole cube is always added)");
  cmd->add_option("--encoding", a->encoding,
                  "Also measure irradiance encodings of a matrix bake (comma-separated names, or "
                  "all): the diffuse shading an engine gets from each against the reference and "
                  "the bake's own relighting");
  cmd->add_option("--window", a->window,
                  "Window the light against ringing at each band count: none | hanning | "
                  "lanczos | dering")
      ->capture_default_str();
  addJsonOption(cmd, a->json);
  cmd->add_option("--image", a->image,
                  "Write a false-colour per-vertex error image (.png/.exr); of a per-texel bake, "
                  "the error per texel in the lightmap (UV space)");
  cmd->add_option("--image-size", a->imageSize, "Error image size WxH")->capture_default_str();
  cmd->callback([a, cmd] {
    a->referenceOptionsGiven.clear();
    for (const char* name : {"--reference-samples", "--vertices", "--seed", "--mis"})
      if (cmd->count(name) > 0) a->referenceOptionsGiven.push_back(name);
    runValidate(*a);
  });
}

}  // namespace prt::cli
