// prt info: what a file holds, on stdout. Bake files (.glb) and transport.txt; light files once
// their reader is in.

#include <fmt/format.h>

#include <cstdio>
#include <iostream>

#include "cli.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/games202_transport.hpp"

namespace prt::cli {

namespace {

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
  std::cout << fmt::format("range       vertices {}..{} ({})\n", b.firstVertex,
                           b.firstVertex + b.vertexCount - 1,
                           b.complete() ? "complete" : "partial: merge before use");
  std::cout << fmt::format("transfers   {}\n", b.transfers.size());
  for (const auto& t : b.transfers) {
    const BakeSettings& s = t.settings;
    const BakeStats& st = t.stats;
    std::cout << fmt::format(
        "  {}: {} bands ({} coefficients) x {} channel(s), attributes {}0..{}\n", toString(s.mode),
        t.field.bands, t.field.coeffs(), t.field.channels, transferAttributePrefix(s.mode),
        (t.field.stride() + 3) / 4 - 1);
    std::cout << fmt::format("    samples {}, bounces {}, seed {}, sampling {}", s.samples,
                             s.bounces, s.seed, toString(s.sampling));
    if (s.albedo)
      std::cout << fmt::format(", albedo {},{},{}", s.albedo->x, s.albedo->y, s.albedo->z);
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

void runInfo(const std::vector<std::string>& files) {
  bool first = true;
  for (const auto& path : files) {
    if (!first) std::cout << '\n';
    first = false;
    const std::string ext = fileExtension(path);
    const auto bytes = readFileBytes(path);
    if (bytes.size() >= 4 && std::string(bytes.begin(), bytes.begin() + 4) == "glTF") {
      describeBake(path);
    } else if (ext == "txt") {
      describeTransportTxt(path);
    } else {
      throw Error(path, "unknown file type (expected a bake file .glb or a transport.txt)");
    }
  }
}

}  // namespace

void addInfoCommand(CLI::App& root) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto* cmd = root.add_subcommand("info", "Describe bake files (.glb) and GAMES202 text files");
  cmd->add_option("files", *files, "Files to describe")->required();
  cmd->callback([files] { runInfo(*files); });
}

}  // namespace prt::cli
