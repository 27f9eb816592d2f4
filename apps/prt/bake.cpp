// prt bake: mesh(es) → transfer → bake file (.glb).
//
//   prt bake bunny.obj --mode shadowed --bands 3 --samples 1024 -o bunny.glb
//   prt bake builtin:sphere-plane --mode unshadowed --mode shadowed -o both.glb
//   prt bake scene.obj --mode shadowed --range 0:50000 -o part0.glb   (split bakes; see
//                                                                       docs/formats-bake.md)

#include <fmt/format.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "cli.hpp"
#include "guard.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/units.hpp"
#include "prt/geometry/load.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transport/bake.hpp"
#include "transfer_options.hpp"

namespace prt::cli {

namespace {

struct BakeArgs {
  std::vector<std::string> inputs;
  std::vector<std::string> modes;
  int bands = 3;
  long long samples = 1024;  // wide, so absurd counts get our message, not a parse error
  int bounces = 1;
  std::uint64_t seed = 0;
  std::string sampling = "cosine";
  std::string albedo;
  std::string transfer = "vector";
  std::string material;
  std::string range;
  std::string output;
};

Rgb parseAlbedo(const std::string& s) {
  float r, g, b;
  char tail;
  const int n = std::sscanf(s.c_str(), "%f,%f,%f%c", &r, &g, &b, &tail);
  if (n == 1 && std::sscanf(s.c_str(), "%f%c", &r, &tail) == 1)
    g = b = r;
  else if (n != 3)
    throw Error("--albedo '" + s + "': expected r,g,b or one grey value");
  for (float x : {r, g, b})
    if (!(x >= 0.0f && x <= 1.0f))
      throw Error("--albedo '" + s + "': components must lie in [0, 1]");
  return {r, g, b};
}

/// "a:b" → [a, b); "a:" → [a, end).
RowRange parseRange(const std::string& s, std::size_t vertices) {
  const auto colon = s.find(':');
  auto num = [&](const std::string& t) -> std::size_t {
    if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos)
      throw Error("--range '" + s + "': expected FIRST:END vertex indices, e.g. 0:5000");
    if (t.size() > 15)  // beyond any mesh; also keeps std::stoull from overflowing
      throw Error(fmt::format("--range {}: {} is past the vertex count {}", s, t, vertices));
    return std::stoull(t);
  };
  if (colon == std::string::npos) throw Error("--range '" + s + "': expected FIRST:END");
  const std::size_t first = num(s.substr(0, colon));
  const std::size_t end = colon + 1 == s.size() ? vertices : num(s.substr(colon + 1));
  if (first >= end || end > vertices)
    throw Error(
        fmt::format("--range {}: must satisfy FIRST < END <= {} (the vertex count)", s, vertices));
  return {first, end - first};
}

std::string seconds(double s) {
  return s < 1 ? fmt::format("{:.0f} ms", s * 1e3) : fmt::format("{:.2f} s", s);
}

/// What every mode of the bake shares, from the options (cheap checks before loading anything).
struct BakePlan {
  std::vector<TransferMode> modes;
  TransferLayout layout = TransferLayout::Vector;
  BakeRecipe recipe;  ///< all but the mode
};

BakePlan planOf(const BakeArgs& a) {
  if (a.modes.empty()) throw Error("no --mode given");
  BakePlan plan;
  for (const auto& m : a.modes) {
    const TransferMode mode = parseTransferMode(m);
    for (TransferMode seen : plan.modes)
      if (seen == mode) throw Error("--mode " + m + " given twice");
    plan.modes.push_back(mode);
  }
  if (a.bands < 1 || a.bands > bands::kMaxBake)
    throw Error(fmt::format("--bands {}: must be 1..{}", a.bands, bands::kMaxBake));
  if (a.samples < 1 || a.samples > kMaxBakeSamples)
    throw Error(fmt::format("--samples {}: must be 1..{}", a.samples, kMaxBakeSamples));
  if (a.bounces < 0 || a.bounces > kMaxBounces)
    throw Error(fmt::format("--bounces {}: must be 0..{}", a.bounces, kMaxBounces));
  BakeRecipe& r = plan.recipe;
  r.sampling = parseSampling(a.sampling == "cosine" ? "cosine-sobol" : a.sampling);
  r.samples = static_cast<int>(a.samples);
  r.bounces = a.bounces;
  r.seed = a.seed;
  plan.layout = parseTransferLayout(a.transfer);
  if (!a.material.empty()) r.material = parseMaterial(a.material);
  if (!a.albedo.empty()) r.material.diffuse = parseAlbedo(a.albedo);
  return plan;
}

/// States the memory a mode's bake takes before the work, and refuses what a bake file cannot
/// hold (naming `output`).
void announce(const Mesh& mesh, const BakeSettings& s, const std::string& output) {
  const std::string what = fmt::format("{} {}", toString(s.mode), toString(s.layout));
  const BakeFootprint fp = bakeFootprint(mesh, s);
  info(fmt::format("{}: {} per vertex, {} in all{}", what, bytesText(fp.bytesPerVertex),
                   bytesText(fp.transferBytes),
                   fp.workingBytes ? " + " + bytesText(fp.workingBytes) + " working" : ""));
  if (s.glossyBounces(s.layout))
    info(
        fmt::format("{}: the bounces follow the material's lobe ({}): {} matrix passes over the "
                    "whole mesh",
                    what, s.material.spec(), s.bounces + 1));
  else if (s.bounces > 0 && s.material.glossy())
    info(
        fmt::format("{}: its bounces treat every surface as diffuse (kd); --transfer matrix "
                    "bounces the light off the lobe too",
                    what));
  // The mesh and the JSON take a little of the file too: a margin of 64 MiB.
  const std::uint64_t fileRoom = kMaxBakeFileBytes - (std::uint64_t(1) << 26);
  if (fp.transferBytes > fileRoom)
    throw Error(output, fmt::format("{} transfer of {} vertices at {} bands is {}, more than a "
                                    "bake file holds ({}); use fewer bands or split the bake "
                                    "with --range",
                                    what, s.rows.count, s.bands, bytesText(fp.transferBytes),
                                    bytesText(fileRoom)));
}

/// The bake's rays, timings and Monte Carlo error, in two lines.
void report(const BakedTransfer& t) {
  const BakeStats& st = t.stats;
  const char* mode = toString(t.mode());
  std::string bounces;
  for (std::size_t k = 0; k < st.secondsBounce.size(); ++k)
    bounces += fmt::format(", bounce {} {}", k + 1, seconds(st.secondsBounce[k]));
  info(fmt::format("{}: {} rays in {} ({:.3g} Mrays/s, {} threads); direct {}{}", mode, st.rays,
                   seconds(st.secondsTotal), st.raysPerSecond / 1e6, st.threads,
                   seconds(st.secondsDirect), bounces));
  info(
      fmt::format("{}: Monte Carlo std. error of T00 mean {:.2e} max {:.2e}; of white-sky "
                  "radiance mean {:.2e} max {:.2e}; {} channel(s)",
                  mode, st.stdErrT0Mean, st.stdErrT0Max, st.stdErrConstMean, st.stdErrConstMax,
                  t.transfer.channels()));
}

/// Never write a bake no reader can use: a non-finite coefficient (an absurd material albedo
/// amplified by the bounces, coordinates beyond float range) fails here, with the vertex.
void refuseNonFinite(const Mesh& mesh, const BakedTransfer& t) {
  const std::size_t stride = t.transfer.stride();
  const FloatArray& values = t.transfer.values();
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k]))
      throw Error(mesh.source,
                  fmt::format("{} transfer of vertex {} is not finite (check the "
                              "material albedos and coordinates); nothing written",
                              toString(t.mode()), t.transfer.rows().first + k / stride));
}

void runBake(const BakeArgs& a) {
  BakePlan plan = planOf(a);
  Material& material = plan.recipe.material;
  if (fileExtension(a.output) != "glb" && !isStandardOutput(a.output))
    throw Error(a.output + ": the bake file must end in .glb");
  std::vector<NamedPath> inputs;
  for (const std::string& in : a.inputs) inputs.push_back({"input", in});
  checkOutputs({{"-o", a.output}}, inputs);
  checkWritable(a.output);

  const auto t0 = std::chrono::steady_clock::now();
  LoadReport loadReport;
  BakeFile file;
  file.mesh = loadScene(a.inputs, &loadReport);
  for (const auto& w : loadReport.warnings) warn(w);
  // Without --material, the file's own glossy surface (MTL Ks/Ns, glTF metallic-roughness).
  if (a.material.empty() && file.mesh.gloss) {
    const std::optional<Rgb> kd = material.diffuse;
    material = materialFromGloss(*file.mesh.gloss);
    material.diffuse = kd;
    info(fmt::format("material from {} ('{}'): {}", file.mesh.source, file.mesh.gloss->material,
                     material.spec()));
  }
  // --albedo (or --material kd=...) replaces the mesh's own albedo in the mesh the bake stores, so
  // every consumer of the file (render, reference, validate, the viewer) relights with the albedo
  // the transfer's bounces were baked with.
  if (material.diffuse) file.mesh.albedo.assign(file.mesh.vertexCount(), *material.diffuse);
  const Mesh& mesh = file.mesh;
  const double loadSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const RowRange rows =
      a.range.empty() ? RowRange{0, mesh.vertexCount()} : parseRange(a.range, mesh.vertexCount());

  const auto t1 = std::chrono::steady_clock::now();
  const auto occluder = makeEmbreeOccluder(mesh);
  const double bvhSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  info(fmt::format("{}: {} vertices, {} triangles, {} part(s); loaded in {}, BVH in {}",
                   mesh.source, mesh.vertexCount(), mesh.triangleCount(), mesh.parts.size(),
                   seconds(loadSeconds), seconds(bvhSeconds)));

  for (TransferMode mode : plan.modes) {
    BakeSettings s;
    static_cast<BakeRecipe&>(s) = plan.recipe;
    s.mode = mode;
    s.bounces = s.effectiveBounces();  // what the file records: 0 unless inter-reflected
    s.layout = plan.layout;
    s.bands = a.bands;
    s.rows = rows;
    announce(mesh, s, a.output);
    BakedTransfer t;
    t.recipe = s;
    t.transfer =
        bake(mesh, *occluder, s, &t.stats, progressBar(std::string("bake ") + toString(mode)));
    report(t);
    refuseNonFinite(mesh, t);
    file.transfers.push_back(std::move(t));
  }
  writeBake(a.output, file);
  info(fmt::format("wrote {} ({}{} vertices {}..{})", a.output,
                   file.complete() ? "" : "partial: ", rows.count, rows.first, rows.end() - 1));
}

}  // namespace

void addBakeCommand(CLI::App& root) {
  auto args = std::make_shared<BakeArgs>();
  auto* cmd =
      root.add_subcommand("bake", "Bake per-vertex SH transfer of a mesh or scene into a .glb");
  cmd->add_option(
         "inputs", args->inputs,
         "Mesh files (OBJ, PLY, OFF, glTF) or builtin:NAME; several are baked as one scene")
      ->required();
  cmd->add_option("--mode", args->modes,
                  "unshadowed | shadowed | interreflected (repeat for several in one file)")
      ->required();
  cmd->add_option("--bands", args->bands,
                  "SH bands B (B² coefficients; the course's SHOrder 2 = 3 bands)")
      ->capture_default_str();
  cmd->add_option("--samples", args->samples, "Directions per vertex")->capture_default_str();
  cmd->add_option("--bounces", args->bounces, "Inter-reflection bounces (interreflected mode)")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Random seed (results are identical for any thread count)")
      ->check(unsignedInt())
      ->capture_default_str();
  cmd->add_option(
         "--sampling", args->sampling,
         "cosine (cosine-weighted Sobol'; also: sobol) | uniform (the course's uniform random)")
      ->capture_default_str();
  cmd->add_option("--albedo", args->albedo,
                  "Uniform albedo r,g,b for the bounces (overrides the mesh's)");
  cmd->add_option("--transfer", args->transfer,
                  "vector (diffuse, B² per vertex) | matrix (glossy, B² x B² per vertex)")
      ->capture_default_str();
  cmd->add_option("--material", args->material,
                  "Surface (stored as the default for relighting): " + materialGrammar())
      ->capture_default_str();
  cmd->add_option("--range", args->range,
                  "Bake only vertices FIRST:END (split bakes; merge later)");
  cmd->add_option("-o,--output", args->output, "Output bake file (.glb)")->required();
  cmd->callback([args] { runBake(*args); });
}

}  // namespace prt::cli
