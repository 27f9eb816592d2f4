// prt light: an environment (image, cube-face folder or builtin:NAME) → SH lighting coefficients.
//
//   prt light studio.exr --bands 3 -o studio.json --preview studio.png
//   prt light Skybox/ --compat games202 --format games202 -o light.txt
//
// Everything is validated before any file is written; outputs are written atomically.

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/options.hpp"
#include "prt/core/version.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/preview.hpp"
#include "prt/envmap/project.hpp"
#include "prt/haar/cube_haar.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/engine_light.hpp"
#include "prt/io/haar_light_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/sh/rotate.hpp"
#include "report.hpp"

namespace prt::cli {

namespace {

constexpr const char* kLightFormats = "json|games202|threejs|gltf-ibl|cmgen|unity";

struct LightOptions {
  std::string input = envmap::kDefaultEnvironment;
  std::string output;
  std::string layout;
  int bands = 3;
  std::string window = "none";
  std::string rotate;
  std::string compat;
  std::string format;
  std::string preview;
  int previewWidth = 512;
  std::optional<float> exposure;
  std::string toneMap = "aces";
  bool strict = false;
  std::string encoding;
  std::string json;
  // --basis haar (issue 33): the environment's largest wavelet terms over a cube map.
  std::string basis = "sh";
  int resolution = 0;  ///< 0: not given (32)
  int terms = 0;       ///< 0: not given (200)
  std::string selection = "area";
};

/// The repairs that changed the light are warned (envmap::repairWarnings); --strict refuses any.
void warnAboutPixels(const envmap::LoadedEnvironment& loaded, bool strict) {
  if (strict && envmap::anyPixelRepaired(loaded)) {
    for (std::size_t i = 0; i < loaded.files.size(); ++i) {
      const image::ReadStats& s = loaded.stats[i];
      if (s.nonFinitePixels + s.negativePixels)
        throw Error(loaded.files[i],
                    fmt::format("{} pixels with NaN/Inf and {} with negative values (--strict)",
                                s.nonFinitePixels, s.negativePixels));
    }
  }
  for (const std::string& w : envmap::repairWarnings(loaded)) warn(w);
}

/// prt light --basis haar: the cube's texel means, the K terms kept by --selection, and the SH
/// of the unshadowed part, into a Haar light file (io/haar_light_file.hpp).
void runHaarLight(const LightOptions& o) {
  if (o.bands != 3 || o.window != "none" || !o.compat.empty() || !o.encoding.empty() ||
      !o.preview.empty())
    throw Error("--basis haar: --bands, --window, --compat, --encoding and --preview shape an "
                "SH light (--resolution and --terms shape a Haar one)");
  const int n = o.resolution ? o.resolution : 32;
  haar::checkResolution(n, "--resolution");
  // Not given: 200 (Ng et al.'s "a few hundred"), or the whole of a smaller cube.
  const std::size_t terms =
      o.terms ? std::size_t(o.terms) : std::min<std::size_t>(200, haar::coefficientCount(n));
  if (terms > haar::coefficientCount(n))
    throw Error(fmt::format("--terms {}: a {}² cube has {} coefficients", terms, n,
                            haar::coefficientCount(n)));
  const haar::Selection selection = haar::parseSelection(o.selection);
  if (!o.format.empty() && o.format != "json")
    throw Error("--basis haar writes prtkit's JSON light file (--format json)");
  checkOutputs({{"-o", o.output}}, {{"input", o.input}});
  if (!isStandardOutput(o.output) && fileExtension(o.output) != "json")
    throw Error(o.output, "--basis haar writes a .json light file");
  Report report("light", o.json);
  report.check({{"-o", o.output}}, {{"input", o.input}});
  checkWritable(o.output);
  const std::array<double, 3> rot = parseEulerDegrees(o.rotate);
  envmap::LoadOptions lo;
  if (!o.layout.empty()) lo.layout = envmap::parseLayout(o.layout);
  const envmap::LoadedEnvironment loaded = envmap::loadEnvironment(o.input, lo);
  warnAboutPixels(loaded, o.strict);
  std::vector<NamedPath> read;
  for (const std::string& f : loaded.files) read.push_back({"input", f});
  checkOutputs({{"-o", o.output}}, read);
  io::HaarLightFile f;
  f.light = haar::projectLight(loaded.env, n, terms, rotationEulerXYZ(rot[0], rot[1], rot[2]),
                               selection);
  for (const Rgb& v : f.light.value)
    if (!isFinite(v))
      throw Error(o.input, "a wavelet coefficient is not finite: the environment is too bright "
                           "for 32-bit floats (scale it down); nothing written");
  f.selection = haar::toString(selection);
  f.source = o.input;
  f.layout = loaded.layout;
  f.rotationDeg = rot;
  f.prtkitVersion = kVersion;
  io::writeHaarLightJson(o.output, f);
  info(fmt::format("wrote {}: Haar {}² cube, the {} largest ({}) of {} terms, {:.4f}% of the "
                   "light's energy",
                   o.output, n, f.light.terms(), f.selection, haar::coefficientCount(n),
                   100 * f.light.energyKept));
  if (report.wanted()) {
    report.input(o.input);
    report.output(o.output);
    report["basis"] = "haar";
    report["resolution"] = n;
    report["terms"] = f.light.terms();
    report["selection"] = f.selection;
    report["energyKept"] = f.light.energyKept;
    report["rotationDegrees"] = rot;
    report.write();
  }
}

void runLight(const LightOptions& o) {
  if (o.basis == "haar") return runHaarLight(o);
  if (o.basis != "sh") throw Error("--basis must be sh or haar, got '" + o.basis + "'");
  if (o.resolution || o.terms || o.selection != "area")
    throw Error("--resolution, --terms and --selection shape a Haar light: add --basis haar");
  // Validate everything first: nothing is written unless all of it works.
  checkOptionRange(OptionSpelling::Cli, "bands", o.bands, 1, bands::kMaxLibrary);
  if (o.previewWidth < 8 || o.previewWidth % 2)
    throw Error("--preview-width must be an even number >= 8");
  const bool compat = o.compat == "games202";
  if (!o.compat.empty() && !compat)
    throw Error("--compat accepts only 'games202', got '" + o.compat + "'");
  checkOutputs({{"-o", o.output}, {"--preview", o.preview}}, {{"input", o.input}});
  // The format: --format, else by extension (.json ours, .txt the course's); an engine's format
  // only when asked for. The extension must be the format's, so no file claims to be what it
  // is not.
  const std::string ext = fileExtension(o.output);
  if (o.format.empty() && !isStandardOutput(o.output) && ext != "json" && ext != "txt")
    throw Error(o.output, "unknown light file extension '." + ext +
                              "': use .json or .txt (GAMES202), or --format " + kLightFormats);
  const std::string format = !o.format.empty() ? o.format : ext == "txt" ? "games202" : "json";
  std::optional<io::EngineLight> engine;
  if (format != "json" && format != "games202") {
    try {
      engine = io::parseEngineLight(format);
    } catch (const Error&) {
      throw Error("--format must be one of " + std::string(kLightFormats) + ", got '" + format +
                  "'");
    }
  }
  const std::string wantExt = engine                 ? io::engineLightExtension(*engine)
                              : format == "games202" ? "txt"
                                                     : "json";
  // gltf-ibl writes a whole glTF asset: .gltf as well as .json.
  const bool gltfToo = engine == io::EngineLight::GltfIbl && ext == "gltf";
  if (!isStandardOutput(o.output) && ext != wantExt && !gltfToo)
    throw Error(o.output, "--format " + format + " writes a ." + wantExt +
                              (engine == io::EngineLight::GltfIbl ? " or .gltf" : "") + " file");
  const std::array<double, 3> rot = parseEulerDegrees(o.rotate);
  const sh::Window window = parseWindow(o.window);
  const image::ToneMap tone = image::parseToneMap(o.toneMap);
  std::optional<sh::IrradianceEncoding> encoding;
  if (!o.encoding.empty()) {
    try {
      encoding = sh::parseIrradianceEncoding(o.encoding);
    } catch (const Error& e) {
      throw Error(std::string("--") + e.what());
    }
    if (format != "json")
      throw Error("--encoding writes the irradiance into prtkit's JSON light file; --format " +
                  format + " has no place for it");
    if (o.bands < 3 && sh::storedNumbers(*encoding) != 12)
      throw Error(std::string("--encoding ") + sh::toString(*encoding) +
                  " keeps band 2 of the light: use --bands 3 or more");
  }
  Report report("light", o.json);
  report.check({{"-o", o.output}, {"--preview", o.preview}}, {{"input", o.input}});
  checkWritable(o.output);
  if (!o.preview.empty()) {
    checkWritable(o.preview);
    if (fileExtension(o.preview) != "png" && fileExtension(o.preview) != "exr" &&
        fileExtension(o.preview) != "hdr")
      throw Error(o.preview, "preview must be .png, .exr or .hdr");
  }

  envmap::LoadOptions lo;
  if (!o.layout.empty()) lo.layout = envmap::parseLayout(o.layout);
  if (compat) lo.ldrDecode = image::LdrDecode::Gamma22;
  const ProgressFn progress = progressBar("prt light");

  envmap::LoadedEnvironment loaded;
  // One projection: with --encoding at sh::kIrradianceReferenceBands at least, the unwindowed
  // reference, whose first bands are the light (the bands are independent).
  const int projectedBands = encoding ? std::max(o.bands, sh::kIrradianceReferenceBands) : o.bands;
  sh::RgbSh reference;
  if (compat) {
    std::error_code ec;
    if (!std::filesystem::is_directory(o.input, ec))
      throw Error(o.input, "--compat games202 needs a folder of six cube faces (posx.jpg …)");
    if (lo.layout && *lo.layout != envmap::Layout::Faces)
      throw Error(o.input, "--compat games202 reads cube faces only");
    // The course reads negx, posx, posy, negy, posz, negz and pairs them with its own frames.
    auto faces = envmap::readFaceFolder(o.input, envmap::kGames202FaceOrder, lo.ldrDecode,
                                        &loaded.files, &loaded.stats);
    warnAboutPixels(loaded, o.strict);
    loaded.layout = "faces";
    info(o.input + ": 6 faces " + std::to_string(faces[0].width) + "x" +
         std::to_string(faces[0].height) +
         ", GAMES202 compatibility (gamma 2.2 decode, course face frames)");
    reference = envmap::projectGames202Faces(faces, projectedBands, progress);
    if (!o.preview.empty()) {
      // Preview in the standard convention: course order → OpenGL order +X −X +Y −Y +Z −Z.
      loaded.env =
          envmap::Environment::cube({faces[1], faces[0], faces[2], faces[3], faces[4], faces[5]});
    }
  } else {
    loaded = envmap::loadEnvironment(o.input, lo);
    warnAboutPixels(loaded, o.strict);
    info(o.input + ": " + loaded.layout + ", " + std::to_string(loaded.env.texelCount()) +
         " texels, " + std::to_string(o.bands) + " bands");
    reference = envmap::projectEnvironment(loaded.env, projectedBands, progress);
  }
  sh::RgbSh f = reference.truncated(o.bands);

  // The files actually read (a face folder's six images) are inputs too.
  std::vector<NamedPath> read;
  for (const std::string& f : loaded.files) read.push_back({"input", f});
  checkOutputs({{"-o", o.output}, {"--preview", o.preview}}, read);

  const sh::DeringResult windowed = sh::applyWindow(f, window);
  if (window == sh::Window::Dering)
    info("de-ringing: minimum " + std::to_string(windowed.minBefore) + " -> " +
         std::to_string(windowed.minAfter));
  const Mat3d rotation = rotationEulerXYZ(rot[0], rot[1], rot[2]);
  if (rot != std::array<double, 3>{0, 0, 0}) {
    f = sh::Rotation(o.bands, rotation).apply(f);
    if (encoding) reference = sh::Rotation(reference.bands, rotation).apply(reference);
  }
  // The irradiance an engine stores, from the light as written (window and rotation included),
  // and what it loses against the environment's converged irradiance.
  std::optional<io::EncodedIrradianceRecord> irradiance;
  if (encoding) {
    io::EncodedIrradianceRecord r;
    r.encoded = sh::encodeIrradiance(f, *encoding);
    const sh::EncodingError err = sh::encodingError(reference, r.encoded);
    r.referenceBands = reference.bands;
    r.relativeRms = err.relativeRms;
    r.negativeShare = err.negativeShare;
    info(
        fmt::format("irradiance as {} ({} numbers): {:.2f}% relative RMS error against {} bands, "
                    "negative for {:.2f}% of normals",
                    sh::toString(*encoding), sh::storedNumbers(*encoding), 100 * r.relativeRms,
                    r.referenceBands, 100 * r.negativeShare));
    irradiance = r;
  }

  // Coefficients beyond float range (an extremely bright image) would be written as "inf",
  // which no reader accepts: refuse with the figure instead.
  for (std::size_t k = 0; k < f.c.size(); ++k)
    for (int ch = 0; ch < 3; ++ch)
      if (!std::isfinite(f.c[k][ch]))
        throw Error(o.input, fmt::format("SH coefficient {} ({} channel) is not finite: the "
                                         "environment is too bright for 32-bit floats (scale it "
                                         "down); nothing written",
                                         k, "RGB"[ch]));

  // The preview first (it is the one that can still fail on encoding), then the light.
  if (!o.preview.empty()) {
    const image::Image panels = envmap::previewPanels(loaded.env, f, o.previewWidth, rotation);
    image::WriteOptions wo{tone, o.exposure ? *o.exposure : envmap::previewExposure(panels, tone)};
    image::writeImage(o.preview, panels, wo);
  }
  if (engine) {
    writeFileAtomically(o.output, io::formatEngineLight(*engine, f, o.input));
  } else if (format == "games202") {
    io::writeLightGames202(o.output, f);
  } else {
    io::LightFile lf;
    lf.coefficients = f;
    lf.source = o.input;
    lf.layout = loaded.layout;
    lf.window = o.window;
    lf.rotationDeg = rot;
    lf.prtkitVersion = kVersion;
    lf.irradiance = irradiance;
    io::writeLightJson(o.output, lf);
  }
  info("wrote " + o.output + (o.preview.empty() ? "" : " and " + o.preview));
  if (report.wanted()) {
    report.input(o.input);
    for (const std::string& file : loaded.files)
      if (file != o.input) report.input(file);
    report.output(o.output);
    if (!o.preview.empty()) report.output(o.preview);
    report["format"] = format;
    report["source"] = o.input;
    report["layout"] = loaded.layout;
    report["window"] = o.window;
    report["rotationDegrees"] = rot;
    report["light"] = shLightJson(f);
    if (irradiance) report["irradiance"] = io::irradianceJson(*irradiance);
    report.write();
  }
}

}  // namespace

void addLightCommand(CLI::App& root) {
  auto opts = std::make_shared<LightOptions>();
  CLI::App* cmd =
      root.add_subcommand("light", "Project an environment onto SH lighting coefficients");
  cmd->add_option("input", opts->input,
                  "Environment: image (.hdr .exr .png .jpg), folder of six faces, or "
                  "builtin:sky|constant|studio "
                  "(default builtin:sky)");
  cmd->add_option("-o,--output", opts->output,
                  "Output light file (.json ours, .txt GAMES202; --format for an engine's)")
      ->required();
  cmd->add_option("--layout", opts->layout,
                  "latlong|probe|vcross|hcross|faces (default: detected)");
  cmd->add_option("-b,--bands", opts->bands,
                  "SH bands B (1.." + std::to_string(bands::kMaxLibrary) + "; B² coefficients)")
      ->capture_default_str();
  cmd->add_option("--window", opts->window, "none|hanning|lanczos|dering")->capture_default_str();
  cmd->add_option("--rotate", opts->rotate, "Rotate the light: X,Y,Z Euler degrees (R = Rz Ry Rx)");
  cmd->add_option("--compat", opts->compat, "games202: reproduce the course framework's numbers");
  cmd->add_option(
      "--format", opts->format,
      std::string(kLightFormats) +
          ": ours, the GAMES202 course's light.txt, a three.js LightProbe, a glTF "
          "asset with an EXT_lights_image_based light (irradiance and a specular cube "
          "prefiltered from the SH light; .gltf or .json), Filament cmgen's sh.txt as "
          "`cmgen -w no` writes it (windowing off; cmgen's default -w auto windows "
          "bands 1 and up, band 2 by 1.2-4x as the image goes), Unity SphericalHarmonicsL2 "
          "(docs/formats-light.md; default: by extension)");
  cmd->add_option("--preview", opts->preview,
                  "Preview image: source, SH radiance, SH irradiance/pi");
  cmd->add_option("--preview-width", opts->previewWidth, "Preview width in pixels")
      ->check(intRange(8, image::kMaxImageSide))
      ->capture_default_str();
  cmd->add_option("--exposure", opts->exposure, "Preview exposure in stops (default: automatic)")
      ->check(exposureStops());
  cmd->add_option("--tonemap", opts->toneMap, "Preview tone mapper: clamp|reinhard|aces")
      ->capture_default_str();
  cmd->add_flag("--strict", opts->strict, "Fail on NaN/Inf or negative pixels instead of warning");
  cmd->add_option("--encoding", opts->encoding,
                  "Also store the irradiance as an engine does, with its error against 12 bands "
                  "(JSON light files): l1, l1-windowed, l1-geomerics, zh3, zh3-shared, "
                  "zh3-optimal, zh3-hallucinated, l2 or l2-deringed (docs/formats-light.md)");
  cmd->add_option("--basis", opts->basis,
                  "sh (spherical harmonics, --bands) | haar (all-frequency: the largest Haar "
                  "wavelet terms over a cube map, for Haar bakes; Ng et al. 2003)")
      ->capture_default_str();
  cmd->add_option("--resolution", opts->resolution,
                  "--basis haar: the cube's side, a power of two 2..256 (default 32)");
  cmd->add_option("--terms", opts->terms,
                  "--basis haar: wavelet terms kept, the non-linear approximation (default 200)")
      ->check(intRange(1, 1 << 20));
  cmd->add_option("--selection", opts->selection,
                  "--basis haar: area (largest |c| x support area, as Ng et al.) | magnitude "
                  "(largest |c|)")
      ->capture_default_str();
  addJsonOption(cmd, opts->json);
  cmd->callback([opts] { runLight(*opts); });
}

}  // namespace prt::cli
