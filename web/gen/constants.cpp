// prt_web_constants OUT.js: writes the browser viewer's constants module (imported in web/src as
// 'prt:constants', bundled by web/build.mjs) from the C++ library, so that the page restates
// none of the library's limits, names, versions or policies (docs/web.md, "Generated from the
// C++"). Built and run by CMake (web/CMakeLists.txt) before the page is bundled.
//
// Every value below is read from the library, not retyped: the band and material limits and
// the bake format version are its constants; mode, layout and tone-map names are its toString /
// parse functions; the transfer pick order is transferPreference run on a bake holding every
// (mode, layout); the two messages the page words like the library are templates cut out of
// the library's own messages (and checked to give them back).

#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/core/luminance.hpp"
#include "prt/core/version.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/haar/turned_cube.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/io/lighting.hpp"
#include "prt/relight/shader_transfer.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/haar_rows.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/probe_grid.hpp"

namespace {

using json = nlohmann::ordered_json;  // keys in the order written (toneMaps: the enum order)

/// Replaces every `from` in `s` by `to`.
std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

/// A message template: `message` with each value replaced by its {key}; throws unless filling
/// the template back (as web/src/messages.js does) gives `message` exactly, so a value that
/// also occurs elsewhere in the wording fails the build instead of producing a wrong template.
std::string cutTemplate(const std::string& message,
                        const std::vector<std::pair<std::string, std::string>>& values) {
  std::string t = message;
  for (const auto& [key, value] : values) t = replaceAll(t, value, "{" + key + "}");
  std::string back = t;
  for (const auto& [key, value] : values) back = replaceAll(back, "{" + key + "}", value);
  if (back != message || t == message)
    throw prt::Error("cannot cut a template out of \"" + message + "\"");
  return t;
}

/// io::loadLighting's warning for a light file with fewer bands than the transfer, as a
/// template over {name}, {light} (the file's bands) and {transfer} (the transfer's).
std::string lightBandsTemplate() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() /
                       ("prt-web-constants-" + std::to_string(std::random_device{}()));
  fs::create_directories(dir);
  const std::string file = (dir / "light.json").string();
  std::string t;
  try {
    prt::io::LightFile light;
    light.coefficients = prt::sh::RgbSh(3);
    light.coefficients.c[0] = prt::Rgb(1.0f);
    prt::io::writeLightJson(file, light);
    const prt::io::Lighting l = prt::io::loadLighting(file, 7);
    if (l.warnings.size() != 1)
      throw prt::Error("io::loadLighting gave " + std::to_string(l.warnings.size()) +
                       " warnings for a 3-band light and a 7-band transfer (1 expected)");
    t = cutTemplate(l.warnings[0], {{"name", file}, {"light", "3"}, {"transfer", "7"}});
  } catch (...) {
    fs::remove_all(dir);
    throw;
  }
  fs::remove_all(dir);
  return t;
}

/// sh::parseIrradianceEncoding's refusal of an unknown name, as a template over {name}.
std::string encodingTemplate() {
  try {
    prt::sh::parseIrradianceEncoding("NAME");
  } catch (const prt::Error& e) {
    return cutTemplate(e.what(), {{"name", "NAME"}});
  }
  throw prt::Error("sh::parseIrradianceEncoding accepted 'NAME'");
}

/// The extreme lightmap UV coordinate geometry::firstUvOutside accepts on the side of `outside`
/// (a value it refuses) from `inside` (one it accepts), as a float: found by bisection, so the
/// page's reader holds UVs to the library's own rule rather than a retyped tolerance.
float acceptedUvBound(double inside, double outside) {
  const auto accepted = [](double u) {
    const prt::Vec2f uv{static_cast<float>(u), 0.5f};
    return !prt::firstUvOutside(std::span<const prt::Vec2f>(&uv, 1)).has_value();
  };
  if (!accepted(inside) || accepted(outside))
    throw prt::Error("firstUvOutside does not accept " + std::to_string(inside) +
                     " and refuse " + std::to_string(outside));
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (inside + outside);
    (accepted(mid) ? inside : outside) = mid;
  }
  return static_cast<float>(inside);
}

json constants() {
  using namespace prt;
  json c;
  c["generator"] = kGenerator;
  c["bands"] = {{"maxLibrary", bands::kMaxLibrary},
                {"maxBake", bands::kMaxBake},
                {"maxPackedLight", bands::kMaxPackedLight},
                {"maxShaderGlossy", bands::kMaxShaderGlossy}};
  c["image"] = {{"maxExposureStops", image::kMaxExposureStops}};
  c["material"] = {{"maxPhongExponent", kMaxPhongExponent},
                   {"minGgxRoughness", kMinGgxRoughness},
                   {"defaultPhongExponent", kDefaultPhongExponent},
                   {"defaultGgxRoughness", kDefaultGgxRoughness},
                   {"defaultSpecular", kDefaultSpecular}};
  // decodeBake reads versions 1..kBakeFormatVersion.
  json versions = json::array();
  for (int v = 1; v <= kBakeFormatVersion; ++v) versions.push_back(v);
  c["bakeFormat"] = {{"version", kBakeFormatVersion},
                     {"reads", versions},
                     {"extension", kBakeExtension},
                     {"firstExtensionVersion", kFirstExtensionVersion}};

  // Modes, richest first, with their glTF names; layouts.
  json modes = json::array();
  for (TransferMode m : kModesRichestFirst)
    modes.push_back({{"name", toString(m)},
                     {"attributePrefix", transferAttributePrefix(m)},
                     {"compressedPrefix", transferCompressedPrefix(m)}});
  c["modes"] = modes;
  c["layouts"] = {toString(TransferLayout::Vector), toString(TransferLayout::Matrix)};
  c["domains"] = {toString(TransferDomain::Vertices), toString(TransferDomain::Texels),
                  toString(TransferDomain::Probes)};
  // Probe grids (docs/probes.md): what decodeBake holds a probeGrid to (checkProbeGrid), and
  // the clamped cosine's kernel A_l (sh::clampedCosineKernel, every band the library reads) that
  // the page shades a normal with, ρ E(n)/π (relight::shadeDiffuse).
  const std::vector<double> kernel = sh::clampedCosineKernel(bands::kMaxLibrary);
  c["probeGrid"] = {{"firstVersion", kFirstProbeVersion},
                    {"maxSide", kMaxProbeSide},
                    {"maxProbes", kMaxProbes},
                    {"maxNumber", kMaxProbeGridNumber}};
  c["clampedCosine"] = kernel;
  // The irradiance encodings engines store (sh/irradiance_encoding.hpp), in the order tables
  // list them, with the numbers each stores and its rows of irradiance SH, and the luminance
  // weights of the zh3 forms' axis: web/src/irradiance_encoding.js ports encodeIrradiance.
  json encodings = json::array();
  for (sh::IrradianceEncoding e : sh::kIrradianceEncodings)
    encodings.push_back({{"name", sh::toString(e)},
                         {"numbers", sh::storedNumbers(e)},
                         {"rows", sh::shRows(e)},
                         {"zonal", sh::isZonal(e)}});
  c["irradianceEncodings"] = encodings;
  c["luminance"] = {kLuminanceR, kLuminanceG, kLuminanceB};
  // The albedo of an object placed in a scene that has one (appendMesh): the page's ball.
  c["defaultAlbedo"] = kDefaultAlbedo;

  // The pick order: transferPreference on a bake with one transfer of every (mode, layout).
  BakeFile all;
  for (TransferMode m : kModesRichestFirst)
    for (TransferLayout l : {TransferLayout::Vector, TransferLayout::Matrix}) {
      BakedTransfer t;
      t.recipe.mode = m;
      TransferShape shape;
      shape.layout = l;
      shape.bands = 1;
      t.transfer = Transfer::zeros(shape);
      all.transfers.push_back(t);
    }
  json order = json::array();
  for (std::size_t i : transferPreference(all))
    order.push_back({{"mode", toString(all.transfers[i].mode())},
                     {"layout", toString(all.transfers[i].transfer.layout())}});
  c["transferPreference"] = order;

  // The GPU paths (relight::ShaderPath) the page draws, by name, with the library's wording.
  c["shaderPaths"] = {
      {"DenseVector", relight::toString(relight::ShaderPath::DenseVector)},
      {"DenseMatrix", relight::toString(relight::ShaderPath::DenseMatrix)},
      {"CpcaVector", relight::toString(relight::ShaderPath::CpcaVector)},
      {"CpcaMatrix", relight::toString(relight::ShaderPath::CpcaMatrix)},
      {"CpuRadiance", relight::toString(relight::ShaderPath::CpuRadiance)},
  };
  c["maxShaderClusters"] = relight::kMaxShaderClusters;
  // The Haar basis (docs/haar.md) as the page reads and relights it: the cube's sizes, a row's
  // quantisation grid (transfer/haar_rows.hpp), the light's unshadowed part (haar_light.hpp) and
  // the turned light's fine cube (turned_cube.hpp).
  c["haar"] = {{"minResolution", haar::kMinResolution},
               {"maxResolution", haar::kMaxResolution},
               {"firstVersion", prt::kFirstHaarVersion},
               {"firstBounceVersion", prt::kFirstHaarBounceVersion},
               {"valueSteps", haar::kHaarValueSteps},
               {"visibleKind", static_cast<int>(haar::HaarRowKind::Visible)},
               {"unshadowedBands", haar::kUnshadowedBands},
               {"brightTexels", haar::kBrightTexels},
               {"fineCubeFactor", haar::kFineCubeFactor},
               {"splatPoints", haar::kSplatPoints},
               {"maxTurnedResolution", haar::kMaxTurnedResolution},
               {"defaultLightTerms", haar::kDefaultLightTerms}};
  c["perTexelMatricesRefusal"] = relight::kPageTexelMatricesRefusal;
  c["maxLightmapSide"] = kMaxLightmapSide;
  // What decodeBake holds a file to beyond the names above (docs/formats-bake.md, "Limits the
  // reader applies"), for the page's reader (web/src/bake.js, checkBakeDocument): the default
  // limits (PRT_MAX_* unset), the recipe's ranges, the lightmap's padding and UV rule.
  const Limits defaults;
  c["bakeFile"] = {{"maxFileBytes", kMaxBakeFileBytes},
                   {"maxVertices", defaults.maxVertices},
                   {"maxTriangles", defaults.maxTriangles},
                   {"maxNesting", defaults.maxNesting},
                   {"maxCoordinate", defaults.maxCoordinate},
                   {"maxBakeSamples", kMaxBakeSamples},
                   {"maxBounces", kMaxBounces},
                   {"maxLightmapPadding", kMaxLightmapPadding},
                   {"lightmapUvMin", acceptedUvBound(0.0, -1.0)},
                   {"lightmapUvMax", acceptedUvBound(1.0, 2.0)}};
  // The tone maps by name, valued as shaders/prt_display.glsl's op (the enum's order).
  // The default is the PNG writer's (what prt render writes without --tonemap).
  json tone = json::object();
  std::string defaultTone;
  for (const char* name : {"clamp", "reinhard", "aces"}) {
    tone[name] = static_cast<int>(image::parseToneMap(name));
    if (image::parseToneMap(name) == image::WriteOptions{}.toneMap) defaultTone = name;
  }
  if (defaultTone.empty()) throw prt::Error("the default tone map has no name here");
  c["toneMaps"] = tone;
  c["defaultToneMap"] = defaultTone;

  c["messages"] = {
      {"bandLimit", cutTemplate(bands::bandLimitMessage("WHAT", 1001, "WHO", 1002),
                                {{"what", "WHAT"}, {"bands", "1001"}, {"who", "WHO"}, {"max", "1002"}})},
      {"lightBands", lightBandsTemplate()},
      {"encoding", encodingTemplate()},
  };
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: prt_web_constants OUT.js\n");
    return 2;
  }
  try {
    const json c = constants();
    std::string js =
        "// Generated at build time by web/gen/constants.cpp from the C++ library; do not edit.\n"
        "// (docs/web.md, \"Generated from the C++\")\n";
    for (const auto& [key, value] : c.items())
      js += "export const " + key + " = " + value.dump() + ";\n";
    prt::writeFileAtomically(argv[1], js);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt_web_constants: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
