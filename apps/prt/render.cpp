// prt render: relight a bake under an environment and render it to an image (CPU, Embree).
//
//   prt render bunny.glb --light builtin:sky --rotate 0,90,0 --size 800x600 -o bunny.png
//   prt render bunny.glb --light studio.exr --turntable 12 --contact-sheet sheet.png -o frame.png
//   prt render boxm.glb --encoding l1 -o box_l1.png     (a matrix bake, as an engine's L1 shows it)
//
// The light is an environment (image, face folder or builtin:NAME), projected to the bake's
// bands. --rotate turns the environment (X, then Y, then Z, degrees) by rotating its SH
// coefficients; the background rotates with it.
//
// --encoding E draws, instead of PRT's radiance, the diffuse shading an engine gets from one of
// the irradiance encodings it stores (sh/irradiance_encoding.hpp) of the light arriving at each
// row of a matrix bake (relight/encoded_diffuse.hpp; docs/lightmaps.md). Diffuse only: a glossy
// material is refused, as are vector and probe bakes (they hold no incident light).

#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/options.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/primary.hpp"
#include "prt/render/relit_view.hpp"
#include "prt/render/render.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "reference_input.hpp"
#include "render_haar.hpp"
#include "render_probes.hpp"
#include "report.hpp"
#include "transfer_options.hpp"

namespace prt::cli {

namespace {

struct RenderOptions {
  std::string bake;
  std::string light = "builtin:sky";
  std::string rotate;
  std::string camera;
  std::string size = "640x480";
  int spp = 4;
  std::string exposure = "auto";
  std::string tonemap = "aces";
  TransferChoice transfer;
  std::string material;
  int bands = 0;
  std::string background = "env";
  int turntable = 0;
  std::string contactSheet;
  unsigned seed = 0;
  std::string output;
  std::string json;
  std::string reference;  ///< --reference FILE: draw prt reference's radiance instead of PRT's
  // A probe bake (render_probes.hpp): the object placed in its grid.
  std::string object, at;
  float objectSize = 0;
  std::string encoding;  ///< --encoding: "" or "none" = PRT's own radiance
  int terms = 0;         ///< --terms: a Haar bake's light terms (0: kDefaultHaarLightTerms)
};

void checkOutput(const std::string& path, const char* what) {
  const std::string ext = fileExtension(path);
  if (ext != "png" && ext != "exr" && ext != "hdr" && !isStandardOutput(path))
    throw Error(path + ": " + what + " must be .png, .exr or .hdr");
  checkWritable(path);
}

// "frame.png" -> "frame_007.png".
std::string framePath(const std::string& out, int k) {
  const std::filesystem::path p(out);
  const std::string name = fmt::format("{}_{:03d}{}", p.stem().string(), k, p.extension().string());
  return (p.parent_path() / name).string();
}

void run(const RenderOptions& o) {
  // Validate everything cheap before any work, so errors come at once and nothing is written.
  render::FrameSettings frame;
  parseSize(o.size, frame.width, frame.height);
  frame.spp = o.spp;
  frame.seed = o.seed;
  render::checkFrameSettings(frame);
  const Mat3d userRotation = parseRotation(o.rotate);
  Rgb bgColour;
  const render::Background bgKind = render::parseBackground(o.background, &bgColour);
  image::WriteOptions write;
  write.toneMap = image::parseToneMap(o.tonemap);
  const std::optional<float> exposure = exposureOption(o.exposure);
  if (o.turntable < 0) throw Error("--turntable must be a positive frame count");
  if (o.turntable > 0)
    refuseStandardOutput({"-o", o.output}, "--turntable writes numbered frames beside -o");
  checkOutput(o.output, "the output");
  if (!o.contactSheet.empty()) {
    if (o.turntable == 0) throw Error("--contact-sheet needs --turntable N");
    checkOutput(o.contactSheet, "the contact sheet");
  }
  if (o.bands != 0) checkOptionRange(OptionSpelling::Cli, "bands", o.bands, 1, bands::kMaxLibrary);
  // What is written: -o itself, or with --turntable its numbered frames and the contact sheet.
  std::vector<NamedPath> outputs;
  if (o.turntable == 0) outputs.push_back({"-o", o.output});
  for (int k = 0; k < o.turntable; ++k)
    outputs.push_back({fmt::format("-o (frame {})", k), framePath(o.output, k)});
  outputs.push_back({"--contact-sheet", o.contactSheet});
  if (!o.reference.empty() && o.turntable > 0)
    throw Error("--reference: the reference holds one light rotation; --turntable turns it");
  std::optional<sh::IrradianceEncoding> encoding;
  if (!o.encoding.empty() && o.encoding != "none")
    encoding = sh::parseIrradianceEncoding(o.encoding);
  if (encoding && !o.reference.empty())
    throw Error(
        "--reference draws the reference's radiance, --encoding PRT's through an encoding: "
        "one or the other");
  const std::vector<NamedPath> inputs = {
      {"input", o.bake}, {"--light", o.light}, {"--reference", o.reference}};
  checkOutputs(outputs, inputs);
  Report report("render", o.json);
  report.check(outputs, inputs);
  const auto start = std::chrono::steady_clock::now();

  const BakeFile bake = readBake(o.bake);
  bake.requireComplete(o.bake);
  if (bake.domain() == TransferDomain::Probes) {
    if (encoding)
      throw Error(o.bake,
                  "holds a probe grid: --encoding draws a surface's matrix transfer "
                  "through an irradiance encoding (prt bake --transfer matrix)");
    // The scene and an object lit through the probes (render_probes.cpp): one light, one frame.
    if (o.turntable > 0 || !o.reference.empty() || !o.material.empty())
      throw Error(o.bake,
                  "holds a probe grid: --turntable, --reference and --material draw a "
                  "surface's transfer (render the probes with --object, --at)");
    ProbeRenderArgs p{o.bake,  o.light, o.camera,     o.output, o.object, o.at,  o.objectSize,
                      o.bands, frame,   userRotation, bgKind,   bgColour, write, exposure};
    renderProbeBake(bake, p, report);
    if (report.wanted()) {
      report.input(o.bake);
      report.input(o.light);
      report.write();
    }
    return;
  }
  if (!o.object.empty() || !o.at.empty())
    throw Error(o.bake,
                "--object and --at place an object in a probe grid (prt probes); this "
                "bake holds a surface's transfer");
  const BakedTransfer& baked = pickTransfer(bake, o.transfer, o.bake);
  // The material: --material, else the one the bake stored.
  const Material material =
      materialOption(o.material, baked, o.bake,
                     "--material changes the surface at each vertex, not the light the surfaces "
                     "send each other (bake again for both)");
  if (encoding && !baked.transfer.isMatrix())
    throw Error(o.bake, "holds " + baked.describe() +
                            " transfer: --encoding encodes the light arriving at each row, which "
                            "a matrix bake holds (prt bake --transfer matrix); vector (diffuse) "
                            "transfer has already integrated it against the normal");
  if (encoding && material.glossy())
    throw Error(o.bake, "--encoding " + o.encoding +
                            ": an irradiance encoding shades the diffuse "
                            "part only, and the material " +
                            material.spec() +
                            " has a glossy lobe (pass --material lambert to see the encoding)");
  warnLobeOnVectors(material, baked, o.bake,
                    "the material's glossy lobe needs a matrix bake (prt bake --transfer matrix)");
  if (baked.transfer.isHaar()) {
    // The all-frequency basis (render_haar.cpp): the light is the environment's largest
    // wavelet terms, rotated by resampling; one frame, PRT's own radiance.
    if (o.turntable > 0 || !o.reference.empty() || encoding || o.bands > 0)
      throw Error(o.bake, "holds Haar transfer: --turntable, --reference, --encoding and --bands "
                          "draw SH transfer (prt render of a Haar bake draws one frame; "
                          "--terms sets the light's wavelet terms)");
    HaarRenderArgs h{o.bake, o.light, o.camera, o.output,
                     o.terms ? o.terms : kDefaultHaarLightTerms, frame, userRotation, bgKind,
                     bgColour, write, exposure};
    renderHaarBake(bake, baked, material, h, report);
    if (report.wanted()) {
      report.input(o.bake);
      report.input(o.light);
      report.write();
    }
    return;
  }
  if (o.terms != 0)
    throw Error(o.bake, "--terms sets a Haar light's wavelet terms; this bake holds " +
                            baked.describe() + " (SH) transfer");
  // Every frame through one view (render/relit_view.hpp): the transfer cut to --bands once, per
  // vertex or per texel, the base-colour texture per pixel.
  const auto occluder = makeEmbreeOccluder(bake.mesh);
  render::RelitView view(bake.mesh, *occluder, baked.transfer, material);
  if (o.bands > baked.transfer.bands())
    warn(fmt::format("--bands {}: the bake has only {} bands; using {}", o.bands,
                     baked.transfer.bands(), baked.transfer.bands()));
  if (o.bands > 0) view.setBands(std::min(o.bands, baked.transfer.bands()));
  if (baked.transfer.isMatrix()) warnLobeEnergyLoss(material, view.bands(), o.bake);
  view.setEncoding(encoding);

  // The light: an SH light file, or an environment projected to the transfer's bands.
  const io::Lighting lighting = io::loadLighting(o.light, view.bands(), progressBar("projecting"));
  for (const std::string& w : lighting.warnings) warn(w);
  const sh::RgbSh& light = lighting.coefficients;

  render::Camera camera = render::frameMesh(bake.mesh, frame.width, frame.height);
  if (!o.camera.empty()) camera = render::parseCamera(o.camera, camera);
  if (render::eyeInsideMesh(bake.mesh, *occluder, camera.eye))
    warn("the camera is inside the mesh; the image will show its inside");

  // --reference: the brute-force radiance of `prt reference` at every vertex, drawn as PRT's
  // would be (the same camera, background and exposure rule), if it is of this scene.
  std::vector<Rgb> referenceRadiance;
  if (!o.reference.empty() && !view.perVertex())
    throw Error(o.reference, "--reference draws a per-vertex reference; " + o.bake + " holds per-" +
                                 view.rowNoun() + " transfer");
  if (!o.reference.empty()) {
    if (lighting.isShFile())
      throw Error(o.light,
                  "--reference needs the environment the reference was computed "
                  "under, not an SH light file");
    const io::ReferenceFile ref = readMatchingReference(
        o.reference, referenceScene(bake.mesh, *lighting.image, o.bake, o.light, userRotation,
                                    baked, material, camera.eye));
    if (ref.vertices.size() != bake.mesh.vertexCount())
      throw Error(o.reference, fmt::format("covers {} of the mesh's {} vertices: an image needs "
                                           "them all (prt reference without --vertices)",
                                           ref.vertices.size(), bake.mesh.vertexCount()));
    referenceRadiance = ref.radiance;  // ascending and complete: entry i is vertex i
    info(fmt::format("drawing the reference of {} ({} samples per vertex) instead of PRT",
                     o.reference, ref.samples));
  }

  const int frames = o.turntable > 0 ? o.turntable : 1;
  std::vector<image::Image> sheet;
  // All or nothing: the frames and the contact sheet wait in temporaries until the last is made.
  OutputBatch batch;
  const char* did = o.turntable > 0 ? "rendered" : "wrote";
  Json frameReports = Json::array();
  for (int k = 0; k < frames; ++k) {
    // Turntable: the environment turns about +Y after the user's rotation.
    const Mat3d rotation = o.turntable > 0
                               ? rotationAxisAngle({0, 1, 0}, 2 * kPi * k / frames) * userRotation
                               : userRotation;
    // Matrix transfer is view-dependent: each row is seen from the camera's eye. The
    // reference's radiance holds the texture already, folded in at its vertices as every
    // per-vertex stage sees it (geometry/mesh.hpp): drawn as it is.
    relight::RelightInfo relit;
    render::ShadeFn shade;
    if (referenceRadiance.empty()) {
      view.relight(light, rotation, camera.eye, o.bake, &relit);
      shade = view.shader();
    } else {
      shade = view.shader(referenceRadiance);
    }
    // --exposure auto: image/exposure.hpp's rule on the first frame's model pixels, kept for
    // every turntable frame so they compare.
    // The first frame's probe pixels also say whether SH ringing blacks out the model.
    if (k == 0) {
      const render::FrameSurvey survey =
          render::surveyFrame(*occluder, shade, camera, frame.width, frame.height, write.toneMap);
      write.exposureStops = exposure ? *exposure : survey.exposureStops;
      const std::string ringing = render::negativeRadianceWarning(survey.negativeShare);
      if (!ringing.empty()) warn(ringing);
      report["negativeShare"] = survey.negativeShare;
    }
    const render::BackgroundFn bg = render::background(
        bgKind, bgColour, lighting.image ? &*lighting.image : nullptr, &light, rotation);
    const std::string label = frames > 1 ? fmt::format("frame {}/{}", k + 1, frames) : "rendering";
    const auto frameStart = std::chrono::steady_clock::now();
    image::Image img =
        render::tracePrimary(camera, frame, *occluder, shade, bg, progressBar(label));
    const std::string path = o.turntable > 0 ? framePath(o.output, k) : o.output;
    image::writeImage(path, img, write);
    report.output(path);
    frameReports.push_back(
        {{"path", path},
         {"lightRotationDegreesY", o.turntable > 0 ? 360.0 * k / frames : 0.0},
         {"seconds",
          std::chrono::duration<double>(std::chrono::steady_clock::now() - frameStart).count()}});
    if (k == 0) report["bands"] = relit.bands;
    if (!o.contactSheet.empty()) sheet.push_back(std::move(img));
    info(fmt::format("{} {} ({}x{}, {} spp, {} bands, {} transfer, {}{}, exposure {:.2f}{})", did,
                     path, frame.width, frame.height, frame.spp, relit.bands, baked.describe(),
                     material.spec(),
                     encoding ? fmt::format(", {} irradiance", sh::toString(*encoding)) : "",
                     write.exposureStops, exposure ? "" : " auto"));
  }
  if (!o.contactSheet.empty()) {
    image::writeImage(o.contactSheet, render::contactSheet(sheet), write);
    report.output(o.contactSheet);
  }
  batch.commit();
  if (report.wanted()) {
    report.input(o.bake);
    report.input(o.light);
    if (!o.reference.empty()) report.input(o.reference);
    report["transfer"] = {{"mode", toString(baked.mode())},
                          {"layout", toString(baked.transfer.layout())},
                          {"representation", baked.transfer.compressed() ? "cpca" : "dense"}};
    report["material"] = material.spec();
    report["encoding"] = encoding ? sh::toString(*encoding) : "none";
    report["width"] = frame.width;
    report["height"] = frame.height;
    report["spp"] = frame.spp;
    report["exposureStops"] = write.exposureStops;
    report["exposureAuto"] = !exposure.has_value();
    report["toneMap"] = o.tonemap;
    report["camera"] = cameraJson(camera);
    report["frames"] = std::move(frameReports);
    report["seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.write();
  }
  if (o.turntable > 0)
    info(fmt::format("wrote {} frames {}..{}{}", frames, framePath(o.output, 0),
                     framePath(o.output, frames - 1),
                     o.contactSheet.empty() ? "" : " and " + o.contactSheet));
}

}  // namespace

void addRenderCommand(CLI::App& root) {
  auto opts = std::make_shared<RenderOptions>();
  CLI::App* cmd = root.add_subcommand("render", "Relight a bake and render an image (CPU)");
  cmd->add_option("bake", opts->bake, "Bake file (.glb)")->required();
  cmd->add_option("--light", opts->light,
                  "Environment image, face folder, builtin:NAME, or SH light (.json/.txt)")
      ->capture_default_str();
  cmd->add_option("--rotate", opts->rotate,
                  "Rotate the environment: X,Y,Z degrees (X, then Y, then Z)");
  cmd->add_option("--camera", opts->camera,
                  "Camera: 'eye=x,y,z;target=x,y,z;up=x,y,z;fov=deg' (default: frame the object — "
                  "the parts other than a ground plane — from above-front)");
  cmd->add_option("--size", opts->size, "Image size WxH")->capture_default_str();
  cmd->add_option("--spp", opts->spp, "Stratified samples per pixel")->capture_default_str();
  cmd->add_option("--exposure", opts->exposure,
                  "Exposure in stops (PNG), or auto: the model's median at light grey, at most 2% "
                  "of its pixels clipped")
      ->check(exposureStopsOrAuto())
      ->capture_default_str();
  cmd->add_option("--tonemap", opts->tonemap, "Tone map for PNG: aces, reinhard, clamp")
      ->capture_default_str();
  addTransferChoice(cmd, opts->transfer, "to relight");
  addMaterialOption(cmd, opts->material, "to relight with");
  cmd->add_option("--bands", opts->bands, "Use at most this many SH bands (default: all)")
      ->check(intRange(1, bands::kMaxLibrary));
  cmd->add_option("--background", opts->background,
                  "What rays that miss show: env, sh (the light's SH reconstruction), none, a "
                  "linear colour r,g,b, or #rrggbb")
      ->capture_default_str();
  cmd->add_option("--turntable", opts->turntable,
                  "Render N frames with the light turning once about +Y (OUT_000.png ...)")
      ->check(intRange(1, 3600));
  cmd->add_option("--contact-sheet", opts->contactSheet,
                  "With --turntable: also a grid of all frames");
  cmd->add_option("--seed", opts->seed, "Seed of the sub-pixel jitter")
      ->check(unsignedInt(UINT32_MAX))
      ->capture_default_str();
  cmd->add_option("-o,--output", opts->output,
                  "Output image (.png tone-mapped sRGB, .exr/.hdr linear)")
      ->required();
  cmd->add_option("--reference", opts->reference,
                  "Draw the brute-force radiance of prt reference's .json (every vertex, this "
                  "bake, light and --rotate) instead of PRT's, to set the two side by side");
  cmd->add_option("--object", opts->object,
                  "A probe bake (prt probes): a mesh file or builtin:NAME placed in the grid, lit "
                  "through the probes with the scene");
  cmd->add_option("--at", opts->at,
                  "With --object: where its centre goes, x,y,z (default: the grid's centre)");
  cmd->add_option("--object-size", opts->objectSize,
                  "With --object: its largest side (default: a fifth of the grid's)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--terms", opts->terms,
                  "A Haar bake: the light's largest wavelet terms kept (default 200; Ng et al. "
                  "2003's non-linear approximation)")
      ->check(intRange(1, 1 << 20));
  cmd->add_option("--encoding", opts->encoding,
                  "Draw the diffuse shading an engine gets from an irradiance encoding of the "
                  "light arriving at each row (a matrix bake, a diffuse material): l1, "
                  "l1-windowed, l1-geomerics, zh3, zh3-shared, zh3-optimal, zh3-hallucinated, l2, "
                  "l2-deringed, or none (PRT's own radiance; docs/lightmaps.md)");
  addJsonOption(cmd, opts->json);
  cmd->callback([opts] { run(*opts); });
}

}  // namespace prt::cli
