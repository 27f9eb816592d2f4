// prt demo: the whole pipeline on a default scene, into a folder a person wants to open.
//
//   prt demo -o demo-out
//   prt demo --mesh bunny.obj --env studio.exr --env builtin:sky -o out
//   prt demo -o out --json demo.json          (index.html's figures as numbers)
//
// The scene is the Stanford bunny on a ground plane when Debian's glmark2-data is installed,
// else the builtin Cornell box. It is baked once with all three transfer modes (unshadowed,
// shadowed, inter-reflected), then for each environment (the builtin sky, and a CC0 Poly Haven
// map from Debian's blender-data when installed) every mode is relit and rendered, the brute-force
// Monte Carlo reference (no SH) is computed at every vertex and rendered the same way, and the
// per-vertex error is shown in false colour beside the per-band validation table. A turntable of
// the light rotating about +Y closes each environment. index.html shows it all with the numbers.
//
// Glossy rows: the scene is also baked as inter-reflected transfer *matrices* (Sloan, Kautz &
// Snyder 2002, §6; --glossy-bands, default 5: B⁴ = 625 floats per vertex; --bounces bounces off
// surfaces of the same glossy material) and relit with a glossy
// material (--glossy, default a Phong lobe) seen from the stills' camera, e(p, v) with
// v = normalize(eye − p) per vertex (relight::relight, as prt render); the brute-force
// reference evaluates the same lobe with no SH (render/reference.hpp), and the table adds the
// fraction of the lobe's energy beyond each band count — what no b-band transfer can hold.
// The matrices go to glossy.glb (the demo's scene.glb stays the small diffuse bake the web page
// loads); prt view and prt render relight it.
//
// Per-texel row (demo_texels.hpp): the builtin Cornell box as a coarse mesh, per vertex, per
// texel and per vertex at the lightmap's bytes, against its Monte Carlo reference.
//
// All-frequency row (demo_haar.hpp): the shadowed SH bake beside a Haar bake of the scene at the
// same bytes per vertex, under the first two environments, against the same reference.
//
// --json reports the figures index.html shows (the bakes' statistics, every validation table,
// the per-texel row) as numbers, with every file the folder holds.
//
// Everything the demo writes comes from the library calls the verbs use (bake, relight,
// renderRelit, validate), so the pictures are exactly what `prt bake/render/validate` give.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include "args.hpp"
#include "cli.hpp"
#include "demo_page.hpp"
#include "demo_report.hpp"
#include "demo_haar.hpp"
#include "demo_texels.hpp"
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
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/load.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight.hpp"
#include "prt/relight/relighter.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/render.hpp"
#include "prt/render/validate.hpp"
#include "prt/transport/bake.hpp"
#include "report.hpp"
#include "web.hpp"

namespace prt::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";
constexpr const char* kPolyHavenDir = "/usr/share/blender/datafiles/studiolights/world";

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

DemoScene makeScene(const std::string& spec) {
  DemoScene s;
  std::string path = spec;
  if (spec == "auto") path = fs::exists(kBunny) ? kBunny : "builtin:cornell";
  s.path = path;
  LoadReport report;
  Mesh object = loadMesh(path, &report);
  for (const auto& w : report.warnings) warn(w);
  const Bounds b = computeBounds(object);
  s.centre = b.centre();
  s.radius = b.radius();
  if (isBuiltinScene(path) && path.rfind("builtin:cornell", 0) == 0) {
    s.mesh = std::move(object);
    s.description = "the builtin Cornell box (install glmark2-data for the Stanford bunny)";
    return s;
  }
  // A ground plane under the object, three times its size, so it casts a shadow.
  const float size = 3 * std::max({b.hi.x - b.lo.x, b.hi.z - b.lo.z}) / 2;
  const std::string plane = fmt::format("builtin:plane?y={:.6g}&size={:.6g}&grid=64", b.lo.y, size);
  s.mesh = std::move(object);
  appendMesh(s.mesh, loadMesh(plane));
  s.mesh.source = path + "+" + plane;
  s.description = (path == kBunny ? "the Stanford bunny (Debian's glmark2-data)" : path) +
                  std::string(" on a ground plane");
  return s;
}

/// The environments: the builtin sky, plus a Poly Haven map from blender-data when installed.
std::vector<std::string> defaultEnvironments() {
  std::vector<std::string> envs = {envmap::kDefaultEnvironment};
  for (const char* name : {"courtyard.exr", "forest.exr", "city.exr"}) {
    const fs::path p = fs::path(kPolyHavenDir) / name;
    if (fs::exists(p)) {
      envs.push_back(p.string());
      break;
    }
  }
  return envs;
}

/// A file-name-safe short name: "builtin:sky?x=1" → "sky", "/a/courtyard.exr" → "courtyard".
std::string shortName(const std::string& spec) {
  std::string s = spec;
  if (s.rfind("builtin:", 0) == 0) s = s.substr(8);
  s = fs::path(s.substr(0, s.find('?'))).stem().string();
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s.empty() ? "env" : s;
}

/// The image as the PNG will show it, still linear: tone mapped (with exposure) and clamped, so
/// pictures with different tone maps can share one contact sheet written with ToneMap::Clamp.
image::Image displayed(image::Image img, const image::WriteOptions& wo) {
  for (Rgb& p : img.pixels) p = image::toneMap(p, wo.toneMap, wo.exposureStops);
  return img;
}

/// The cheap checks, before anything is loaded; the glossy rows' material, if any.
std::optional<Material> checkArgs(const DemoArgs& a) {
  checkOptionRange(OptionSpelling::Cli, "bands", a.bands, 1, bands::kMaxBake);
  if (a.samples < 1 || a.samples > kMaxBakeSamples)
    throw Error(fmt::format("--samples {}: must be 1..{}", a.samples, kMaxBakeSamples));
  if (a.referenceSamples < 1 || a.glossyReferenceSamples < 1)
    throw Error("--reference-samples and --glossy-reference-samples must be at least 1");
  if (a.bounces < 1 || a.bounces > kMaxBounces)
    throw Error(fmt::format("--bounces {}: must be 1..{}", a.bounces, kMaxBounces));
  if (a.frames < 0 || a.frames > 360) throw Error("--frames must be 0..360");
  if (a.glossyBands < 1 || a.glossyBands > bands::kMaxShaderGlossy)
    throw Error(
        fmt::format("--glossy-bands {}: must be 1..{} (the page draws glossy matrices up "
                    "to that)",
                    a.glossyBands, bands::kMaxShaderGlossy));
  if (a.glossySamples < 1 || a.glossySamples > kMaxBakeSamples)
    throw Error(
        fmt::format("--glossy-samples {}: must be 1..{}", a.glossySamples, kMaxBakeSamples));
  if (a.glossy == "none") return std::nullopt;
  const Material m = parseMaterial(a.glossy);
  if (!m.glossy())
    throw Error(
        fmt::format("--glossy '{}': no glossy lobe (use 'none' for no glossy rows)", a.glossy));
  return m;
}

/// The outputs are written inside the demo's partial folder (FolderOutput).
struct DemoFolder {
  fs::path root;
  std::string operator()(const std::string& relative) const { return (root / relative).string(); }
};

/// The three diffuse modes, baked into one file (scene.glb).
BakeFile bakeModes(const Mesh& mesh, const Occluder& occluder, const DemoArgs& a) {
  BakeFile bake;
  bake.mesh = mesh;
  for (TransferMode mode :
       {TransferMode::Unshadowed, TransferMode::Shadowed, TransferMode::Interreflected}) {
    BakeSettings s;
    s.mode = mode;
    s.bands = a.bands;
    s.samples = a.samples;
    s.bounces = effectiveBounces(mode, a.bounces);
    BakedTransfer t;
    t.recipe = s;
    t.transfer = prt::bake(bake.mesh, occluder, s, &t.stats,
                           progressBar(std::string("bake ") + toString(mode)));
    info(fmt::format("demo: baked {} in {:.2f} s ({} rays)", toString(mode), t.stats.secondsTotal,
                     t.stats.rays));
    bake.transfers.push_back(std::move(t));
  }
  return bake;
}

/// The glossy bake: inter-reflected transfer matrices (glossy bounces), written to glossy.glb.
GlossyBake bakeGlossy(const Mesh& mesh, const Occluder& occluder, const DemoArgs& a,
                      const Material& material, const DemoFolder& file) {
  const auto tg = Clock::now();
  GlossyBake glossy;
  glossy.material = material;
  BakeFile& g = glossy.file;
  g.mesh = mesh;
  BakeSettings s;
  s.mode = TransferMode::Interreflected;
  s.bounces = a.bounces;
  s.layout = TransferLayout::Matrix;
  s.bands = a.glossyBands;
  s.samples = a.glossySamples;
  s.material = material;
  BakedTransfer t;
  t.recipe = s;
  t.transfer = prt::bake(g.mesh, occluder, s, &t.stats, progressBar("bake glossy"));
  g.transfers.push_back(std::move(t));
  writeBake(file("glossy.glb"), g);
  glossy.bytes = fs::file_size(file("glossy.glb"));
  glossy.seconds = since(tg);
  info(fmt::format("demo: baked glossy matrices ({} bands) in {:.2f} s, glossy.glb {:.0f} MB",
                   a.glossyBands, glossy.seconds, glossy.bytes / 1e6));
  return glossy;
}

/// What every mode of one environment is drawn with.
struct LightScene {
  const Mesh& mesh;
  const Occluder& occluder;
  const envmap::Environment& env;
  const render::Camera& camera;
  const render::FrameSettings& frame;
  const DemoFolder& file;
};

/// One transfer under one environment: validated against the reference, relit, and drawn as
/// PRT, reference and error pictures (appended, as displayed, to `panels`).
ModeResult renderMode(const LightScene& ls, const BakedTransfer& bt, const sh::RgbSh& light,
                      LightResult& L, const DemoArgs& a, std::vector<image::Image>& panels) {
  const auto tm = Clock::now();
  const Mesh& mesh = ls.mesh;
  ModeResult m;
  m.mode = bt.mode();
  m.glossy = bt.transfer.layout() == TransferLayout::Matrix;
  const std::string key = m.glossy ? "glossy" : toString(m.mode);
  render::ValidateSettings vs;
  vs.reference.samples = m.glossy ? a.glossyReferenceSamples : a.referenceSamples;
  // Glossy: PRT and reference see each vertex from the stills' camera.
  if (m.glossy) vs.reference.eye = ls.camera.eye;
  m.report = render::validate(mesh, ls.occluder, bt.transfer, bt.recipe, ls.env, light, vs,
                              progressBar(fmt::format("reference {} {}", L.name, key)));
  writeFileAtomically(ls.file(fmt::format("validation/{}_{}.json", L.name, key)),
                      render::reportJson(m.report));
  const std::vector<Rgb> relit =
      relight::relight(bt.transfer, light, bt.recipe.material,
                       {mesh.positions, mesh.normals, mesh.albedo}, ls.camera.eye);
  // One exposure per environment, from its unshadowed (brightest) relighting, so every picture
  // under it compares directly.
  if (m.mode == TransferMode::Unshadowed)
    L.exposure = render::autoExposure(mesh, ls.occluder, relit, ls.camera, ls.frame.width,
                                      ls.frame.height, image::ToneMap::Aces);
  const image::WriteOptions wo{image::ToneMap::Aces, L.exposure};
  const std::string base = fmt::format("img/{}_{}", L.name, key);
  const render::BackgroundFn background = render::environmentBackground(ls.env, Mat3d::identity());
  const auto draw = [&](std::span<const Rgb> radiance, const render::BackgroundFn& bg) {
    return render::renderRelit(mesh, ls.occluder, radiance, ls.camera, ls.frame, bg);
  };
  const auto save = [&](const std::string& name, const image::Image& img,
                        const image::WriteOptions& opts) {
    panels.push_back(displayed(img, opts));
    image::writeImage(ls.file(name), panels.back(), {image::ToneMap::Clamp, 0.0f});
    return name;
  };
  m.prtImage = save(base + "_prt.png", draw(relit, background), wo);
  std::vector<Rgb> reference(mesh.vertexCount());
  for (std::size_t i = 0; i < m.report.reference.vertices.size(); ++i)
    reference[m.report.reference.vertices[i]] = m.report.reference.radiance[i];
  m.refImage = save(base + "_ref.png", draw(reference, background), wo);
  const std::vector<Rgb> colours = render::vertexErrorColours(mesh, m.report, &m.errorScale);
  m.errImage = save(base + "_err.png", draw(colours, render::colourBackground(Rgb(0.0f))),
                    {image::ToneMap::Clamp, 0.0f});
  const render::BandRow& last = m.report.rows.back();
  info(
      fmt::format("demo: {} {}: rel. RMSE {:.2f}% at {} bands (floor {:.2f}%, reference std. "
                  "error {:.2f}%; reference {:.1f} s, all {:.1f} s)",
                  L.name, key, 100 * last.relRmse, last.bands, 100 * last.floor,
                  100 * last.refStdErr, m.report.reference.seconds, since(tm)));
  m.seconds = since(tm);
  return m;
}

/// The light turning once about +Y: SH rotation of the light, the background with it.
void renderTurntable(const LightScene& ls, const BakedTransfer& bt, const sh::RgbSh& light,
                     const DemoScene& scene, const DemoArgs& a, LightResult& L) {
  render::FrameSettings small = ls.frame;
  small.width = ls.frame.width * 2 / 3;
  small.height = ls.frame.height * 2 / 3;
  const render::Camera cam = render::frameMesh(ls.mesh, small.width, small.height);
  std::vector<image::Image> sheet;
  relight::Relighter relighter(bt.transfer, {ls.mesh.positions, ls.mesh.normals, ls.mesh.albedo});
  relighter.setMaterial(bt.recipe.material);
  for (int k = 0; k < a.frames; ++k) {
    const Mat3d rot = rotationAxisAngle({0, 1, 0}, 2 * kPi * k / a.frames);
    const std::span<const Rgb> relit = relighter.relight(light, rot, cam.eye);
    image::Image img = render::renderRelit(ls.mesh, ls.occluder, relit, cam, small,
                                           render::environmentBackground(ls.env, rot));
    const std::string name = fmt::format("img/{}_turn_{:02d}.png", L.name, k);
    image::writeImage(ls.file(name), img, {image::ToneMap::Aces, L.exposure});
    L.frames.push_back(name);
    sheet.push_back(std::move(img));
  }
  L.turntable = "img/" + L.name + "_turntable.png";
  image::writeImage(ls.file(L.turntable), render::contactSheet(sheet, 4),
                    {image::ToneMap::Aces, L.exposure});
}

/// The live viewer: prt web's folder for the same bake and environments, in web/. Returns why
/// there is none ("" when written); `report` gets what prt web --json reports of it.
std::string writeLiveViewer(const std::vector<std::string>& envSpecs, const DemoFolder& file,
                            const std::string& output, float exposure, Json& report) {
  std::string why;
  report = nullptr;
  if (!webAssetsAvailable(&why)) {
    warn("demo: no live viewer on the page: " + why);
    return why;
  }
  WebOptions w;
  w.bake = file("scene.glb");
  w.envs = envSpecs;
  w.output = file("web");
  w.reportAs = (fs::path(output) / "web").string();  // where it will be, not the partial folder
  w.mode = "interreflected";
  // The stills' framing is the page's own (render::meshFraming: the object, not the ground
  // plane); the page opens at the stills' exposure of the first environment.
  w.exposure = exposure;
  report = writeWebViewer(w);
  report["bake"]["path"] = (fs::path(output) / "scene.glb").string();  // not the partial folder
  return "";
}

void runDemo(const DemoArgs& a) {
  const auto t0 = Clock::now();
  const std::optional<Material> glossyMaterial = checkArgs(a);
  render::FrameSettings frame;
  parseSize(a.size, frame.width, frame.height);
  const std::vector<std::string> envSpecs = a.envs.empty() ? defaultEnvironments() : a.envs;
  // The output folder (and its .partial sibling) is replaced as a whole: no input may live there.
  {
    std::vector<NamedPath> inputs = {{"--mesh", a.mesh == "auto" ? "" : a.mesh}};
    for (const std::string& e : envSpecs) inputs.push_back({"--env", e});
    checkOutputFolder({"-o", a.output}, inputs);
  }
  checkFolderReplaceable(a.output, "prt demo");
  Report report("demo", a.json);
  {
    std::vector<NamedPath> inputs = {{"--mesh", a.mesh == "auto" ? "" : a.mesh}};
    for (const std::string& e : envSpecs) inputs.push_back({"--env", e});
    report.checkOutsideFolder({"-o", a.output});
    report.check({{"-o", a.output}}, inputs);
  }

  // Inputs first: a bad mesh or environment fails before anything is written.
  const DemoScene scene = makeScene(a.mesh);
  std::vector<envmap::LoadedEnvironment> envs;
  for (const std::string& spec : envSpecs) {
    envs.push_back(envmap::loadEnvironment(spec));
    for (const std::string& w : envmap::repairWarnings(envs.back())) info(w);
  }

  // The output folder is built beside its final name and renamed into place at the end
  // (FolderOutput), so a failed or cancelled demo leaves no half-made folder (an earlier complete
  // one is replaced only once the new one is complete).
  const fs::path out = fs::absolute(a.output);
  FolderOutput folder(a.output, "prt demo");
  const DemoFolder file{folder.path()};
  std::error_code ec;
  for (const char* sub : {"img", "lights", "validation"})
    if (!fs::create_directories(file.root / sub, ec))
      throw Error(out.string(), "cannot create the output folder (" + ec.message() + ")");

  info(fmt::format("demo: {} ({} vertices, {} triangles)", scene.description,
                   scene.mesh.vertexCount(), scene.mesh.triangleCount()));
  const auto tb = Clock::now();
  const auto occluder = makeEmbreeOccluder(scene.mesh);
  const BakeFile bake = bakeModes(scene.mesh, *occluder, a);
  writeBake(file("scene.glb"), bake);
  const double bakeSeconds = since(tb);
  std::optional<GlossyBake> glossy;
  if (glossyMaterial) glossy = bakeGlossy(scene.mesh, *occluder, a, *glossyMaterial, file);

  const render::Camera camera = render::frameMesh(scene.mesh, frame.width, frame.height);
  std::vector<LightResult> lights;
  Json envReports = Json::array();  // --json: per environment, what the page shows
  for (std::size_t li = 0; li < envs.size(); ++li) {
    const auto tl = Clock::now();
    const envmap::Environment& env = envs[li].env;
    const LightScene ls{bake.mesh, *occluder, env, camera, frame, file};
    LightResult L;
    L.spec = envSpecs[li];
    L.name = shortName(L.spec);
    for (const LightResult& other : lights)
      if (other.name == L.name) L.name += "_" + std::to_string(li);
    const sh::RgbSh light = envmap::projectEnvironment(env, a.bands);
    io::LightFile lf;
    lf.coefficients = light;
    lf.source = L.spec;
    lf.layout = envs[li].layout;
    lf.prtkitVersion = kVersion;
    io::writeLightJson(file("lights/" + L.name + ".json"), lf);
    const image::Image preview = envmap::previewPanels(env, light, 512);
    L.preview = "lights/" + L.name + "_preview.png";
    image::writeImage(
        file(L.preview), preview,
        {image::ToneMap::Aces, envmap::previewExposure(preview, image::ToneMap::Aces)});

    // The glossy light: this environment projected at the glossy bands (a light with more bands
    // is cut; one with fewer would leave the matrices' upper columns dark).
    const sh::RgbSh glossyLight =
        glossy && a.glossyBands > a.bands ? envmap::projectEnvironment(env, a.glossyBands) : light;
    std::vector<image::Image> panels;  // per mode: PRT, reference, error (display values)
    for (const BakedTransfer& bt : bake.transfers)
      L.modes.push_back(renderMode(ls, bt, light, L, a, panels));
    if (glossy)
      L.modes.push_back(renderMode(ls, glossy->file.transfers.front(), glossyLight, L, a, panels));
    L.comparison = "img/" + L.name + "_comparison.png";
    image::writeImage(file(L.comparison), render::contactSheet(panels, 3, 4, Rgb(1.0f)),
                      {image::ToneMap::Clamp, 0.0f});
    if (a.frames > 0)
      renderTurntable(ls, *bake.find(TransferMode::Interreflected), light, scene, a, L);
    L.seconds = since(tl);
    info(fmt::format("demo: {} done in {:.1f} s", L.name, L.seconds));
    envReports.push_back(environmentJson(L, light));
    lights.push_back(std::move(L));
  }

  // The per-texel row, under the first environment.
  const TexelRow texels =
      demoTexelRow(envs.front().env, envSpecs.front(), a, frame, file.root.string());
  // The all-frequency row, under the first two.
  std::optional<HaarRow> haarRow;
  if (const BakedTransfer* shadowed = bake.find(TransferMode::Shadowed)) {
    std::vector<const envmap::Environment*> envPtrs;
    for (const auto& e : envs) envPtrs.push_back(&e.env);
    haarRow = demoHaarRow(bake.mesh, *occluder, *shadowed, envPtrs, envSpecs, a, frame, camera,
                          file.root.string());
  }
  Json web;
  const std::string webWhy =
      writeLiveViewer(envSpecs, file, a.output, lights.front().exposure, web);
  const double totalSeconds = since(t0);
  writeDemoPage(file("index.html"), scene, bake, lights, a, bakeSeconds, totalSeconds, webWhy,
                glossy ? &*glossy : nullptr, &texels, haarRow ? &*haarRow : nullptr);
  // Into place: replace an earlier demo folder only now that the new one is complete.
  folder.commit();
  info(
      fmt::format("demo: finished in {:.0f} s; open {}", since(t0), (out / "index.html").string()));

  writeDemoReport(report, {scene, bake, glossy ? &*glossy : nullptr, std::move(envReports),
                           texels, haarRow ? &*haarRow : nullptr, std::move(web), webWhy,
                           bakeSeconds, totalSeconds},
                  a.output, envSpecs);
}

}  // namespace

void addDemoCommand(CLI::App& root) {
  auto a = std::make_shared<DemoArgs>();
  auto* cmd = root.add_subcommand(
      "demo", "Bake, relight, render and validate a default scene into a folder with index.html");
  cmd->add_option("-o,--output", a->output, "Output folder")->capture_default_str();
  cmd->add_option("--mesh", a->mesh,
                  "Mesh file or builtin:NAME (auto: the Stanford bunny from glmark2-data on a "
                  "plane, else builtin:cornell)")
      ->capture_default_str();
  cmd->add_option("--env", a->envs,
                  "Environment (repeatable; default builtin:sky and a Poly Haven map from "
                  "blender-data when installed)");
  cmd->add_option("--bands", a->bands, "SH bands")->capture_default_str();
  cmd->add_option("--samples", a->samples, "Bake directions per vertex")->capture_default_str();
  cmd->add_option("--reference-samples", a->referenceSamples,
                  "Reference Monte Carlo samples per vertex")
      ->capture_default_str();
  cmd->add_option("--bounces", a->bounces, "Inter-reflection bounces")->capture_default_str();
  cmd->add_option("--size", a->size, "Image size WxH")->capture_default_str();
  cmd->add_option("--frames", a->frames, "Turntable frames per environment (0: none)")
      ->capture_default_str();
  cmd->add_option("--glossy", a->glossy,
                  "Material of the glossy rows (shadowed transfer matrices, glossy.glb), or "
                  "none")
      ->capture_default_str();
  cmd->add_option("--glossy-bands", a->glossyBands,
                  "SH bands of the glossy matrices (B⁴ floats per vertex)")
      ->capture_default_str();
  cmd->add_option("--glossy-samples", a->glossySamples, "Bake directions per vertex, glossy")
      ->capture_default_str();
  cmd->add_option("--glossy-reference-samples", a->glossyReferenceSamples,
                  "Reference Monte Carlo samples per vertex, glossy rows")
      ->capture_default_str();
  addJsonOption(cmd, a->json);
  cmd->callback([a] { runDemo(*a); });
}

}  // namespace prt::cli
