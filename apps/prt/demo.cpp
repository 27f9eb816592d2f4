// prt demo: the whole pipeline on a default scene, into a folder a person wants to open.
//
//   prt demo -o demo-out
//   prt demo --mesh bunny.obj --env studio.exr --env builtin:sky -o out
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
// v = normalize(eye − p) per vertex (relight::relightGlossy, as prt render); the brute-force
// reference evaluates the same lobe with no SH (render/reference.hpp), and the table adds the
// fraction of the lobe's energy beyond each band count — what no b-band transfer can hold.
// The matrices go to glossy.glb (the demo's scene.glb stays the small diffuse bake the web page
// loads); prt view and prt render relight it.
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
#include "guard.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
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
#include "prt/render/render.hpp"
#include "prt/render/validate.hpp"
#include "prt/transport/bake.hpp"
#include "web.hpp"

namespace prt::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";
constexpr const char* kPolyHavenDir = "/usr/share/blender/datafiles/studiolights/world";

struct DemoArgs {
  std::string output = "demo-out";
  std::string mesh = "auto";
  std::vector<std::string> envs;
  int bands = 5;
  int samples = 512;
  int referenceSamples = 512;
  int bounces = 1;
  std::string size = "480x360";
  int frames = 12;
  std::string glossy = "phong?exponent=12&ks=0.5&kd=0.5";  ///< "none": no glossy rows
  int glossyBands = 5;
  int glossySamples = 256;
  /// Each glossy reference sample is a diffuse and a glossy one (two rays and more): half the
  /// diffuse modes' count costs about what one of them does.
  int glossyReferenceSamples = 256;
};

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// The demo scene: what was asked, or the bunny on a plane, or the Cornell box; and the sphere
/// the camera frames (the object, not the whole ground plane).
struct Scene {
  Mesh mesh;
  std::string description;
  Vec3f centre{0.0f};
  float radius = 1;
};

Scene makeScene(const std::string& spec) {
  Scene s;
  std::string path = spec;
  if (spec == "auto") path = fs::exists(kBunny) ? kBunny : "builtin:cornell";
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

std::string htmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// Exposure (stops) that puts the median luminance of the relit vertices at 0.3 after exposure
/// (a white object under the sky or a real environment then reads as light grey to white, with
/// the tone map's shoulder left for the brightest parts).
float objectExposure(std::span<const Rgb> radiance) {
  std::vector<float> lum;
  lum.reserve(radiance.size());
  for (const Rgb& c : radiance) lum.push_back(image::luminance(c));
  if (lum.empty()) return 0;
  const auto mid = lum.begin() + static_cast<std::ptrdiff_t>(lum.size() / 2);
  std::nth_element(lum.begin(), mid, lum.end());
  return *mid > 0 ? image::clampExposure(std::log2(0.3f / *mid)) : 0.0f;
}

/// The image as the PNG will show it, still linear: tone mapped (with exposure) and clamped, so
/// pictures with different tone maps can share one contact sheet written with ToneMap::Clamp.
image::Image displayed(image::Image img, const image::WriteOptions& wo) {
  for (Rgb& p : img.pixels) p = image::toneMap(p, wo.toneMap, wo.exposureStops);
  return img;
}

struct ModeResult {
  TransferMode mode;
  bool glossy = false;  ///< matrix transfer with the --glossy material
  double seconds = 0;   ///< validation, relighting and pictures
  render::ValidationReport report;
  float errorScale = 0;
  std::string prtImage, refImage, errImage;
};

struct LightResult {
  std::string spec, name, preview, turntable, comparison;
  std::vector<std::string> frames;
  float exposure = 0;
  std::vector<ModeResult> modes;
  double seconds = 0;
};

/// The glossy bake, when made.
struct GlossyBake {
  BakeFile file;
  Material material;
  double seconds = 0;
  std::size_t bytes = 0;
};

/// "shadowed" or "glossy (shadowed matrix, phong?...)".
std::string modeTitle(const ModeResult& m, const GlossyBake* g) {
  if (!m.glossy || !g) return toString(m.mode);
  return fmt::format("glossy: {} transfer matrices, {}", toString(m.mode), g->material.spec());
}

void writeIndex(const std::string& path, const Scene& scene, const BakeFile& bake,
                const std::vector<LightResult>& lights, const DemoArgs& a, double bakeSeconds,
                double totalSeconds, const std::string& webWhy, const GlossyBake* glossy) {
  std::ostringstream h;
  h << R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>prtkit demo</title>
<style>
body{font-family:system-ui,sans-serif;margin:2em auto;padding:0 2em;max-width:1500px;color:#222;background:#fafafa;line-height:1.4}
h1,h2,h3{font-weight:600} table{border-collapse:collapse;margin:.5em 0}
td,th{border:1px solid #ccc;padding:.25em .6em;text-align:right;font-variant-numeric:tabular-nums}
th{background:#eee} .imgs{display:grid;grid-template-columns:repeat(3,1fr);gap:.6em} figure{margin:0}
figcaption{font-size:.85em;color:#555} img{display:block;max-width:100%} .imgs img{width:100%}
code{background:#eee;padding:0 .2em} .preview{max-width:420px}
.mode{border-top:1px solid #ddd;padding-top:.5em;margin-top:1em} .note{max-width:75em}
</style></head><body>
<h1>prtkit demo</h1>
)";
  // The live viewer (prt web, docs/web.md) above the still images.
  if (webWhy.empty())
    h << "<iframe src=\"web/index.html\" title=\"live viewer\" style=\"width:100%;height:540px;"
         "border:1px solid #ccc;background:#000\"></iframe>\n<p>Live, in this browser (WebGL2): "
         "left-drag orbits, right-drag (or shift-drag) turns the light, the panel switches "
         "environments, transfer modes and bands; drop another <code>.glb</code> bake or SH light "
         "<code>.json</code> on it. <a href=\"web/index.html\">Open it full-window</a>; "
         "<code>prt web scene.glb -o DIR</code> writes the same for any bake.</p>\n";
  else
    h << "<p class=\"note\">(No live viewer here: " << htmlEscape(webWhy) << ")</p>\n";
  h << "<p>Scene: " << htmlEscape(scene.description) << ", " << bake.mesh.vertexCount()
    << " vertices, " << bake.mesh.triangleCount() << " triangles. Baked with " << a.bands
    << " SH bands (" << a.bands * a.bands << " coefficients), " << a.samples
    << " cosine-weighted Sobol' directions per vertex, " << a.bounces
    << " inter-reflection bounce(s), in " << fmt::format("{:.1f}", bakeSeconds)
    << " s. Reference: " << a.referenceSamples
    << " Monte Carlo samples per vertex (environment importance sampling and cosine sampling "
       "combined by MIS), no spherical harmonics anywhere. Total "
    << fmt::format("{:.0f}", totalSeconds) << " s.</p>\n";
  h << "<p class=\"note\">How to read it: every mode should match the reference up to the SH "
       "truncation (the table's <i>truncation floor</i>: the error a perfect transfer of that many "
       "bands would still have) plus noise. <b>Shadowed</b> and "
       "<b>inter-reflected</b> PRT carry only the low-frequency part of visibility × light: "
       "ambient occlusion, soft shadows and colour bleeding come out right, but a sharp sun "
       "shadow is blurred (and can ring) at "
    << a.bands
    << " bands — the error image shows where. Bake more bands (<code>--bands 9</code>) or use "
       "a softer environment to watch it shrink. Errors near the reference's own noise are below "
       "what this comparison can resolve.</p>\n";
  h << "<table><tr><th>mode</th><th>rays</th><th>time</th><th>Mrays/s</th><th>std. error of "
       "T<sub>00</sub> (mean)</th></tr>\n";
  for (const BakedTransfer& t : bake.transfers) {
    if (t.stats.rays == 0) {  // unshadowed: the clamped-cosine lobe in closed form
      h << "<tr><td>" << toString(t.mode())
        << "</td><td colspan=\"4\" style=\"text-align:left\">exact: the clamped-cosine lobe "
           "about the normal, in closed form (no rays)</td></tr>\n";
      continue;
    }
    h << fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{:.2f} s</td><td>{:.1f}</td><td>{:.2e}</td></tr>\n",
        toString(t.mode()), t.stats.rays, t.stats.secondsTotal, t.stats.raysPerSecond / 1e6,
        t.stats.stdErrT0Mean);
  }
  if (glossy) {
    const BakedTransfer& t = glossy->file.transfers.front();
    h << fmt::format(
        "<tr><td>glossy ({} matrices, {} bands, {} samples)</td><td>{}</td><td>{:.2f} s</td>"
        "<td>{:.1f}</td><td>{:.2e}</td></tr>\n",
        toString(t.mode()), t.transfer.bands(), t.recipe.samples, t.stats.rays,
        t.stats.secondsTotal, t.stats.raysPerSecond / 1e6, t.stats.stdErrT0Mean);
  }
  h << "</table>\n";
  double glossySeconds = glossy ? glossy->seconds : 0;
  for (const LightResult& L : lights)
    for (const ModeResult& m : L.modes)
      if (m.glossy) glossySeconds += m.seconds;
  if (glossy)
    h << "<p class=\"note\">Glossy (" << fmt::format("{:.0f}", glossySeconds)
      << " s of the total: the bake, then per environment its reference at "
      << a.glossyReferenceSamples
      << " samples per vertex, each a diffuse and a glossy one, and the pictures): "
         "<code>glossy.glb</code> ("
      << fmt::format("{:.0f}", glossy->bytes / 1e6) << " MB: a " << a.glossyBands * a.glossyBands
      << "×" << a.glossyBands * a.glossyBands
      << " matrix per vertex) holds inter-reflected transfer matrices M<sub>p</sub>, "
         "L'<sub>p</sub> "
         "= M<sub>p</sub>L the light arriving at p, shadowed and bounced "
      << a.bounces << " time(s) off surfaces of the material <code>"
      << htmlEscape(glossy->material.spec())
      << "</code> (glossy bounces: what a surface sends toward p depends on the direction); the "
         "material at p is applied at relighting time, each vertex seen from the stills' camera "
         "(<code>prt view glossy.glb</code> relights it live, <code>prt render glossy.glb "
         "--material ...</code> with another lobe at p). Its reference uses the same lobe, at p "
         "and at every bounce, with no SH, "
         "so the error is SH truncation of visibility, light <i>and</i> lobe (the table's last "
         "column: the lobe's energy beyond b bands) plus noise.</p>\n";
  h << "<p>Files: <code>scene.glb</code> (the bake; any glTF viewer opens it as a mesh), "
       "<code>lights/*.json</code> (SH lighting), <code>validation/*.json</code>. Try "
       "<code>prt render scene.glb --light lights/"
    << (lights.empty() ? "sky" : lights.front().name) << ".json -o mine.png</code>.</p>\n";

  for (const LightResult& L : lights) {
    h << "<h2>" << htmlEscape(L.spec) << "</h2>\n<figure class=\"preview\"><img src=\"" << L.preview
      << "\"><figcaption>The environment (top), its " << a.bands
      << "-band SH reconstruction, and the irradiance/π it gives a white surface.</figcaption>"
         "</figure>\n";
    for (const ModeResult& m : L.modes) {
      const render::ValidationReport& r = m.report;
      h << "<div class=\"mode\"><h3>" << htmlEscape(modeTitle(m, glossy))
        << "</h3><div class=\"imgs\">";
      h << "<figure><img src=\"" << m.prtImage << "\"><figcaption>PRT, " << r.bands
        << " bands</figcaption></figure>";
      h << "<figure><img src=\"" << m.refImage
        << "\"><figcaption>Monte Carlo reference (no SH)</figcaption></figure>";
      h << "<figure><img src=\"" << m.errImage
        << fmt::format(
               "\"><figcaption>relative error per vertex: black 0 … white {:.1f}% "
               "(the reference's own noise: {:.1f}%)",
               100 * m.errorScale, 100 * r.rows.back().refStdErr)
        << "</figcaption></figure></div>\n";
      h << "<table><tr><th>bands</th><th>rel. RMSE</th><th>energy-weighted</th><th>mean rel. "
           "error</th><th>max rel. error</th><th>truncation floor</th><th>reference std. "
           "error</th>"
        << (m.glossy ? "<th>lobe energy &gt; b</th>" : "") << "</tr>\n";
      for (const render::BandRow& row : r.rows)
        h << fmt::format(
                 "<tr><td>{}</td><td>{:.2f}%</td><td>{:.2f}%</td><td>{:.2f}%</td><td>{:.1f}%</td>"
                 "<td>{:.2f}%</td><td>{:.2f}%</td>",
                 row.bands, 100 * row.relRmse, 100 * row.energyRel, 100 * row.meanRel,
                 100 * row.maxRel, 100 * row.floor, 100 * row.refStdErr)
          << (m.glossy ? fmt::format("<td>{:.1f}%</td>", 100 * row.lobeEnergyBeyond) : "")
          << "</tr>\n";
      h << "</table></div>\n";
    }
    h << "<p><a href=\"" << L.comparison
      << "\">All modes in one picture</a> (rows: unshadowed, shadowed, inter-reflected"
      << (glossy ? ", glossy" : "") << "; columns: PRT, reference, error).</p>\n";
    if (!L.frames.empty()) {
      h << "<h3>The light turning about +Y (inter-reflected, SH rotation)</h3>\n<img id=\"turn_"
        << L.name << "\" src=\"" << L.frames.front() << "\"><p><a href=\"" << L.turntable
        << "\">contact sheet</a></p>\n<script>(function(){const f=[";
      for (std::size_t k = 0; k < L.frames.size(); ++k)
        h << (k ? "," : "") << '"' << L.frames[k] << '"';
      h << "];let i=0;const im=document.getElementById(\"turn_" << L.name
        << "\");setInterval(()=>{i=(i+1)%f.length;im.src=f[i];},150);})();</script>\n";
    }
  }
  h << "<p>Made by <code>prt demo</code> (prtkit " << kVersion
    << "). Relative error per vertex: sqrt(Σ<sub>c</sub>(R<sub>PRT</sub>−R<sub>ref</sub>)² / "
       "Σ<sub>c</sub>(R<sub>ref</sub>² + ε)); energy-weighted: ‖R<sub>PRT</sub>−R<sub>ref</sub>‖ / "
       "‖R<sub>ref</sub>‖ over all vertices; the truncation floor is the error a perfect "
       "transfer would still have at that band count: R(L − L<sub>b</sub>), by quadrature "
       "(unshadowed) or by the reference run with the residual light (shadowed, inter-reflected; "
       "see docs/validation.md).</p>\n"
       "</body></html>\n";
  writeFileAtomically(path, h.str());
}

void runDemo(const DemoArgs& a) {
  const auto t0 = Clock::now();
  if (a.bands < 1 || a.bands > bands::kMaxBake)
    throw Error(fmt::format("--bands {}: must be 1..{}", a.bands, bands::kMaxBake));
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
  std::optional<Material> glossyMaterial;
  if (a.glossy != "none") {
    glossyMaterial = parseMaterial(a.glossy);
    if (!glossyMaterial->glossy())
      throw Error(
          fmt::format("--glossy '{}': no glossy lobe (use 'none' for no glossy rows)", a.glossy));
  }
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

  // Inputs first: a bad mesh or environment fails before anything is written.
  const Scene scene = makeScene(a.mesh);
  std::vector<envmap::LoadedEnvironment> envs;
  for (const std::string& spec : envSpecs) {
    envs.push_back(envmap::loadEnvironment(spec));
    const envmap::LoadedEnvironment& e = envs.back();
    for (const std::string& w : envmap::repairWarnings(e)) info(w);
  }

  // The output folder is built beside its final name and renamed into place at the end
  // (FolderOutput), so a failed or cancelled demo leaves no half-made folder (an earlier complete
  // one is replaced only once the new one is complete).
  const fs::path out = fs::absolute(a.output);
  FolderOutput folder(a.output, "prt demo");
  const fs::path tmp = folder.path();
  std::error_code ec;
  if (!fs::create_directories(tmp / "img", ec) || !fs::create_directories(tmp / "lights", ec) ||
      !fs::create_directories(tmp / "validation", ec))
    throw Error(out.string(), "cannot create the output folder (" + ec.message() + ")");
  const auto file = [&](const std::string& rel) { return (tmp / rel).string(); };

  info(fmt::format("demo: {} ({} vertices, {} triangles)", scene.description,
                   scene.mesh.vertexCount(), scene.mesh.triangleCount()));

  // Bake the three modes into one file.
  const auto tb = Clock::now();
  BakeFile bake;
  bake.mesh = scene.mesh;
  const auto occluder = makeEmbreeOccluder(bake.mesh);
  for (TransferMode mode :
       {TransferMode::Unshadowed, TransferMode::Shadowed, TransferMode::Interreflected}) {
    BakeSettings s;
    s.mode = mode;
    s.bands = a.bands;
    s.samples = a.samples;
    s.bounces = a.bounces;
    s.bounces = s.effectiveBounces();
    BakedTransfer t;
    t.recipe = s;
    t.transfer = prt::bake(bake.mesh, *occluder, s, &t.stats,
                           progressBar(std::string("bake ") + toString(mode)));
    info(fmt::format("demo: baked {} in {:.2f} s ({} rays)", toString(mode), t.stats.secondsTotal,
                     t.stats.rays));
    bake.transfers.push_back(std::move(t));
  }
  writeBake(file("scene.glb"), bake);
  const double bakeSeconds = since(tb);

  // The glossy bake: inter-reflected transfer matrices (glossy bounces), in a file of their own.
  std::optional<GlossyBake> glossy;
  if (glossyMaterial) {
    const auto tg = Clock::now();
    glossy.emplace();
    glossy->material = *glossyMaterial;
    BakeFile& g = glossy->file;
    g.mesh = bake.mesh;
    BakeSettings s;
    s.mode = TransferMode::Interreflected;
    s.bounces = a.bounces;
    s.layout = TransferLayout::Matrix;
    s.bands = a.glossyBands;
    s.samples = a.glossySamples;
    s.material = *glossyMaterial;
    BakedTransfer t;
    t.recipe = s;
    t.transfer = prt::bake(g.mesh, *occluder, s, &t.stats, progressBar("bake glossy"));
    g.transfers.push_back(std::move(t));
    writeBake(file("glossy.glb"), g);
    glossy->bytes = fs::file_size(file("glossy.glb"));
    glossy->seconds = since(tg);
    info(fmt::format("demo: baked glossy matrices ({} bands) in {:.2f} s, glossy.glb {:.0f} MB",
                     a.glossyBands, glossy->seconds, glossy->bytes / 1e6));
  }

  render::Camera camera =
      render::frameSphere(scene.centre, scene.radius, frame.width, frame.height);
  std::vector<LightResult> lights;
  for (std::size_t li = 0; li < envs.size(); ++li) {
    const auto tl = Clock::now();
    const envmap::Environment& env = envs[li].env;
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
    const image::Image panels = envmap::previewPanels(env, light, 512);
    L.preview = "lights/" + L.name + "_preview.png";
    image::writeImage(file(L.preview), panels,
                      {image::ToneMap::Aces, envmap::previewExposure(panels)});

    const render::BackgroundFn background = render::environmentBackground(env, Mat3d::identity());
    std::vector<image::Image> panels3;  // per mode: PRT, reference, error (display values)
    std::vector<const BakedTransfer*> rows;
    for (const BakedTransfer& bt : bake.transfers) rows.push_back(&bt);
    if (glossy) rows.push_back(&glossy->file.transfers.front());
    // The glossy light: this environment projected at the glossy bands (relightGlossy and
    // validate cut a light with more bands; one with fewer would leave the matrices' upper
    // columns dark).
    const sh::RgbSh glossyLight =
        glossy && a.glossyBands > a.bands ? envmap::projectEnvironment(env, a.glossyBands) : light;
    for (const BakedTransfer* btp : rows) {
      const BakedTransfer& bt = *btp;
      const auto tm = Clock::now();
      ModeResult m;
      m.mode = bt.mode();
      m.glossy = bt.transfer.isMatrix();
      const std::string key = m.glossy ? "glossy" : toString(m.mode);
      render::ValidateSettings vs;
      vs.reference.samples = m.glossy ? a.glossyReferenceSamples : a.referenceSamples;
      // Glossy: PRT and reference see each vertex from the stills' camera.
      if (m.glossy) vs.reference.eye = camera.eye;
      const sh::RgbSh& lightHere = m.glossy ? glossyLight : light;
      m.report = render::validate(bake.mesh, *occluder, bt.transfer, bt.recipe, env, lightHere, vs,
                                  progressBar(fmt::format("reference {} {}", L.name, key)));
      writeFileAtomically(file(fmt::format("validation/{}_{}.json", L.name, key)),
                          render::reportJson(m.report));
      const std::vector<Rgb> relit =
          relight::relight(bt.transfer, lightHere, bt.recipe.material,
                           {bake.mesh.positions, bake.mesh.normals, bake.mesh.albedo}, camera.eye);
      // One exposure per environment, from its unshadowed (brightest) relighting, so every picture
      // under it compares directly.
      if (m.mode == TransferMode::Unshadowed) L.exposure = objectExposure(relit);
      const image::WriteOptions wo{image::ToneMap::Aces, L.exposure};
      const std::string base = fmt::format("img/{}_{}", L.name, key);
      const auto save = [&](const std::string& name, const image::Image& img,
                            const image::WriteOptions& opts) {
        panels3.push_back(displayed(img, opts));
        image::writeImage(file(name), panels3.back(), {image::ToneMap::Clamp, 0.0f});
        return name;
      };
      m.prtImage =
          save(base + "_prt.png",
               render::renderRelit(bake.mesh, *occluder, relit, camera, frame, background), wo);
      std::vector<Rgb> reference(bake.mesh.vertexCount());
      for (std::size_t i = 0; i < m.report.reference.vertices.size(); ++i)
        reference[m.report.reference.vertices[i]] = m.report.reference.radiance[i];
      m.refImage =
          save(base + "_ref.png",
               render::renderRelit(bake.mesh, *occluder, reference, camera, frame, background), wo);
      const std::vector<Rgb> colours =
          render::vertexErrorColours(bake.mesh, m.report, &m.errorScale);
      m.errImage = save(base + "_err.png",
                        render::renderRelit(bake.mesh, *occluder, colours, camera, frame,
                                            render::colourBackground(Rgb(0.0f))),
                        {image::ToneMap::Clamp, 0.0f});
      const render::BandRow& last = m.report.rows.back();
      info(
          fmt::format("demo: {} {}: rel. RMSE {:.2f}% at {} bands (floor {:.2f}%, reference "
                      "std. error {:.2f}%; reference {:.1f} s, all {:.1f} s)",
                      L.name, key, 100 * last.relRmse, last.bands, 100 * last.floor,
                      100 * last.refStdErr, m.report.reference.seconds, since(tm)));
      m.seconds = since(tm);
      L.modes.push_back(std::move(m));
    }

    L.comparison = "img/" + L.name + "_comparison.png";
    image::writeImage(file(L.comparison), render::contactSheet(panels3, 3, 4, Rgb(1.0f)),
                      {image::ToneMap::Clamp, 0.0f});

    // The light turning once about +Y: SH rotation of the light, the background with it.
    if (a.frames > 0) {
      const BakedTransfer& bt = *bake.find(TransferMode::Interreflected);
      render::FrameSettings small = frame;
      small.width = frame.width * 2 / 3;
      small.height = frame.height * 2 / 3;
      const render::Camera cam =
          render::frameSphere(scene.centre, scene.radius, small.width, small.height);
      std::vector<image::Image> sheet;
      relight::Relighter relighter(bt.transfer,
                                   {bake.mesh.positions, bake.mesh.normals, bake.mesh.albedo});
      relighter.setMaterial(bt.recipe.material);
      for (int k = 0; k < a.frames; ++k) {
        const Mat3d rot = rotationAxisAngle({0, 1, 0}, 2 * kPi * k / a.frames);
        const std::span<const Rgb> relit = relighter.relight(light, rot, cam.eye);
        image::Image img = render::renderRelit(bake.mesh, *occluder, relit, cam, small,
                                               render::environmentBackground(env, rot));
        const std::string name = fmt::format("img/{}_turn_{:02d}.png", L.name, k);
        image::writeImage(file(name), img, {image::ToneMap::Aces, L.exposure});
        L.frames.push_back(name);
        sheet.push_back(std::move(img));
      }
      L.turntable = "img/" + L.name + "_turntable.png";
      image::writeImage(file(L.turntable), render::contactSheet(sheet, 4),
                        {image::ToneMap::Aces, L.exposure});
    }
    L.seconds = since(tl);
    info(fmt::format("demo: {} done in {:.1f} s", L.name, L.seconds));
    lights.push_back(std::move(L));
  }

  // The live viewer: prt web's folder for the same bake and environments, in web/.
  std::string webWhy;
  if (webAssetsAvailable(&webWhy)) {
    WebOptions w;
    w.bake = file("scene.glb");
    w.envs = envSpecs;
    w.output = file("web");
    w.mode = "interreflected";
    // The stills' framing: the object, not the whole ground plane.
    const render::Camera c = render::frameSphere(scene.centre, scene.radius, 640, 480);
    w.camera = fmt::format("eye={},{},{};target={},{},{}", c.eye.x, c.eye.y, c.eye.z, c.target.x,
                           c.target.y, c.target.z);
    writeWebViewer(w);
  } else {
    warn("demo: no live viewer on the page: " + webWhy);
  }

  writeIndex(file("index.html"), scene, bake, lights, a, bakeSeconds, since(t0), webWhy,
             glossy ? &*glossy : nullptr);

  // Into place: replace an earlier demo folder only now that the new one is complete.
  folder.commit();
  info(
      fmt::format("demo: finished in {:.0f} s; open {}", since(t0), (out / "index.html").string()));
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
  cmd->callback([a] { runDemo(*a); });
}

}  // namespace prt::cli
