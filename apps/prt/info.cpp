// prt info: what a file holds, on stdout: bake files (.glb), SH light files (.json and the
// course's light.txt), GAMES202 transport.txt, and environments (images, face folders,
// builtin:NAME).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/units.hpp"
#include "prt/envmap/builtin.hpp"
#include "prt/envmap/load.hpp"
#include "prt/envmap/project.hpp"
#include "prt/image/color.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/games202_transport.hpp"
#include "prt/io/light_file.hpp"

namespace prt::cli {

namespace {

/// How a transfer is stored, in one line.
std::string storage(const BakedTransfer& t) {
  const Transfer& x = t.transfer;
  const TransferMode mode = t.mode();
  if (x.compressed())
    return fmt::format("CPCA-compressed, accessors {}*", transferCompressedPrefix(mode));
  if (x.isMatrix()) return fmt::format("accessor {}", transferMatrixName(mode));
  return fmt::format("attributes {}0..{}", transferAttributePrefix(mode), (x.stride() + 3) / 4 - 1);
}

void describeBake(const std::string& path) {
  const BakeFile b = readBake(path);
  const Mesh& m = b.mesh;
  std::cout << fmt::format("{}: prtkit bake file, format version {} (written by {})\n", path,
                           b.formatVersion, b.generator);
  std::cout << fmt::format("source      {}\n", m.source);
  std::cout << fmt::format("vertices    {}\ntriangles   {}\n", m.vertexCount(), m.triangleCount());
  std::cout << fmt::format("parts       {}:", m.parts.size());
  for (const auto& p : m.parts)
    std::cout << fmt::format(" {} ({} v, {} t)", p.name, p.vertexCount, p.triangleCount);
  std::cout << '\n';
  std::cout << fmt::format("attributes  normals{}{}\n", m.uvs.empty() ? "" : ", uvs",
                           m.albedo.empty() ? "" : ", albedo");
  const RowRange rows = b.rows();
  std::cout << fmt::format("range       vertices {}..{} ({})\n", rows.first, rows.end() - 1,
                           b.complete() ? "complete" : "partial: merge before use");
  std::cout << fmt::format("transfers   {}\n", b.transfers.size());
  for (const auto& t : b.transfers) {
    const BakeRecipe& s = t.recipe;
    const BakeStats& st = t.stats;
    const Transfer& x = t.transfer;
    const std::size_t dense = x.stride() * sizeof(float);
    if (x.isMatrix())
      std::cout << fmt::format(
          "  {}: matrix (glossy), {} bands ({}x{} per vertex) x {} channel(s), {} per vertex, {}\n",
          toString(s.mode), x.bands(), x.coeffs(), x.coeffs(), x.channels(), bytesText(dense),
          storage(t));
    else
      std::cout << fmt::format(
          "  {}: vector (diffuse), {} bands ({} coefficients) x {} channel(s), {}\n",
          toString(s.mode), x.bands(), x.coeffs(), x.channels(), storage(t));
    if (x.compressed()) {
      const CpcaRecord& c = t.compression;
      std::cout << fmt::format(
          "    compressed: CPCA, {} clusters x {} components (seed {}), {} -> {} ({:.2f}x)\n",
          x.cpca().clusters, x.cpca().basisCount, c.fit.seed, bytesText(x.shape().denseBytes()),
          bytesText(x.bytes()), c.stats.compressionRatio);
      std::cout << fmt::format(
          "    compression error: relative RMS {:.4e}, SNR {:.2f} dB, squared {:.6e}, max vertex "
          "{:.4e}; {} iterations, {:.2f} s\n",
          c.stats.relativeRms, c.stats.snrDb, c.stats.squaredError, c.stats.maxRowError,
          c.stats.iterations, c.stats.seconds);
    }
    std::cout << fmt::format("    material {}{}\n", s.material.spec(),
                             s.glossyBounces(x.layout()) ? " (the bounces follow its lobe)" : "");
    std::cout << fmt::format("    samples {}, bounces {}, seed {}, sampling {}", s.samples,
                             s.bounces, s.seed, toString(s.sampling));
    if (s.material.diffuse)
      std::cout << fmt::format(", albedo {},{},{}", s.material.diffuse->x, s.material.diffuse->y,
                               s.material.diffuse->z);
    std::cout << '\n';
    std::cout << fmt::format("    rays {}, {:.3g} Mrays/s, {:.3f} s total ({:.3f} s direct",
                             st.rays, st.raysPerSecond / 1e6, st.secondsTotal, st.secondsDirect);
    for (std::size_t k = 0; k < st.secondsBounce.size(); ++k)
      std::cout << fmt::format(", bounce {} {:.3f} s", k + 1, st.secondsBounce[k]);
    std::cout << fmt::format("), {} threads\n", st.threads);
    std::cout << fmt::format(
        "    MC std. error: T00 mean {:.3e} max {:.3e}; white-sky radiance mean {:.3e} max "
        "{:.3e}\n",
        st.stdErrT0Mean, st.stdErrT0Max, st.stdErrConstMean, st.stdErrConstMax);
  }
}

void describeTransportTxt(const std::string& path) {
  const Games202Transport t = readGames202Transport(path);
  std::cout << fmt::format("{}: GAMES202 transport.txt\n", path);
  std::cout << fmt::format("vertices    {} (first line)\n", t.vertexCount);
  std::cout << fmt::format(
      "layout      {} ({} lines{})\n", t.layout == Games202Layout::Faces ? "faces" : "vertices",
      t.rowCount,
      t.layout == Games202Layout::Faces ? fmt::format(", {} triangles", t.rowCount / 3) : "");
  std::cout << fmt::format("bands       {} ({} coefficients per line)\n", t.bands,
                           t.bands * t.bands);
  std::cout << "first line ";
  for (int i = 0; i < t.bands * t.bands; ++i) std::cout << fmt::format(" {:.6g}", t.rows[i]);
  std::cout << '\n';
}

/// Mean radiance, per-band energy and the dominant direction of SH lighting. With Y1,-1 = −c y,
/// Y1,0 = c z, Y1,1 = −c x (docs/conventions.md), the linear band of a lobe along d is ∝
/// (−d_y, d_z, −d_x).
void describeSh(const sh::RgbSh& c) {
  const double k = 1.0 / std::sqrt(4 * kPi);
  std::cout << fmt::format("bands       {} ({} coefficients)\n", c.bands, c.c.size());
  std::cout << fmt::format("mean        {:.6g} {:.6g} {:.6g} (radiance averaged over the sphere)\n",
                           c.c[0].x * k, c.c[0].y * k, c.c[0].z * k);
  std::cout << "band energy";
  for (int l = 0; l < c.bands; ++l) {
    double e = 0;
    for (int m = -l; m <= l; ++m) {
      const double y = image::luminance(c.c[l * (l + 1) + m]);
      e += y * y;
    }
    std::cout << fmt::format(" {:.3g}", e);
  }
  std::cout << " (luminance, sum over m of L_lm^2, per band)\n";
  if (c.bands >= 2) {
    const double x = -image::luminance(c.c[3]), y = -image::luminance(c.c[1]),
                 z = image::luminance(c.c[2]);
    const double n = std::sqrt(x * x + y * y + z * z);
    if (n > 0)
      std::cout << fmt::format(
          "dominant    direction {:.3f} {:.3f} {:.3f} (from band 1; elevation {:.1f} degrees)\n",
          x / n, y / n, z / n, std::asin(std::clamp(y / n, -1.0, 1.0)) * 180 / kPi);
  }
}

void describeLightJson(const std::string& path) {
  const io::LightFile lf = io::readLightJson(path);
  std::cout << fmt::format("{}: prtkit SH light (JSON)\n", path);
  std::cout << fmt::format("source      {} ({}), window {}, rotation {},{},{} degrees\n", lf.source,
                           lf.layout, lf.window, lf.rotationDeg[0], lf.rotationDeg[1],
                           lf.rotationDeg[2]);
  describeSh(lf.coefficients);
}

void describeLightTxt(const std::string& path) {
  const sh::RgbSh c = io::readLightGames202(path);
  std::cout << fmt::format("{}: GAMES202 light.txt\n", path);
  describeSh(c);
}

void describeEnvironment(const std::string& spec) {
  const envmap::LoadedEnvironment e = envmap::loadEnvironment(spec);
  std::cout << fmt::format("{}: environment, layout {}\n", spec, e.layout);
  const auto& imgs = e.env.images();
  if (!imgs.empty())
    std::cout << fmt::format("size        {} image(s) of {}x{}, {} texels\n", imgs.size(),
                             imgs[0].width, imgs[0].height, e.env.texelCount());
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
  std::cout << fmt::format("solid angle {:.6f} x 4 pi\n", total / (4 * kPi));
  std::cout << fmt::format(
      "radiance    mean {:.6g} {:.6g} {:.6g}; luminance min {:.4g}, max {:.4g}\n", mean.x, mean.y,
      mean.z, lumMin, lumMax);
  std::cout << fmt::format("brightest   direction {:.3f} {:.3f} {:.3f}\n", brightest.x, brightest.y,
                           brightest.z);
  for (std::size_t k = 0; k < e.files.size(); ++k)
    if (e.stats[k].nonFinitePixels + e.stats[k].negativePixels > 0)
      std::cout << fmt::format("repaired    {}: {} non-finite and {} negative pixels set to 0\n",
                               e.files[k], e.stats[k].nonFinitePixels, e.stats[k].negativePixels);
  std::cout << "as 3-band SH:\n";
  describeSh(envmap::projectEnvironment(e.env, 3));
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

void describe(const std::string& path);

void runInfo(const std::vector<std::string>& files) {
  bool first = true;
  for (const auto& path : files) {
    if (!first) std::cout << '\n';
    first = false;
    // A parser's own exception (a JSON library's "number overflow ...") does not name the file:
    // name it here. Our errors already do; out-of-memory is reported as such by main.
    try {
      describe(path);
    } catch (const Error&) {
      throw;
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(path, oneLine(e.what(), 200));
    }
  }
}

void describe(const std::string& path) {
  {
    const std::string ext = fileExtension(path);
    std::error_code ec;
    if (envmap::isBuiltin(path) || std::filesystem::is_directory(path, ec) ||
        image::isReadableImageExtension(ext)) {
      describeEnvironment(path);
      return;
    }
    const auto bytes = readFileBytes(path);
    if (bytes.size() >= 4 && std::string(bytes.begin(), bytes.begin() + 4) == "glTF") {
      describeBake(path);
    } else if (ext == "json") {
      describeLightJson(path);
    } else if (ext == "txt") {
      if (isLightTxt(path))
        describeLightTxt(path);
      else
        describeTransportTxt(path);
    } else {
      throw Error(path,
                  "unknown file type (expected a bake .glb, a light .json or .txt, a "
                  "transport.txt, an environment image, a face folder or builtin:NAME)");
    }
  }
}

}  // namespace

void addInfoCommand(CLI::App& root) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto* cmd = root.add_subcommand(
      "info", "Describe bakes, SH light files, GAMES202 text files and environments");
  cmd->add_option("files", *files, "Files to describe")->required();
  cmd->callback([files] { runInfo(*files); });
}

}  // namespace prt::cli
