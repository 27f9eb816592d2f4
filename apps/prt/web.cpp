// prt web: writes the browser viewer (web/, docs/web.md) for a bake into a folder that works
// opened straight from disk (file://, no server) and from any static web server.
//
//   prt web bunny.glb --env studio.exr --env builtin:sky -o bunny-web/
//   prt web bunny.glb -o bunny-web/ --json web.json       (what it wrote and what the page draws)
//   prt web boxm.glb --encoding l1 -o boxm-web/            (a matrix bake as an engine's L1 shows
//   it)
//
// The folder: index.html and prt-web.js (the page and its bundled JavaScript: three.js, lil-gui,
// the shared GLSL; built from web/ by CMake with esbuild, see web/build.mjs), and prt-data.js,
// written here: `window.PRT_DATA = {...}` holding the bake (.glb bytes, base64), each
// environment's SH coefficients at the bake's bands and a small lat-long background (RGBE,
// base64); and three/, the three.js example (prtkit-three, docs/three.md), which shows the same
// bake and environments from ../prt-data.js in an ordinary three.js scene. Classic <script>
// files because Chromium refuses fetch() and ES-module imports of file:// URLs.

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "args.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/json.hpp"
#include "prt/core/options.hpp"
#include "prt/core/version.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/preview.hpp"
#include "prt/envmap/project.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/haar/turned_cube.hpp"
#include "prt/image/color.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relight_haar.hpp"
#include "prt/relight/shader_transfer.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/exposure.hpp"
#include "prt/render/haar_shader.hpp"
#include "prt/render/probe_shading.hpp"
#include "prt/render/relit_view.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/sh/irradiance_encoding.hpp"
#include "prt/transfer/prepared_material.hpp"
#include "report.hpp"
#include "transfer_options.hpp"
#include "web.hpp"
#include "web_report.hpp"

namespace prt::cli {

namespace {

namespace fs = std::filesystem;

/// The page's built assets (index.html, prt-web.js): $PRT_WEB_ASSETS, else
/// <exe>/../share/prtkit/web (installed), else the build tree's web/ (PRT_WEB_ASSETS_DIR, set by
/// CMake).
fs::path findAssets() {
  std::vector<fs::path> tried;
  if (const char* env = std::getenv("PRT_WEB_ASSETS")) tried.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) tried.push_back(exe.parent_path().parent_path() / "share" / "prtkit" / "web");
#ifdef PRT_WEB_ASSETS_DIR
  tried.emplace_back(PRT_WEB_ASSETS_DIR);
#endif
  for (const fs::path& p : tried)
    if (fs::is_regular_file(p / "prt-web.js") && fs::is_regular_file(p / "index.html")) return p;
  std::string where;
  for (const fs::path& p : tried) where += (where.empty() ? "" : ", ") + p.string();
  throw Error(fmt::format(
      "the browser viewer's assets (index.html, prt-web.js) are not built (looked in {}); run "
      "scripts/setup.sh, which installs web/node_modules with npm, then rebuild (ninja "
      "prt_web_assets), or set PRT_WEB_ASSETS",
      where.empty() ? "nowhere" : where));
}

std::string base64(const void* data, std::size_t n) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < n; i += 3) {
    const unsigned v = (p[i] << 16) | (p[i + 1] << 8) | p[i + 2];
    out += k[v >> 18], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += k[v & 63];
  }
  if (i + 1 == n) {
    const unsigned v = p[i] << 16;
    out += k[v >> 18], out += k[(v >> 12) & 63], out += "==";
  } else if (i + 2 == n) {
    const unsigned v = (p[i] << 16) | (p[i + 1] << 8);
    out += k[v >> 18], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += '=';

  }
  return out;
}

/// `spec` for the page: its SH at `bands`, its background and, for a Haar bake over an N =
/// `haarResolution` cube (0: an SH bake), the cube the page turns the light from.
WebEnvironment loadEnvironment(const std::string& spec, int bands, int width, int haarResolution) {
  io::Lighting l = io::loadLighting(spec, bands, progressBar("projecting"));
  for (const std::string& w : l.warnings) warn(w);
  WebEnvironment e;
  e.spec = spec;
  // What the page's menu shows: a file's name, not the folders it was found in (a build
  // machine's absolute path means nothing to whoever opens the page); builtin:NAME as it is.
  e.name = envmap::isBuiltin(spec) ? spec : fs::path(spec).filename().string();
  if (e.name.empty()) e.name = fs::path(spec).parent_path().filename().string();  // "faces/"
  // The page always reads the bake's bands: a light with fewer is padded with zeros (the
  // transfer's upper bands see no light, as the warning says).
  e.light = io::padded(l.coefficients, bands);
  if (l.isShFile()) {
    e.background = envmap::renderSh(l.coefficients, width);
    for (Rgb& p : e.background.pixels) p = max(p, Rgb(0.0f));
  } else {
    e.background = envmap::renderEnvironment(*l.image, width);
  }
  if (haarResolution > 0) {
    if (l.isShFile())
      throw Error(spec,
                  "is an SH light file, and the bake holds Haar transfer, relit from an "
                  "environment: give an image, a face folder or builtin:NAME");
    e.haar = haar::environmentCube(*l.image, haarResolution);
  }
  return e;
}

/// Radiance RGBE (Ward, "Real Pixels", Graphics Gems II, 1991): a shared exponent and three
/// 8-bit mantissas, 4 bytes a pixel (a float32 RGB lat-long is 3× larger, and half floats
/// overflow at a sun's radiance). Relative precision ~1/256 of the largest channel.
std::vector<unsigned char> encodeRgbe(const image::Image& img) {
  std::vector<unsigned char> out(img.pixels.size() * 4, 0);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const Rgb p = max(img.pixels[i], Rgb(0.0f));
    const float v = std::max({p.x, p.y, p.z});
    if (!(v >= 1e-32f) || !std::isfinite(v)) continue;
    int e = 0;
    const float scale = std::frexp(v, &e) * 256.0f / v;
    if (e + 128 > 255) e = 127;
    out[4 * i] = static_cast<unsigned char>(std::min(255.0f, p.x * scale));
    out[4 * i + 1] = static_cast<unsigned char>(std::min(255.0f, p.y * scale));
    out[4 * i + 2] = static_cast<unsigned char>(std::min(255.0f, p.z * scale));
    out[4 * i + 3] = static_cast<unsigned char>(e + 128);
  }
  return out;
}

std::string readText(const fs::path& p) {
  const std::vector<unsigned char> b = readFileBytes(p.string());
  return std::string(b.begin(), b.end());
}

}  // namespace

bool webAssetsAvailable(std::string* why) {
  try {
    findAssets();
    return true;
  } catch (const Error& e) {
    if (why) *why = e.what();
    return false;
  }
}

namespace {

/// Everything cheap, before any work, so errors come at once and nothing is written.
void checkOptions(const WebOptions& a) {
  parseEulerDegrees(a.rotate);
  image::parseToneMap(a.toneMap);
  if (a.exposure) image::checkExposure(*a.exposure, "--exposure");
  if (a.backgroundWidth < 8 || a.backgroundWidth > 8192 || a.backgroundWidth % 2)
    throw Error("--background-width must be an even number of pixels in 8..8192");
  if (a.bands != 0) checkOptionRange(OptionSpelling::Cli, "bands", a.bands, 1, bands::kMaxLibrary);
  if (a.terms != 0)
    checkOptionRange(OptionSpelling::Cli, "terms", a.terms, 1,
                     long(haar::coefficientCount(haar::kMaxTurnedResolution)));
  if (a.embed != "auto" && a.embed != "always" && a.embed != "never")
    throw Error("--embed '" + a.embed + "': expected auto, always or never");
  if (!a.material.empty()) parseMaterial(a.material);
  if (!a.encoding.empty() && a.encoding != "none") sh::parseIrradianceEncoding(a.encoding);
}

bool perVertexMatrix(const Transfer& t) {
  return t.isMatrix() && t.domain() == TransferDomain::Vertices;
}

/// The encoding the page opens the picked transfer `t` drawn through (the page's shownEncoding,
/// web/src/encoded_diffuse.js): --encoding for a per-vertex matrix transfer, l2 for dense ones
/// without it (the page draws those on the CPU only), else none.
std::optional<sh::IrradianceEncoding> openingEncoding(const WebOptions& a, const Transfer& t) {
  if (!perVertexMatrix(t)) return std::nullopt;
  if (!a.encoding.empty() && a.encoding != "none") return sh::parseIrradianceEncoding(a.encoding);
  if (!t.compressed()) return sh::IrradianceEncoding::L2;
  return std::nullopt;
}

/// A Haar bake (docs/haar.md), relit by the page on the CPU under a light it turns from each
/// environment's finer cube (haar/turned_cube.hpp, web/src/haar_light.js) — per vertex, or per
/// texel at the texels' normals prt web ships beside it (texelPointsFor): complete, over a cube
/// of at most kMaxTurnedResolution² a face, without a base-colour texture (prt render folds it
/// into the vertices' albedo, which the page cannot: it does not read a texture's pixels), and
/// without the options that shape SH transfer.
void checkHaarForPage(const WebOptions& a, const BakeFile& bake) {
  bake.requireComplete(a.bake);
  const int n = bake.transfers.front().transfer.shape().haar.resolution;
  if (n > haar::kMaxTurnedResolution)
    throw Error(a.bake, fmt::format("holds Haar transfer over a {0}² cube; the page turns its "
                                    "light from a cube {1} times finer and takes cubes up to "
                                    "{2}² (bake with --resolution {2} or less, or view it with "
                                    "prt view)",
                                    n, haar::kFineCubeFactor, haar::kMaxTurnedResolution));
  if (bake.mesh.baseColour)
    throw Error(a.bake,
                "holds Haar transfer on a mesh with a base-colour texture, which prt "
                "render folds into the vertices' albedo (per texel, multiplies per pixel); the "
                "page does not read a texture's pixels for Haar bakes (view it with prt view)");
  if (!a.encoding.empty() && a.encoding != "none")
    throw Error(a.bake,
                "holds Haar transfer: --encoding draws a matrix transfer through an "
                "irradiance encoding");
  if (a.bands != 0)
    throw Error(a.bake,
                "holds Haar transfer: --bands cuts SH transfer (--terms sets the light's "
                "wavelet terms)");
  if (!a.material.empty())
    throw Error(a.bake,
                "holds Haar transfer, which is diffuse: --material shades glossy "
                "matrices");
}

/// The bake, validated here (one clear line now rather than on the page): complete, and every
/// transfer on a GPU path of relight/shader_transfer.hpp — vectors (dense or compressed; per
/// vertex, or per texel relit per pixel) and compressed matrices (per vertex, or per texel
/// shaded at the texels' points, texelPointsBytes) — or dense per-vertex matrices, which the
/// page relights on the CPU and draws through an irradiance encoding (l2 unless --encoding
/// names one). Dense per-texel matrices are refused, as the page refuses such a file dropped on
/// it. A probe grid (docs/probes.md) is relit on the CPU, any form. --encoding is refused, as
/// prt render --encoding refuses it, where the picked transfer is not a per-vertex matrix. A
/// file beyond what the page takes is refused before it is read.
std::vector<unsigned char> readBakeForPage(const WebOptions& a, BakeFile& bake) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(a.bake, ec);
  if (!ec && size > kMaxPageBakeBytes)
    throw Error(a.bake, fmt::format("{:.0f} MB is more than the browser viewer takes ({:.0f} MB: "
                                    "its transfer goes to the GPU as float textures); compress "
                                    "it (prt compress: CPCA, typically 10x smaller) or bake "
                                    "fewer bands",
                                    double(size) / 1e6, double(kMaxPageBakeBytes) / 1e6));
  std::vector<unsigned char> glb = readFileBytes(a.bake, kMaxPageBakeBytes, "the page's limit");
  bake = decodeBake(glb, a.bake);
  // A probe grid's matrices are relit on the CPU, in JavaScript (web/src/probe_lighting.js):
  // any bands, dense or compressed. What the page shades with them is diffuse.
  if (bake.domain() == TransferDomain::Probes && !a.material.empty())
    throw Error(a.bake,
                "holds a probe grid, which lights what moves through it diffusely; "
                "--material belongs to a surface's transfer");
  const bool encoding = !a.encoding.empty() && a.encoding != "none";
  if (!bake.transfers.empty() && bake.transfers.front().transfer.isHaar()) {
    checkHaarForPage(a, bake);
    return glb;
  }
  if (a.terms != 0)
    throw Error(a.bake,
                "--terms sets the light's wavelet terms of a Haar bake; this one holds SH "
                "transfer");
  if (encoding && bake.domain() == TransferDomain::Probes)
    throw Error(a.bake,
                "holds a probe grid: --encoding draws a surface's matrix transfer through an "
                "irradiance encoding (prt bake --transfer matrix)");
  for (const BakedTransfer& t : bake.transfers) {
    if (t.transfer.domain() == TransferDomain::Probes) continue;
    if (t.transfer.isMatrix() && !t.transfer.compressed() &&
        t.transfer.domain() == TransferDomain::Texels)
      throw Error(a.bake, fmt::format("the {} transfer holds dense glossy matrices per texel; the "
                                      "browser viewer draws them CPCA-compressed only (prt "
                                      "compress), or view them with prt view",
                                      toString(t.mode())));
    if (perVertexMatrix(t.transfer) && !t.transfer.compressed()) continue;  // on the CPU
    try {
      relight::shaderPath(t.transfer, true);
    } catch (const Error& e) {
      throw Error(a.bake, std::string(e.what()) + " (" + t.describe() + ")");
    }
  }
  if (bake.transfers.empty())
    throw Error(a.bake, "the bake holds no transfer (bake it with prt bake --mode ...)");
  bake.requireComplete(a.bake);
  bake.requireSh(a.bake, "the page relights SH transfer");
  std::optional<TransferMode> mode;
  if (!a.mode.empty()) mode = parseTransferMode(a.mode);
  const BakedTransfer& picked = prt::pickTransfer(bake, mode, {}, a.bake);
  if (encoding && !picked.transfer.isMatrix())
    throw Error(a.bake, "holds " + picked.describe() +
                            " transfer: --encoding encodes the light arriving at each row, which "
                            "a matrix bake holds (prt bake --transfer matrix); vector (diffuse) "
                            "transfer has already integrated it against the normal");
  if (encoding && !perVertexMatrix(picked.transfer))
    throw Error(a.bake, "holds " + picked.describe() +
                            " transfer: the browser viewer draws --encoding per vertex only (prt "
                            "render --encoding draws it per texel)");
  // A base-colour texture stays in the file: the page multiplies it per pixel, as prt render.
  return glb;
}

/// Per-texel glossy matrices are shaded at each texel's own sample point, normal and albedo,
/// and per-texel Haar rows relit at each texel's normal (render::texelRelight, what prt render
/// and prt view relight them at), which the page cannot compute (the inside-geometry probe
/// traces rays): prt web ships them beside the bake as render::packTexelPoints' texels, three
/// RGBA32F texels a lightmap texel. Empty when no transfer needs them. Their albedo leaves the
/// base-colour texture out: the page multiplies it per pixel.
std::vector<float> texelPointsFor(const BakeFile& bake) {
  for (const BakedTransfer& t : bake.transfers)
    if (std::vector<float> points = render::shadingPoints(bake.mesh, t.transfer, t.recipe.material);
        !points.empty())
      return points;
  return {};
}

Json vec3(const Vec3f& v) {
  return jsonFloats(&v.x, 3);
}

/// render::relitSurvey of a matrix transfer drawn through an irradiance encoding at 640x480, as
/// prt render --encoding draws it: the material's diffuse part (what the page draws of it).
render::FrameSurvey encodedSurvey(const Mesh& mesh, const Transfer& transfer, Material material,
                                  sh::IrradianceEncoding encoding, const sh::RgbSh& light,
                                  const Mat3d& rotation, const render::Camera& camera,
                                  image::ToneMap op, int bands) {
  material.specular = Rgb(0.0f);
  const auto occluder = makeEmbreeOccluder(mesh);
  render::RelitView view(mesh, *occluder, transfer, material);
  if (bands > 0 && bands < transfer.bands()) view.setBands(bands);
  view.setEncoding(encoding);
  view.relight(light, rotation, camera.eye, mesh.source);
  return render::surveyFrame(*occluder, view.shader(), camera, 640, 480, op);
}

/// A Haar bake's light terms on the page: --terms, else the viewers' default.
std::size_t haarLightTerms(const WebOptions& a) {
  return a.terms > 0 ? std::size_t(a.terms) : haar::kDefaultLightTerms;
}

/// The initial view. The camera from the library's numbers only (docs/conventions.md,
/// "Camera"): the default framing (render::meshFraming: the bounding sphere, view direction,
/// up, fov, margin), which the page turns into frameCamera's camera for its canvas, and
/// --camera's eye, target, up and fov (keys not given come from the default framing at
/// 640x480), which it uses as they are.
/// The exposure the page opens at: --exposure, else the auto exposure of what it first shows
/// (the picked transfer under the first environment, the initial rotation and camera at 640x480).
float initialExposure(const WebOptions& a, const BakeFile& bake, const WebEnvironment& env) {
  if (a.exposure) return *a.exposure;
  const sh::RgbSh& light = env.light;
  std::optional<TransferMode> mode;
  if (!a.mode.empty()) mode = parseTransferMode(a.mode);
  const BakedTransfer& t = prt::pickTransfer(bake, mode, {}, a.bake);
  const Material material =
      t.transfer.isMatrix() && !a.material.empty() ? parseMaterial(a.material) : t.recipe.material;
  const render::Framing f = render::meshFraming(bake.mesh);
  render::Camera c = render::frameCamera(f, 640, 480);
  if (!a.camera.empty()) c = render::parseCamera(a.camera, c);
  const image::ToneMap op = image::parseToneMap(a.toneMap);
  if (t.transfer.isHaar()) {
    // The light the page turns from the environment's cube, relit as prt render relights a Haar
    // bake (render/haar_shader.hpp).
    const haar::HaarLight l = haar::turnedLight(*env.haar, t.transfer.shape().haar.resolution,
                                                haarLightTerms(a), parseRotation(a.rotate));
    const auto occluder = makeEmbreeOccluder(bake.mesh);
    std::vector<Rgb> radiance;
    const render::ShadeFn shade =
        render::haarShader(bake.mesh, *occluder, t.transfer, material, l, radiance, a.bake);
    return render::surveyFrame(*occluder, shade, c, 640, 480, op).exposureStops;
  }
  // A probe grid: the scene lit through its relit probes (what the page draws around the ball).
  const std::optional<sh::IrradianceEncoding> encoding = openingEncoding(a, t.transfer);
  const render::FrameSurvey survey =
      bake.domain() == TransferDomain::Probes
          ? render::probeSurvey(bake.mesh, t.transfer, light, parseRotation(a.rotate), c, 640, 480,
                                op, a.bands)
      : encoding ? encodedSurvey(bake.mesh, t.transfer, material, *encoding, light,
                                 parseRotation(a.rotate), c, op, a.bands)
                 : render::relitSurvey(bake.mesh, t.transfer, material, light,
                                       parseRotation(a.rotate), c, 640, 480, op, a.bands);
  const std::string ringing = render::negativeRadianceWarning(survey.negativeShare);
  if (!ringing.empty()) warn(ringing + " (the page's first view)");
  return survey.exposureStops;
}

Json viewJson(const WebOptions& a, const Mesh& mesh, float exposure) {
  const std::array<double, 3> euler = parseEulerDegrees(a.rotate);
  const render::Framing f = render::meshFraming(mesh);
  Json camera = nullptr;
  if (!a.camera.empty()) {
    const render::Camera c = render::parseCamera(a.camera, render::frameCamera(f, 640, 480));

    camera = {{"eye", vec3(c.eye)},
              {"target", vec3(c.target)},
              {"up", vec3(c.up)},
              {"fov", jsonFloat(c.fovY)}};
  }
  return {{"rotate", Json::array({euler[0], euler[1], euler[2]})},
          {"exposure", jsonFloat(exposure)},
          {"tonemap", a.toneMap},
          {"mode", a.mode},
          {"encoding", a.encoding.empty() ? "none" : a.encoding},
          {"bands", a.bands},
          {"terms", haarLightTerms(a)},
          {"camera", camera},
          {"framing",
           {{"centre", vec3(f.centre)},
            {"radius", jsonFloat(f.radius)},
            {"direction", vec3(f.direction)},
            {"up", vec3(f.up)},
            {"fov", jsonFloat(f.fovY)},
            {"margin", jsonFloat(f.margin)}}}};
}

/// Glossy matrices: the bake's material (or --material) as the page's shader takes it (kernels
/// times the SH normalisation its basis leaves out, relight::shaderKernel), per mode; drawn
/// through an irradiance encoding (dense ones always), their kd, and a warning when a lobe is
/// left out.
Json glossyJson(const WebOptions& a, const BakeFile& bake) {
  Json out = Json::object();
  // --encoding, checked by checkOptions ("" for none).
  const std::string asked = a.encoding == "none" ? "" : a.encoding;
  for (const BakedTransfer& t : bake.transfers) {
    if (!t.transfer.isMatrix() || t.transfer.domain() == TransferDomain::Probes) continue;
    const Material material =
        materialOption(a.material, t, a.bake,
                       "the page shades each vertex with --material, the bounced light keeps the "
                       "bake's");
    const bool dense = perVertexMatrix(t.transfer) && !t.transfer.compressed();
    if (material.glossy() && (dense || (!asked.empty() && perVertexMatrix(t.transfer))))
      warn(
          fmt::format("{}: the page draws the {} matrices' diffuse part through {} irradiance "
                      "(an encoding holds irradiance): the lobe of {} is left out{}",
                      a.bake, toString(t.mode()), asked.empty() ? "l2" : asked, material.spec(),
                      dense ? " (prt compress them to see it)" : ""));
    if (!dense) warnLobeEnergyLoss(material, t.transfer.bands(), a.bake);
    const PreparedMaterial pm = prepareMaterial(material, t.transfer.bands());
    const std::array<float, 64> diffuse = relight::shaderKernel(pm.diffuse),
                                lobe = relight::shaderKernel(pm.glossy);
    out[toString(t.mode())] = {{"material", material.spec()},
                               {"diffuse", jsonFloats(diffuse.data(), diffuse.size())},
                               {"lobe", jsonFloats(lobe.data(), lobe.size())},
                               {"kd", pm.kd ? jsonFloats(&pm.kd->x, 3) : Json(nullptr)},
                               {"ks", jsonFloats(&pm.specular.x, 3)}};
  }
  return out;
}

Json environmentJson(const WebEnvironment& e) {
  Json coefficients = Json::array();
  for (const Rgb& c : e.light.c) coefficients.push_back(jsonFloats(&c.x, 3));
  const std::vector<unsigned char> rgbe = encodeRgbe(e.background);
  Json j = {{"name", e.name},
            {"bands", e.light.bands},
            {"coefficients", std::move(coefficients)},
            {"background",
             {{"width", e.background.width},
              {"height", e.background.height},
              {"rgbe", base64(rgbe.data(), rgbe.size())}}}};
  if (e.haar) {
    // The cube a Haar bake's light is turned from: its 6 M² texel means as RGBE (face by face,
    // row by row: cube_haar.hpp's order) and its SH at kUnshadowedBands.
    image::Image means(e.haar->resolution, 6 * e.haar->resolution);
    means.pixels = e.haar->means;
    const std::vector<unsigned char> cube = encodeRgbe(means);
    Json sh = Json::array();
    for (const Rgb& c : e.haar->sh.c) sh.push_back(jsonFloats(&c.x, 3));
    j["haar"] = {{"resolution", e.haar->resolution},
                 {"rgbe", base64(cube.data(), cube.size())},
                 {"sh", std::move(sh)}};
  }
  return j;
}

}  // namespace

Json writeWebViewer(const WebOptions& a) {
  checkOptions(a);
  const fs::path assets = findAssets();
  // The folder is written as a whole (FolderOutput) and replaces only an empty folder or one
  // prt web made; no input may lie inside it.
  {
    std::vector<NamedPath> inputs = {{"input", a.bake}};
    for (const std::string& e : a.envs) inputs.push_back({"--env", e});
    checkOutputFolder({"-o", a.output}, inputs);
  }
  checkFolderReplaceable(a.output, "prt web");

  BakeFile bake;
  const std::vector<unsigned char> glb = readBakeForPage(a, bake);
  int bands = 0;
  for (const BakedTransfer& t : bake.transfers) bands = std::max(bands, t.transfer.bands());
  // A Haar bake has no bands: its environments' one-band SH serve the background's 'sh' mode,
  // and each carries the cube the page turns the light from.
  const Transfer& first = bake.transfers.front().transfer;
  const int haarResolution = first.isHaar() ? first.shape().haar.resolution : 0;
  std::vector<WebEnvironment> envs;
  const std::vector<std::string> specs =
      a.envs.empty() ? std::vector<std::string>{"builtin:sky"} : a.envs;
  for (const std::string& s : specs)
    envs.push_back(loadEnvironment(s, std::max(bands, 1), a.backgroundWidth, haarResolution));

  // Small bakes inside prt-data.js (base64: the page then works opened from disk); larger ones
  // beside it as bake.glb, which the page fetches (over http; a browser refuses file:// fetches).
  // Per-texel glossy matrices' points go where the bake goes.
  const std::vector<float> points = texelPointsFor(bake);
  const std::size_t pointBytes = points.size() * sizeof(float);
  const bool embed = a.embed == "always" ||
                     (a.embed == "auto" && glb.size() + pointBytes <= kMaxEmbeddedBakeBytes);
  Json bakeEntry = {{"name", fs::path(a.bake).filename().string()}, {"bytes", glb.size()}};
  if (embed)
    bakeEntry["glb"] = base64(glb.data(), glb.size());
  else
    bakeEntry["file"] = kBakeFileName;
  if (!points.empty()) {
    Json p = {{"rows", points.size() / 12}, {"bytes", pointBytes}};
    if (embed)
      p["base64"] = base64(points.data(), pointBytes);
    else
      p["file"] = kTexelPointsFileName;
    bakeEntry["texelPoints"] = std::move(p);
  }
  const float exposure = initialExposure(a, bake, envs.front());
  Json data;
  data["generator"] = kGenerator;
  data["view"] = viewJson(a, bake.mesh, exposure);
  data["bake"] = std::move(bakeEntry);
  data["glossy"] = glossyJson(a, bake);
  data["environments"] = Json::array();
  for (const WebEnvironment& e : envs) data["environments"].push_back(environmentJson(e));

  FolderOutput folder(a.output, "prt web");
  for (const char* f : {"index.html", "prt-web.js", "THIRD_PARTY_LICENSES.txt"})
    if (fs::is_regular_file(assets / f)) folder.write(f, readText(assets / f));
  if (!embed)
    folder.write(kBakeFileName,
                 std::string_view(reinterpret_cast<const char*>(glb.data()), glb.size()));
  if (!embed && !points.empty())
    folder.write(kTexelPointsFileName,
                 std::string_view(reinterpret_cast<const char*>(points.data()), pointBytes));
  // The three.js example (prtkit-three, docs/three.md) for the same bake and lights: three/
  // reads ../prt-data.js.
  const fs::path example = assets / "three" / "example";
  if (fs::is_regular_file(example / "example.js") && fs::is_regular_file(example / "index.html")) {
    fs::create_directories(folder.file("three"));
    for (const char* f : {"index.html", "example.js"})
      folder.write(std::string("three/") + f, readText(example / f));
  }
  folder.write("prt-data.js", "// Written by prt web (" + std::string(kGenerator) +
                                  "): the bake and its lights, read by prt-web.js.\n"
                                  "window.PRT_DATA = " +
                                  formatJson(data, 0) + ";\n");
  folder.commit();
  const std::string shown = a.reportAs.empty() ? a.output : a.reportAs;
  const std::string basis = haarResolution > 0 ? fmt::format("a Haar {}² cube", haarResolution)
                                               : fmt::format("{} bands", bands);
  info(fmt::format("wrote {} (open {} in a browser; {} environment(s), {}{})", shown,
                   (fs::path(shown) / "index.html").string(), envs.size(), basis,
                   embed ? ""
                         : fmt::format("; the bake, {:.0f} MB, is beside it as {}: serve the "
                                       "folder over http, e.g. python3 -m http.server -d {}",
                                       double(glb.size()) / 1e6, kBakeFileName, shown)));

  return webReport(a, bake, envs,
                   {shown, glb.size(), embed, pointBytes, bands, exposure, data["glossy"]});
}

namespace {

void runWeb(const WebOptions& a) {
  std::vector<NamedPath> inputs = {{"input", a.bake}};
  for (const std::string& e : a.envs) inputs.push_back({"--env", e});
  Report report("web", a.json);
  report.checkOutsideFolder({"-o", a.output});
  report.check({{"-o", a.output}}, inputs);
  const Json web = writeWebViewer(a);
  report.input(a.bake);
  for (const Json& e : web["environments"]) report.input(e["source"].get<std::string>());
  report.outputFolder(web["folder"]);
  for (const auto& [key, value] : web.items()) report[key.c_str()] = value;
  report.write();
}

}  // namespace

void addWebCommand(CLI::App& root) {
  auto args = std::make_shared<WebOptions>();
  CLI::App* cmd = root.add_subcommand(
      "web", "Write the browser viewer (WebGL2) for a bake: a folder that works from file://");
  cmd->add_option("bake", args->bake, "Bake file (.glb)")->required();
  cmd->add_option("--env,--light", args->envs,
                  "Environment (image, face folder, builtin:NAME) or SH light file; repeat to "
                  "offer several (default builtin:sky)");
  cmd->add_option("-o,--output", args->output, "Folder to write")->required();
  cmd->add_option("--rotate", args->rotate, "Initial light rotation X,Y,Z (degrees)");
  cmd->add_option("--camera", args->camera,
                  "Initial camera 'eye=x,y,z;target=x,y,z;up=x,y,z;fov=deg' (as prt render; "
                  "default: framed)");
  cmd->add_option("--mode", args->mode, "Initial transfer mode");
  addMaterialOption(cmd, args->material, "for glossy (matrix) transfer");
  cmd->add_option("--encoding", args->encoding,
                  "Open a per-vertex matrix transfer drawn as an engine's irradiance encoding "
                  "shades it (its diffuse part, as prt render --encoding): l1, l1-windowed, "
                  "l1-geomerics, zh3, zh3-shared, zh3-optimal, zh3-hallucinated, l2, l2-deringed, "
                  "or none (PRT's own radiance; dense matrices are drawn through l2 then)");
  cmd->add_option("--bands", args->bands, "Initial band count (default: the bake's)");
  cmd->add_option("--terms", args->terms,
                  "A Haar bake: the light's wavelet terms the page opens with (default 200; the "
                  "page turns the light itself)");
  cmd->add_option_function<std::string>(
         "--exposure", [args](const std::string& s) { args->exposure = exposureOption(s); },
         "Initial exposure in stops, or auto (default): prt render's rule on a CPU relight of "
         "the first view")
      ->check(exposureStopsOrAuto());
  cmd->add_option("--tonemap", args->toneMap, "Initial tone map: aces, reinhard, clamp")
      ->capture_default_str();
  cmd->add_option("--embed", args->embed,
                  fmt::format("Where the bake goes: auto (inside prt-data.js up to {} MB, so the "
                              "page opens from disk; else beside it as {}, fetched over http), "
                              "always, never",
                              kMaxEmbeddedBakeBytes >> 20, kBakeFileName))
      ->capture_default_str();
  cmd->add_option("--background-width", args->backgroundWidth,
                  "Width of each environment's lat-long background image")
      ->capture_default_str();
  addJsonOption(cmd, args->json);
  cmd->callback([args] { runWeb(*args); });
}

}  // namespace prt::cli
