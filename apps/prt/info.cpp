// prt info: what a file holds, on stdout: bake files (.glb), SH light files (.json and the
// course's light.txt), GAMES202 transport.txt, and environments (images, face folders,
// builtin:NAME).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string_view>

#include "cli.hpp"
#include "guard.hpp"
#include "info_domain.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/limits.hpp"
#include "prt/core/units.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/project.hpp"
#include "prt/geometry/builtin.hpp"
#include "prt/geometry/lightmap_uvs.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/haar/resolution.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/games202_transport.hpp"
#include "prt/io/haar_light_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/render/lightmap_seams.hpp"
#include "prt/sh/encode_irradiance.hpp"
#include "prt/transfer/material.hpp"
#include "report.hpp"

namespace prt::cli {

namespace {

/// How a transfer is stored, in one line.
/// "attributes  normals, uvs, …" (report.hpp's names).
std::string attributesLine(const Mesh& m) {
  std::string line = "attributes  ";
  const std::vector<std::string> a = meshAttributes(m);
  for (std::size_t i = 0; i < a.size(); ++i) line += (i ? ", " : "") + a[i];
  return line + "\n";
}

/// How the mesh's UV sets hold a side × side lightmap (geometry/lightmap_uvs.hpp's rule): the
/// set used and its coverage, or why none can. Into the text and j["lightmap"].
void describeLightmap(const Mesh& m, int side, std::ostream& out, Json& j) {
  Json l = {{"resolution", side}};
  try {
    const LightmapUvChoice c = chooseLightmapUvs(m, UvSetOption::Auto, side, side);
    const TexelSamples s = sampleTexels(m, c.uvs, side, side);
    std::size_t partial = 0;
    for (const TexelSample& t : s.samples) partial += !t.centreInside;
    const double share = double(s.samples.size()) / double(s.texelCount());
    l["uvSet"] = c.name;
    l["coveredTexels"] = s.samples.size();
    l["partialTexels"] = partial;
    l["coverage"] = share;
    out << fmt::format("lightmap    {} at {}x{}: {:.1f}% of the texels covered ({}; {} partly)\n",
                       c.name, side, side, 100.0 * share, s.samples.size(), partial);
    for (const std::string& r : c.refused) out << fmt::format("            (not {})\n", r);
    l["refused"] = c.refused;
  } catch (const Error& e) {
    std::string why = e.what();
    if (why.rfind(m.source + ": ", 0) == 0) why = why.substr(m.source.size() + 2);
    l["uvSet"] = nullptr;
    l["refused"] = Json::array({why});
    out << fmt::format("lightmap    none: {}\n", why);
  }
  j["lightmap"] = std::move(l);
}

/// A mesh file or builtin scene, before any bake: what `prt bake` would read.
void describeMesh(const std::string& path, int lightmapSide, std::ostream& out, Json& j) {
  const Mesh m = loadMesh(path);
  j["kind"] = "mesh";
  j["mesh"] = meshJson(m);
  const Bounds b = computeBounds(m);
  out << fmt::format("{}: mesh\n", path);
  out << fmt::format("vertices    {}\ntriangles   {}\n", m.vertexCount(), m.triangleCount());
  out << fmt::format("parts       {}:", m.parts.size());
  for (const auto& p : m.parts)
    out << fmt::format(" {} ({} v, {} t)", p.name, p.vertexCount, p.triangleCount);
  out << '\n';
  out << fmt::format("bounds      ({:.4g}, {:.4g}, {:.4g}) .. ({:.4g}, {:.4g}, {:.4g})\n", b.lo.x,
                     b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
  out << attributesLine(m);
  describeLightmap(m, lightmapSide, out, j);
}

void describeBake(const std::string& path, std::ostream& out, Json& j) {
  const BakeFile b = readBake(path);
  const Mesh& m = b.mesh;
  j["kind"] = "bake";
  j["formatVersion"] = b.formatVersion;
  j["generator"] = b.generator;
  j["mesh"] = meshJson(m);
  j["rows"] = {{"first", b.rows().first}, {"end", b.rows().end()}, {"complete", b.complete()}};
  j["domain"] = toString(b.domain());
  const char* per = rowName(b.domain());
  j["transfers"] = Json::array();
  for (const auto& t : b.transfers) j["transfers"].push_back(transferJson(t));
  out << fmt::format("{}: prtkit bake file, format version {} (written by {})\n", path,
                     b.formatVersion, b.generator);
  out << fmt::format("source      {}\n", m.source);
  out << fmt::format("vertices    {}\ntriangles   {}\n", m.vertexCount(), m.triangleCount());
  out << fmt::format("parts       {}:", m.parts.size());
  for (const auto& p : m.parts)
    out << fmt::format(" {} ({} v, {} t)", p.name, p.vertexCount, p.triangleCount);
  out << '\n';
  out << attributesLine(m);
  const RowRange rows = b.rows();
  describeBakeDomain(b, out, j);
  out << fmt::format("range       {} {}..{} ({})\n", toString(b.domain()), rows.first,
                     rows.end() - 1, b.complete() ? "complete" : "partial: merge before use");
  out << fmt::format("transfers   {}\n", b.transfers.size());
  for (const auto& t : b.transfers) {
    const BakeRecipe& s = t.recipe;
    const BakeStats& st = t.stats;
    const Transfer& x = t.transfer;
    const std::size_t dense = x.stride() * sizeof(float);
    if (x.isHaar())
      out << fmt::format(
          "  {}: vector (diffuse; each row its occluded or its visible part), Haar wavelets "
          "over a {}² cube ({} coefficients), the {} largest kept per {}{}, {} per {} as stored, "
          "{}\n",
          toString(s.mode), x.shape().haar.resolution, x.coeffs(), x.shape().haar.terms, per,
          x.shape().haar.bounceBands > 0
              ? fmt::format(", and its bounce in {} SH bands x {} channel(s)",
                            x.shape().haar.bounceBands, x.channels())
              : std::string(),
          bytesText(x.bytes() / std::max<std::size_t>(x.rowCount(), 1)), per, transferStorage(t));
    else if (x.isMatrix())
      out << fmt::format(
          "  {}: matrix ({}), {} bands ({}x{} per {}) x {} channel(s), {} per {}, {}\n",
          toString(s.mode),
          x.domain() == TransferDomain::Probes ? "the light arriving from every direction"
                                               : "glossy",
          x.bands(), x.coeffs(), x.coeffs(), per, x.channels(), bytesText(dense), per,
          transferStorage(t));
    else
      out << fmt::format(
          "  {}: vector (diffuse), {} bands ({} coefficients) x {} channel(s), {} per {}, {}\n",
          toString(s.mode), x.bands(), x.coeffs(), x.channels(), bytesText(dense), per,
          transferStorage(t));
    if (x.compressed()) {
      const CpcaRecord& c = t.compression;
      out << fmt::format(
          "    compressed: CPCA, {} clusters x {} components (seed {}), {} -> {} ({:.2f}x)\n",
          x.cpca().clusters, x.cpca().basisCount, c.fit.seed, bytesText(x.shape().denseBytes()),
          bytesText(x.bytes()), c.stats.compressionRatio);
      out << fmt::format(
          "    compression error: relative RMS {:.4e}, SNR {:.2f} dB, squared {:.6e}, max row "
          "{:.4e}; {} iterations, {:.2f} s\n",
          c.stats.relativeRms, c.stats.snrDb, c.stats.squaredError, c.stats.maxRowError,
          c.stats.iterations, c.stats.seconds);
    }
    if (x.domain() == TransferDomain::Probes) {
      out << "    surfaces bounce diffusely (their albedo)\n";
    } else {
      out << fmt::format("    material {}{}\n", s.material.spec(),
                         s.glossyBounces(x.layout()) ? " (the bounces follow its lobe)" : "");
      out << fmt::format("      ({})\n", describe(s.material.lobe));
    }
    out << fmt::format("    samples {}, bounces {}, seed {}, sampling {}", s.samples, s.bounces,
                       s.seed, toString(s.sampling));
    if (s.adaptive())
      out << fmt::format(
          " (adaptive: at most {} per row, to a standard error of {:g}; {:.1f} "
          "rays per row and pass on average)",
          s.samples, s.targetError, st.raysPerRowAndPass());
    if (s.material.diffuse)
      out << fmt::format(", albedo {},{},{}", s.material.diffuse->x, s.material.diffuse->y,
                         s.material.diffuse->z);
    out << '\n';
    // Each rate over the time it divides by, as prt bake prints them (issue 37).
    out << fmt::format(
        "    rays {}, {:.3g} Mrays/s over the {:.3f} s total ({:.3g} Mrays/s while casting; "
        "{:.3f} s direct",
        st.rays, raysPerSecondOf(st.rays, st.secondsTotal) / 1e6, st.secondsTotal,
        st.raysPerSecond / 1e6, st.secondsDirect);
    for (std::size_t k = 0; k < st.secondsBounce.size(); ++k)
      out << fmt::format(", bounce {} {:.3f} s", k + 1, st.secondsBounce[k]);
    out << fmt::format("), {} threads\n", st.threads);
    out << fmt::format(
        "    MC std. error: T00 mean {:.3e} max {:.3e}; white-sky radiance mean {:.3e} max "
        "{:.3e}\n",
        st.stdErrT0Mean, st.stdErrT0Max, st.stdErrConstMean, st.stdErrConstMax);
  }
}

void describeTransportTxt(const std::string& path, std::ostream& out, Json& j) {
  const Games202Transport t = readGames202Transport(path);
  j["kind"] = "games202-transport";
  j["vertices"] = t.vertexCount;
  j["layout"] = t.layout == Games202Layout::Faces ? "faces" : "vertices";
  j["rows"] = t.rowCount;
  j["bands"] = t.bands;
  out << fmt::format("{}: GAMES202 transport.txt\n", path);
  out << fmt::format("vertices    {} (first line)\n", t.vertexCount);
  out << fmt::format(
      "layout      {} ({} lines{})\n", t.layout == Games202Layout::Faces ? "faces" : "vertices",
      t.rowCount,
      t.layout == Games202Layout::Faces ? fmt::format(", {} triangles", t.rowCount / 3) : "");
  out << fmt::format("bands       {} ({} coefficients per line)\n", t.bands, t.bands * t.bands);
  out << "first line ";
  for (int i = 0; i < t.bands * t.bands; ++i) out << fmt::format(" {:.6g}", t.rows[i]);
  out << '\n';
}

/// Mean radiance, per-band energy and the dominant direction of SH lighting (summarizeSh).
void describeSh(const sh::RgbSh& c, std::ostream& out) {
  const ShSummary s = summarizeSh(c);
  out << fmt::format("bands       {} ({} coefficients)\n", c.bands, c.c.size());
  out << fmt::format("mean        {:.6g} {:.6g} {:.6g} (radiance averaged over the sphere)\n",
                     s.meanRadiance.x, s.meanRadiance.y, s.meanRadiance.z);
  out << "band energy";
  for (double e : s.bandEnergy) out << fmt::format(" {:.3g}", e);
  out << " (luminance, sum over m of L_lm^2, per band)\n";
  if (s.hasDirection) {
    const Vec3d& d = s.dominantDirection;
    out << fmt::format(
        "dominant    direction {:.3f} {:.3f} {:.3f} (from band 1; elevation {:.1f} degrees)\n", d.x,
        d.y, d.z, std::asin(std::clamp(d.y, -1.0, 1.0)) * 180 / kPi);
  }
}

/// What each irradiance encoding of `radiance` loses against the irradiance of `reference`
/// (issue 34), as a table; `against` says what the reference is.
void describeEncodings(const sh::RgbSh& radiance, const sh::RgbSh& reference,
                       const std::string& against, std::ostream& out, Json& j) {
  j["irradianceEncodings"] = irradianceEncodingsJson(radiance, reference);
  j["irradianceEncodingsReferenceBands"] = reference.bands;
  out << "irradiance as engines store it (error against " << against << "):\n";
  for (const Json& e : j["irradianceEncodings"])
    out << fmt::format(
        "  {:<17} {:>2} numbers  {:6.2f}% rel. RMS  negative for {:.1f}% of "
        "normals\n",
        e["encoding"].get<std::string>(), e["numbers"].get<int>(),
        100 * e["relativeRms"].get<double>(), 100 * e["negativeShare"].get<double>());
}

/// A Haar light file (prt light --basis haar; io/haar_light_file.hpp).
void describeHaarLight(const std::string& path, std::ostream& out, Json& j) {
  const io::HaarLightFile f = io::readHaarLightJson(path);
  const haar::HaarLight& l = f.light;
  j["kind"] = "haar-light";
  j["source"] = f.source;
  j["layout"] = f.layout;
  j["rotationDegrees"] = f.rotationDeg;
  j["resolution"] = l.resolution;
  j["terms"] = l.terms();
  j["selection"] = f.selection;
  j["energyKept"] = l.energyKept;
  j["brightTexels"] = l.bright.size();
  out << fmt::format("{}: prtkit Haar light (JSON)\n", path);
  out << fmt::format("source      {} ({}), rotation {},{},{} degrees\n", f.source, f.layout,
                     f.rotationDeg[0], f.rotationDeg[1], f.rotationDeg[2]);
  out << fmt::format("basis       Haar wavelets over a {}² cube ({} coefficients)\n", l.resolution,
                     haar::coefficientCount(l.resolution));
  out << fmt::format("terms       the {} largest ({}), {:.6f}% of the light's wavelet energy\n",
                     l.terms(), f.selection, 100 * l.energyKept);
  out << fmt::format("unshadowed  {} brightest texels exactly, the rest in {}-band SH\n",
                     l.bright.size(), l.unshadowed.bands);
}

void describeLightJson(const std::string& path, std::ostream& out, Json& j) {
  if (io::isHaarLightFile(path)) return describeHaarLight(path, out, j);
  const io::LightFile lf = io::readLightJson(path);
  j["kind"] = "light";
  j["source"] = lf.source;
  j["layout"] = lf.layout;
  j["window"] = lf.window;
  j["rotationDegrees"] = lf.rotationDeg;
  j["light"] = shLightJson(lf.coefficients);
  out << fmt::format("{}: prtkit SH light (JSON)\n", path);
  out << fmt::format("source      {} ({}), window {}, rotation {},{},{} degrees\n", lf.source,
                     lf.layout, lf.window, lf.rotationDeg[0], lf.rotationDeg[1], lf.rotationDeg[2]);
  describeSh(lf.coefficients, out);
  if (lf.irradiance) {
    j["irradiance"] = io::irradianceJson(*lf.irradiance);
    out << fmt::format(
        "irradiance  stored as {} ({} numbers): {:.2f}% rel. RMS against {} bands, "
        "negative for {:.1f}% of normals\n",
        sh::toString(lf.irradiance->encoded.encoding),
        sh::storedNumbers(lf.irradiance->encoded.encoding), 100 * lf.irradiance->relativeRms,
        lf.irradiance->referenceBands, 100 * lf.irradiance->negativeShare);
  }
  if (lf.coefficients.bands > 3)
    describeEncodings(lf.coefficients, lf.coefficients,
                      "the light's own " + std::to_string(lf.coefficients.bands) + " bands", out,
                      j);
}

void describeLightTxt(const std::string& path, std::ostream& out, Json& j) {
  const sh::RgbSh c = io::readLightGames202(path);
  j["kind"] = "games202-light";
  j["light"] = shLightJson(c);
  out << fmt::format("{}: GAMES202 light.txt\n", path);
  describeSh(c, out);
}

void describeEnvironment(const std::string& spec, std::ostream& out, Json& j) {
  const envmap::LoadedEnvironment e = envmap::loadEnvironment(spec);
  out << fmt::format("{}: environment, layout {}\n", spec, e.layout);
  const auto& imgs = e.env.images();
  if (!imgs.empty())
    out << fmt::format("size        {} image(s) of {}x{}, {} texels\n", imgs.size(), imgs[0].width,
                       imgs[0].height, e.env.texelCount());
  double total = 0, lumMax = -1, lumMin = std::numeric_limits<double>::infinity();
  Vec3d mean(0.0), brightest(0.0, 1.0, 0.0);
  for (std::size_t k = 0; k < e.env.texelCount(); ++k) {
    const envmap::Texel t = e.env.texel(k);
    if (t.solidAngle <= 0) continue;
    total += t.solidAngle;
    mean += Vec3d(t.radiance) * double(t.solidAngle);
    const double lum = image::luminance(t.radiance);
    lumMin = std::min(lumMin, lum);
    if (lum > lumMax) lumMax = lum, brightest = Vec3d(t.direction);
  }
  mean = mean * (1.0 / (4 * kPi));
  out << fmt::format("solid angle {:.6f} x 4 pi\n", total / (4 * kPi));
  out << fmt::format("radiance    mean {:.6g} {:.6g} {:.6g}; luminance min {:.4g}, max {:.4g}\n",
                     mean.x, mean.y, mean.z, lumMin, lumMax);
  out << fmt::format("brightest   direction {:.3f} {:.3f} {:.3f}\n", brightest.x, brightest.y,
                     brightest.z);
  for (std::size_t k = 0; k < e.files.size(); ++k)
    if (e.stats[k].nonFinitePixels + e.stats[k].negativePixels > 0)
      out << fmt::format("repaired    {}: {} non-finite and {} negative pixels set to 0\n",
                         e.files[k], e.stats[k].nonFinitePixels, e.stats[k].negativePixels);
  out << "as 3-band SH:\n";
  // One projection: its first 3 bands are the 3-band light (bands are independent).
  const sh::RgbSh reference = envmap::projectEnvironment(e.env, sh::kIrradianceReferenceBands);
  const sh::RgbSh sh3 = reference.truncated(3);
  describeSh(sh3, out);
  describeEncodings(sh3, reference,
                    fmt::format("its {}-band projection", sh::kIrradianceReferenceBands), out, j);
  j["kind"] = "environment";
  j["layout"] = e.layout;
  j["images"] = imgs.size();
  j["width"] = imgs.empty() ? 0 : imgs[0].width;
  j["height"] = imgs.empty() ? 0 : imgs[0].height;
  j["texels"] = e.env.texelCount();
  j["solidAngleOver4Pi"] = total / (4 * kPi);
  j["meanRadiance"] = {mean.x, mean.y, mean.z};
  j["luminanceMin"] = lumMin;
  j["luminanceMax"] = lumMax;
  j["brightestDirection"] = {brightest.x, brightest.y, brightest.z};
  j["repaired"] = Json::array();
  for (std::size_t k = 0; k < e.files.size(); ++k)
    if (e.stats[k].nonFinitePixels + e.stats[k].negativePixels > 0)
      j["repaired"].push_back({{"file", e.files[k]},
                               {"nonFinitePixels", e.stats[k].nonFinitePixels},
                               {"negativePixels", e.stats[k].negativePixels}});
  j["sh3"] = shLightJson(sh3);
}

/// A .txt is the course's light.txt when its first line holds three numbers, else transport.txt.
bool isLightTxt(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line.find_first_not_of(" \t\r") == std::string::npos) {
  }
  std::istringstream ls(line);
  int tokens = 0;
  for (std::string tok; ls >> tok;) ++tokens;
  return tokens == 3;
}

void describe(const std::string& path, int lightmapSide, std::ostream& out, Json& j);

void runInfo(const std::vector<std::string>& files, int lightmapSide, const std::string& json) {
  Report report("info", json);
  std::vector<NamedPath> inputs;
  for (const std::string& f : files) inputs.push_back({"input", f});
  report.check({}, inputs);
  // With --json - the report is standard output: the text goes nowhere.
  std::ostringstream discard;
  std::ostream& out = report.toStandardOutput() ? discard : std::cout;
  report["files"] = Json::array();
  bool first = true;
  for (const auto& path : files) {
    if (!first) out << '\n';
    first = false;
    report.input(path);
    Json j = {{"path", path}};
    // A parser's own exception (a JSON library's "number overflow ...") does not name the file:
    // name it here. Our errors already do; out-of-memory is reported as such by main.
    try {
      describe(path, lightmapSide, out, j);
    } catch (const Error&) {
      throw;
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(path, oneLine(e.what(), 200));
    }
    report["files"].push_back(std::move(j));
  }
  report.write();
}

void describe(const std::string& path, int lightmapSide, std::ostream& out, Json& j) {
  {
    const std::string ext = fileExtension(path);
    std::error_code ec;
    const auto meshExts = meshExtensions();
    // builtin:NAME is a scene or an environment by its name (the two sets do not meet).
    const auto sceneNames = builtinSceneNames();
    const std::string builtinName =
        isBuiltinScene(path)
            ? path.substr(
                  8, path.find('?') == std::string::npos ? std::string::npos : path.find('?') - 8)
            : "";
    if (std::find(sceneNames.begin(), sceneNames.end(), builtinName) != sceneNames.end() ||
        (ext != "glb" && std::find(meshExts.begin(), meshExts.end(), ext) != meshExts.end())) {
      describeMesh(path, lightmapSide, out, j);
      return;
    }
    if (envmap::isBuiltin(path) || std::filesystem::is_directory(path, ec) ||
        image::isReadableImageExtension(ext)) {
      describeEnvironment(path, out, j);
      return;
    }
    // Sniffed from its head alone: each kind's reader then reads the file under its own limit
    // (a bake up to the GLB's 4 GiB, not the 2 GiB of PRT_MAX_FILE_BYTES).
    std::vector<unsigned char> bytes = readFileHead(path, 20);
    if (bytes.size() >= 4 && std::string(bytes.begin(), bytes.begin() + 4) == "glTF") {
      // A glTF binary without prtkit's extension is a mesh (prt unwrap writes those): its JSON
      // chunk (GLB §4.4: length at byte 12, text from byte 20) names no prtkit object.
      std::string_view json;
      // A truncated file goes to the bake reader, which says what is missing.
      if (bytes.size() >= 20) {
        const std::size_t length = std::uint32_t(bytes[12]) | std::uint32_t(bytes[13]) << 8 |
                                   std::uint32_t(bytes[14]) << 16 | std::uint32_t(bytes[15]) << 24;
        // (A JSON chunk past the JSON limit is the bake reader's to refuse.)
        if (length <= limits().maxFileBytes) bytes = readFileHead(path, 20 + length);
        if (length <= bytes.size() - 20)
          json = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20, length);
      }
      if (!json.empty() && json.find("PRTKIT_radiance_transfer") == std::string_view::npos &&
          json.find("\"prtkit\"") == std::string_view::npos) {
        describeMesh(path, lightmapSide, out, j);
        return;
      }
      describeBake(path, out, j);
    } else if (ext == "json") {
      describeLightJson(path, out, j);
    } else if (ext == "txt") {
      if (isLightTxt(path))
        describeLightTxt(path, out, j);
      else
        describeTransportTxt(path, out, j);
    } else {
      throw Error(path,
                  "unknown file type (expected a bake .glb, a mesh, a light .json or .txt, a "
                  "transport.txt, an environment image, a face folder or builtin:NAME)");
    }
  }
}

}  // namespace

void addInfoCommand(CLI::App& root) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto json = std::make_shared<std::string>();
  auto side = std::make_shared<int>(512);
  auto* cmd = root.add_subcommand(
      "info", "Describe bakes, meshes, SH light files, GAMES202 text files and environments");
  cmd->add_option("files", *files, "Files to describe")->required();
  cmd->add_option("--resolution", *side,
                  "Meshes: the lightmap side to judge their UV sets against (texels)")
      ->check(CLI::Range(1, kMaxLightmapSide))
      ->capture_default_str();
  addJsonOption(cmd, *json);
  cmd->callback([files, side, json] { runInfo(*files, *side, *json); });
}

}  // namespace prt::cli
