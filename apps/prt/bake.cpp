// prt bake: mesh(es) → transfer → bake file (.glb).
//
//   prt bake bunny.obj --mode shadowed --bands 3 --samples 1024 -o bunny.glb
//   prt bake builtin:sphere-plane --mode unshadowed --mode shadowed -o both.glb
//   prt bake scene.obj --mode shadowed --range 0:50000 -o part0.glb   (split bakes; see
//                                                                       docs/formats-bake.md)
//   mpirun -np 8 prt bake bunny.obj --mode interreflected -o bunny.glb  (one bake across MPI
//                                                                       ranks; docs/distributed.md)
//   prt bake scene.obj --mode shadowed --shard 3/16 -o part3.glb      (job arrays, no MPI)
//   prt bake builtin:cornell --mode interreflected --domain texels --resolution 256 -o box.glb
//                                                                      (per-texel transfer)
//   prt bake scene.obj --mode interreflected --pass 1 --previous pass0.prtpass --shard 3/16
//            -o pass1-3.prtpass                                        (a job array's bounces)

#include <fmt/format.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <tuple>

#include "cli.hpp"
#include "guard.hpp"
#include "mpi_verb.hpp"
#include "prt/core/band_limits.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/units.hpp"
#include "prt/geometry/lightmap_uvs.hpp"
#include "prt/geometry/load.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/pass_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/bake_texels.hpp"
#include "prt/transport/passes.hpp"
#include "prt/unwrap/unwrap.hpp"
#include "report.hpp"
#include "seam_fix.hpp"
#include "transfer_options.hpp"
#if PRT_HAVE_MPI
#include <iostream>

#include "prt/distributed/run.hpp"
#endif

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
  // Per-texel transfer (docs/transport.md): the lightmap and the UV set it is over.
  std::string domain = "vertices";
  int resolution = 0;  ///< 0: not given (kDefaultResolution)
  std::string uv;      ///< "": not given (auto)
  int padding = -1;    ///< −1: not given (kDefaultPadding)
  bool seamFix = false;  ///< --seam-fix
  // Distributed and split bakes (docs/distributed.md).
  std::string checkpoint;  ///< MPI: folder of finished chunks
  std::size_t chunk = 0;   ///< MPI: rows per chunk (0: the default)
  std::string shard;       ///< I/N, auto, auto/N: one shard of the work (job arrays)
  int pass = -1;           ///< one pass of a multi-pass bake (job arrays)
  std::string previous;    ///< the merged pass file of pass K − 1
  std::string json;        ///< --json: the report
};

/// --shard: "I/N" (0 ≤ I < N), or "auto" / "auto/N" with I (and N) from the scheduler:
/// SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN and SLURM_ARRAY_TASK_COUNT (Slurm job arrays), or
/// JOB_COMPLETION_INDEX (Kubernetes indexed Jobs, which do not say N: give auto/N).
std::pair<std::size_t, std::size_t> parseShard(const std::string& s) {
  const auto number = [&](const std::string& t, const char* what) -> std::size_t {
    if (t.empty() || t.size() > 9 || t.find_first_not_of("0123456789") != std::string::npos)
      throw Error(fmt::format("--shard {}: {} '{}' is not a count", s, what, t));
    return std::stoull(t);
  };
  const auto slash = s.find('/');
  const std::string head = s.substr(0, slash);
  std::size_t i = 0, n = 0;
  if (slash != std::string::npos) n = number(s.substr(slash + 1), "N");
  if (head == "auto") {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* k8s = std::getenv("JOB_COMPLETION_INDEX");
    if (id) {
      const char* lo = std::getenv("SLURM_ARRAY_TASK_MIN");
      const std::size_t first = lo ? number(lo, "SLURM_ARRAY_TASK_MIN") : 0;
      i = number(id, "SLURM_ARRAY_TASK_ID");
      if (i < first) throw Error("--shard auto: SLURM_ARRAY_TASK_ID is below SLURM_ARRAY_TASK_MIN");
      i -= first;
      if (!n)
        if (const char* c = std::getenv("SLURM_ARRAY_TASK_COUNT"))
          n = number(c, "SLURM_ARRAY_TASK_COUNT");
    } else if (k8s) {
      i = number(k8s, "JOB_COMPLETION_INDEX");
    } else {
      throw Error(
          "--shard auto: neither SLURM_ARRAY_TASK_ID nor JOB_COMPLETION_INDEX is set "
          "(give --shard I/N)");
    }
    if (!n)
      throw Error(
          "--shard auto: the shard count is unknown (SLURM_ARRAY_TASK_COUNT is not set; "
          "give --shard auto/N)");
  } else {
    if (slash == std::string::npos) throw Error("--shard '" + s + "': expected I/N, e.g. 3/16");
    i = number(head, "I");
  }
  if (n == 0 || i >= n)
    throw Error(fmt::format("--shard {}: must satisfy 0 <= I < N (got {}/{})", s, i, n));
  return {i, n};
}

/// Shard i of n of rows: [first + ⌊i·count/n⌋, first + ⌊(i+1)·count/n⌋).
RowRange shardOf(RowRange rows, std::size_t i, std::size_t n) {
  const std::size_t lo = rows.count * i / n, hi = rows.count * (i + 1) / n;
  return {rows.first + lo, hi - lo};
}

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

/// "a:b" → [a, b); "a:" → [a, end), of `rows` rows named `what` ("vertex", "texel").
RowRange parseRange(const std::string& s, std::size_t rows, const char* what = "vertex") {
  const auto colon = s.find(':');
  auto num = [&](const std::string& t) -> std::size_t {
    if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos)
      throw Error(fmt::format("--range '{}': expected FIRST:END {} indices, e.g. 0:5000", s, what));
    if (t.size() > 15)  // beyond any mesh; also keeps std::stoull from overflowing
      throw Error(fmt::format("--range {}: {} is past the {} count {}", s, t, what, rows));
    return std::stoull(t);
  };
  if (colon == std::string::npos) throw Error("--range '" + s + "': expected FIRST:END");
  const std::size_t first = num(s.substr(0, colon));
  const std::size_t end = colon + 1 == s.size() ? rows : num(s.substr(colon + 1));
  if (first >= end || end > rows)
    throw Error(
        fmt::format("--range {}: must satisfy FIRST < END <= {} (the {} count)", s, rows, what));
  return {first, end - first};
}

/// A per-texel bake's lightmap, when --domain texels.
struct TexelPlan {
  int resolution = 512;  ///< the lightmap's side
  int padding = 2;       ///< rings of gutter dilated
  UvSetOption uv = UvSetOption::Auto;
  bool seamFix = false;  ///< the least-squares seam fix after the bake
};

std::string seconds(double s) {
  return s < 1 ? fmt::format("{:.0f} ms", s * 1e3) : fmt::format("{:.2f} s", s);
}

/// What every mode of the bake shares, from the options (cheap checks before loading anything).
struct BakePlan {
  std::vector<TransferMode> modes;
  TransferLayout layout = TransferLayout::Vector;
  BakeRecipe recipe;                ///< all but the mode
  std::optional<TexelPlan> texels;  ///< --domain texels
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
  const TransferDomain domain = parseTransferDomain(a.domain);
  if (domain == TransferDomain::Texels) {
    TexelPlan t;
    if (a.resolution) t.resolution = a.resolution;
    if (a.padding >= 0) t.padding = a.padding;
    if (!a.uv.empty()) t.uv = parseUvSetOption(a.uv);
    t.seamFix = a.seamFix;
    if (t.resolution < 1 || t.resolution > kMaxLightmapSide)
      throw Error(fmt::format("--resolution {}: must be 1..{}", t.resolution, kMaxLightmapSide));
    if (t.padding > kMaxLightmapPadding)
      throw Error(fmt::format("--padding {}: must be 0..{}", t.padding, kMaxLightmapPadding));
    if (a.pass >= 0 || !a.checkpoint.empty())
      throw Error(
          "--domain texels bakes in one process: --pass and --checkpoint split "
          "per-vertex bakes (--range and --shard split texel bakes)");
    plan.texels = t;
  } else if (a.resolution || a.padding >= 0 || !a.uv.empty() || a.seamFix) {
    throw Error(
        "--resolution, --uv, --padding and --seam-fix shape a lightmap: add --domain texels");
  }
  return plan;
}

/// --domain texels: picks the UV set (--uv), says which and why not another, and makes it the
/// mesh's lightmap UVs (what the bake file records the texels over). With --uv auto and no set
/// that can hold the lightmap, the mesh is unwrapped (prt unwrap's atlas at this resolution and
/// padding, unwrap/unwrap.hpp) and the bake is of the unwrapped mesh, which the file keeps.
void chooseTexelUvs(Mesh& mesh, const TexelPlan& t) {
  LightmapUvChoice c = t.uv == UvSetOption::Auto
                           ? findLightmapUvs(mesh, t.uv, t.resolution, t.resolution)
                           : chooseLightmapUvs(mesh, t.uv, t.resolution, t.resolution);
  if (c.uvs.empty()) {
    UnwrapSettings us;
    us.resolution = t.resolution;
    us.padding = t.padding;
    UnwrapResult u = unwrap(mesh, us, progressBar("unwrap"));
    std::string why;
    for (const std::string& r : c.refused) why += (why.empty() ? "" : "; ") + r;
    info(
        fmt::format("{}: no UV set of its own can hold the lightmap ({}): unwrapped it, {} charts "
                    "({} cut), {:.1f}% of the texels wasted, L2 stretch {:.3f}, in {} (prt "
                    "unwrap makes the same atlas)",
                    mesh.source, why, u.stats.charts, u.splitCharts, 100 * u.stats.wastedTexels,
                    u.stats.stretchL2, seconds(u.stats.seconds)));
    u.mesh.source = mesh.source;
    mesh = std::move(u.mesh);
    c = chooseLightmapUvs(mesh, UvSetOption::Lightmap, t.resolution, t.resolution);
    c.name = "atlas (prt unwrap)";
  }
  for (const std::string& why : c.refused)
    info(fmt::format("{}: passed over {}", mesh.source, why));
  info(fmt::format("{}: a {} x {} lightmap over its {} (padding {})", mesh.source, t.resolution,
                   t.resolution, c.name, t.padding));
  if (c.uvs.data() != mesh.lightmapUvs.data()) mesh.lightmapUvs.assign(c.uvs.begin(), c.uvs.end());
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

/// A per-texel bake's memory, before the work (texelBakeFootprint), refusing what a bake file
/// cannot hold.
void announceTexels(const Mesh& mesh, const BakeSettings& s, const TexelPlan& t,
                    const std::string& output) {
  const std::string what = fmt::format("{} {} per texel", toString(s.mode), toString(s.layout));
  const std::size_t texels = std::size_t(t.resolution) * t.resolution;
  const TexelBakeFootprint fp = texelBakeFootprint(mesh, s, t.resolution, t.resolution);
  info(fmt::format("{}: {} per texel, {} for {} texels + {} working", what,
                   bytesText(fp.bytesPerTexel), bytesText(fp.transferBytes), s.rows.count,
                   bytesText(fp.workingBytes)));
  if (s.glossyBounces(s.layout))
    info(
        fmt::format("{}: the bounces follow the material's lobe ({}): {} matrix passes over the "
                    "whole lightmap",
                    what, s.material.spec(), s.bounces + 1));
  if (s.effectiveBounces() > 0 && s.rows.count < texels)
    info(
        fmt::format("{}: the bounces read the whole lightmap: each range bakes every texel's "
                    "earlier passes",
                    what));
  const std::uint64_t fileRoom = kMaxBakeFileBytes - (std::uint64_t(1) << 26);
  if (fp.transferBytes > fileRoom)
    throw Error(
        output,
        fmt::format("{} transfer of {} texels at {} bands is {}, more than a bake "
                    "file holds ({}); use a smaller --resolution, fewer bands or split "
                    "the bake with --range",
                    what, s.rows.count, s.bands, bytesText(fp.transferBytes), bytesText(fileRoom)));
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
                  fmt::format("{} transfer of {} {} is not finite (check the "
                              "material albedos and coordinates); nothing written",
                              toString(t.mode()), rowName(t.transfer.domain()),
                              t.transfer.rows().first + k / stride));
}

/// --json: the written bake (or pass file) and how it was made. `ranks` > 0 for an MPI run.
void writeReport(const BakeArgs& a, const BakeFile& file, int ranks = 0, Json pass = nullptr) {
  Report r("bake", a.json);
  if (!r.wanted()) return;
  for (const std::string& in : a.inputs) r.input(in);
  if (a.pass > 0) r.input(a.previous);
  r.output(a.output);
  r["mesh"] = meshJson(file.mesh);
  const RowRange rows = file.rows();
  r["rows"] = {{"first", rows.first}, {"end", rows.end()}, {"complete", file.complete()}};
  if (ranks > 0) r["mpiRanks"] = ranks;
  if (!pass.is_null()) r["pass"] = std::move(pass);
  r["transfers"] = Json::array();
  for (const BakedTransfer& t : file.transfers) r["transfers"].push_back(transferJson(t));
  r.write();
}

/// A mesh argument that is a mode's name ("--mode shadowed unshadowed bunny.obj" took
/// "unshadowed" as a mesh): say how several modes are given.
void refuseModesAsInputs(const BakeArgs& a) {
  for (const std::string& in : a.inputs) {
    bool isMode = true;
    try {
      parseTransferMode(in);
    } catch (const Error&) {
      isMode = false;
    }
    std::error_code ec;
    if (isMode && !std::filesystem::exists(in, ec))
      throw Error(
          fmt::format("'{}' is a mode, not a mesh: give each mode its own --mode "
                      "(--mode shadowed --mode {}) or list them (--mode shadowed,{})",
                      in, in, in));
  }
}

#if PRT_HAVE_MPI
constexpr const char* kMpiNote = "";

/// `mpirun -np N prt bake ...`: one bake across the ranks (prt/distributed/run.hpp). Every rank
/// loads the scene and builds its BVH; rank 0 reports and writes the file. Failures that every
/// rank meets (a bad option, a missing file) are agreed on and reported once, by rank 0.
void runBakeMpi(const BakeArgs& a) {
  distributed::Session session("prt bake", [](const std::string& line) {
    std::cerr << "prt bake: error: " << line << std::endl;
  });
  const bool root = session.root();
  if (!root) globals().quiet = globals().silent = true;
  try {
    BakePlan plan;
    BakeFile file;
    RowRange rows;
    std::unique_ptr<Occluder> occluder;
    std::exception_ptr failure;
    try {
      if (!a.shard.empty() || a.pass >= 0)
        throw Error(
            "--shard and --pass split a bake for job arrays without MPI; under mpirun the "
            "ranks share the work (drop them)");
      plan = planOf(a);
      if (plan.texels)
        throw Error(
            "--domain texels under mpirun: per-texel bakes run in one process so far (split "
            "them with --shard or --range and join the pieces with prt merge)");
      if (fileExtension(a.output) != "glb" && !isStandardOutput(a.output))
        throw Error(a.output + ": the bake file must end in .glb");
      refuseModesAsInputs(a);
      if (root) {
        std::vector<NamedPath> inputs;
        for (const std::string& in : a.inputs) inputs.push_back({"input", in});
        checkOutputs({{"-o", a.output}}, inputs);
        checkWritable(a.output);
        Report("bake", a.json).check({{"-o", a.output}}, inputs);
      }
      LoadReport loadReport;
      file.mesh = loadScene(a.inputs, &loadReport);
      for (const auto& w : loadReport.warnings) warn(w);
      Material& material = plan.recipe.material;
      if (a.material.empty() && file.mesh.gloss) {
        const std::optional<Rgb> kd = material.diffuse;
        material = materialFromGloss(*file.mesh.gloss);
        material.diffuse = kd;
      }
      if (material.diffuse) {
        file.mesh.albedo.assign(file.mesh.vertexCount(), *material.diffuse);
        file.mesh.baseColour.reset();
      }
      rows = a.range.empty() ? RowRange{0, file.mesh.vertexCount()}
                             : parseRange(a.range, file.mesh.vertexCount());
      occluder = makeEmbreeOccluder(file.mesh);
    } catch (...) {
      failure = std::current_exception();
    }
    session.agree(failure);
    const Mesh& mesh = file.mesh;
    info(fmt::format("{}: {} vertices, {} triangles; {} MPI ranks x {} threads", mesh.source,
                     mesh.vertexCount(), mesh.triangleCount(), session.size(), maxThreads()));
    distributed::RunOptions options;
    options.chunkRows = a.chunk;
    options.checkpoint = a.checkpoint;
    // Rank 0 keeps a matrix transfer that would not fit its memory in a mapped scratch file
    // beside the output (PRT_MPI_SPILL_ABOVE=BYTES lowers the threshold, for tests).
    if (!isStandardOutput(a.output)) {
      const std::string parent = std::filesystem::path(a.output).parent_path().string();
      options.spillFolder = parent.empty() ? "." : parent;
    }
    if (const char* v = std::getenv("PRT_MPI_SPILL_ABOVE")) options.spillAbove = std::stoull(v);
    for (std::size_t m = 0; m < plan.modes.size(); ++m) {
      BakeSettings s;
      static_cast<BakeRecipe&>(s) = plan.recipe;
      s.mode = plan.modes[m];
      s.bounces = s.effectiveBounces();
      s.layout = plan.layout;
      s.bands = a.bands;
      s.rows = rows;
      if (root) announce(mesh, s, a.output);
      distributed::RunOptions o = options;
      if (!o.checkpoint.empty()) o.checkpoint += std::string("/") + toString(s.mode);
      BakedTransfer t;
      t.recipe = s;
      distributed::RunReport rep;
      t.transfer = distributed::bake(
          session, mesh, *occluder, s, o, &t.stats, &rep,
          root ? progressBar(std::string("bake ") + toString(s.mode)) : ProgressFn{});
      if (!root) continue;
      if (rep.spilled)
        info(
            fmt::format("{}: rank 0 kept the transfer ({}) in a mapped scratch file beside the "
                        "output, not in memory",
                        toString(s.mode), bytesText(bakeFootprint(mesh, s).transferBytes)));
      for (std::size_t j = 0; j < rep.jobs.size(); ++j) {
        const distributed::JobStats& js = rep.jobs[j];
        // What moved: each rank receives the rows it did not compute, (N − 1) × the pass's
        // bytes over all ranks for an all-gather (rank 0 alone, its share, for the last pass);
        // rank 0 also receives each row's variance (8 B) for the error estimate.
        info(fmt::format(
            "{}: {} chunks ({} on rank 0{}), {:.3f} s, exchange {:.3f} s; rows "
            "received {} B ({:.2f} x the pass's {} B), variances {} B",
            rep.names[j], js.chunks, js.chunksHere,
            js.chunksResumed ? fmt::format(", {} from the checkpoint", js.chunksResumed)
                             : std::string(),
            js.seconds, js.exchangeSeconds, js.rowBytesAll,
            double(js.rowBytesAll) / double(std::max<std::uint64_t>(rep.passBytes[j], 1)),
            rep.passBytes[j], js.sideBytesAll));
      }
      report(t);
      refuseNonFinite(mesh, t);
      file.transfers.push_back(std::move(t));
    }
    if (root) {
      writeBake(a.output, file);
      info(fmt::format("wrote {} ({}{} vertices {}..{})", a.output,
                       file.complete() ? "" : "partial: ", rows.count, rows.first, rows.end() - 1));
      writeReport(a, file, session.size());
    }
  } catch (const distributed::AgreedFailure&) {
    throw QuietFailure();
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    if (root) throw;
    if (!session.agreedOnce()) throw QuietFailure();
    throw Error("rank " + std::to_string(session.rank()) + ": " + e.what());
  }
}
#else
constexpr const char* kMpiNote =
    "; this prt was built without MPI (scripts/setup.sh installs Open MPI; rebuild)";
#endif

/// `prt bake --pass K`: rows of one pass of a multi-pass bake, reading the merged pass K − 1.
/// The passes before the last write pass files; the last writes a bake piece, as --range does.
void runPassBake(const BakeArgs& a, BakeFile& file, const Occluder& occluder, BakeSettings s,
                 std::size_t shard, std::size_t shards) {
  const Mesh& mesh = file.mesh;
  const auto t0 = std::chrono::steady_clock::now();
  const BakePasses passes(mesh, occluder, s);
  const int count = passes.count(), k = a.pass;
  if (k < 0 || k >= count)
    throw Error(fmt::format("--pass {}: this bake has passes 0..{}", k, count - 1));
  const BakePassInfo& p = passes.pass(k);
  const bool last = k == count - 1;
  const std::string ext = fileExtension(a.output);
  if (!last && ext != "prtpass")
    throw Error(a.output, fmt::format("pass {} of {} ('{}') is written to a pass file (.prtpass); "
                                      "the last pass, {}, writes the bake",
                                      k, count, p.name, count - 1));
  if (last && ext != "glb") throw Error(a.output, "the last pass writes the bake (.glb)");
  const std::string identity = bakeIdentity(mesh, s);
  PassPiece prev;
  if (k > 0) {
    if (a.previous.empty())
      throw Error(
          fmt::format("--pass {} reads pass {}: give --previous PASS{}.prtpass (its "
                      "merged pieces)",
                      k, k - 1, k - 1));
    prev = readPassPiece(a.previous);
    if (prev.identity != identity)
      throw Error(a.previous, "is a pass of another bake (" + prev.identity + ")");
    if (prev.pass != k - 1)
      throw Error(a.previous, fmt::format("is pass {}, not {}", prev.pass, k - 1));
    if (!(prev.shape.rows == passes.pass(k - 1).shape.rows))
      throw Error(a.previous,
                  fmt::format("holds vertices {}..{} of pass {} only: merge all its pieces first",
                              prev.shape.rows.first, prev.shape.rows.end() - 1, k - 1));
  } else if (!a.previous.empty()) {
    throw Error("--previous: pass 0 reads no earlier pass");
  }
  const RowRange rows = shardOf(p.shape.rows, shard, shards);
  info(fmt::format("pass {} of {} ('{}'): vertices {}..{} (shard {} of {})", k, count, p.name,
                   rows.first, rows.end() - 1, shard, shards));
  // What pass k reads, over the whole mesh: the previous pass, or the sum of those before.
  Transfer input;
  if (p.input == PassInput::Previous)
    input = Transfer::dense(prev.shape, prev.values);
  else if (p.input == PassInput::Sum) {
    TransferShape sh = prev.shape;
    sh.layout = TransferLayout::Vector;
    sh.channels = prev.sumChannels;
    input = Transfer::dense(sh, prev.sum);
  }
  TransferShape shape = p.shape;
  shape.rows = rows;
  Transfer out = Transfer::zeros(shape);
  std::vector<double> var(rows.count, 0.0);
  Progress progress(progressBar(std::string("bake ") + toString(s.mode)), rows.count);
  const std::uint64_t rays = passes.compute(k, rows, input, out.mutableValues(),
                                            p.variance ? var.data() : nullptr, &progress);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The variance summed over the passes so far, in pass order.
  std::vector<double> variance(rows.count, 0.0);
  for (std::size_t r = 0; r < rows.count; ++r) {
    if (k > 0) variance[r] = prev.variance[rows.first - prev.shape.rows.first + r];
    if (p.variance) variance[r] += var[r];
  }
  std::vector<std::uint64_t> raysPer = k > 0 ? prev.rays : std::vector<std::uint64_t>{};
  std::vector<double> secondsPer = k > 0 ? prev.seconds : std::vector<double>{};
  raysPer.push_back(rays);
  secondsPer.push_back(secs);
  // The running sum over these rows: the previous one's, plus this pass.
  const bool summing = passes.resultIsSum() || passes.needsFullSum();
  std::vector<float> sum;
  if (summing && !(last && !passes.resultIsSum())) {
    const std::size_t width = static_cast<std::size_t>(p.shape.coeffs()) * passes.sumChannels();
    sum.assign(rows.count * width, 0.0f);
    if (k > 0)
      std::copy_n(prev.sum.data() + (rows.first - prev.shape.rows.first) * width, sum.size(),
                  sum.data());
    passes.accumulate(k, rows, out.values().data(), rows, sum.data());
  }
  if (!last) {
    PassPiece piece;
    piece.identity = identity;
    piece.pass = k;
    piece.passes = count;
    piece.name = p.name;
    piece.shape = shape;
    piece.values = out.values();
    piece.sumChannels = sum.empty() ? 0 : passes.sumChannels();
    piece.sum = FloatArray(std::move(sum));
    piece.variance = std::move(variance);
    piece.rays = std::move(raysPer);
    piece.seconds = std::move(secondsPer);
    writePassPiece(a.output, piece);
    info(fmt::format("wrote {} (pass {} of {}, vertices {}..{}, {} rays)", a.output, k, count,
                     rows.first, rows.end() - 1, rays));
    if (!a.json.empty()) {
      Report r("bake", a.json);
      for (const std::string& in : a.inputs) r.input(in);
      if (k > 0) r.input(a.previous);
      r.output(a.output);
      r["mesh"] = meshJson(mesh);
      r["pass"] = {{"index", k},          {"count", count},    {"name", p.name},
                   {"first", rows.first}, {"end", rows.end()}, {"rays", rays},
                   {"seconds", secs},     {"shard", shard},    {"shards", shards}};
      r.write();
    }
    return;
  }
  // The last pass: a bake piece of these rows. The earlier passes' rays and seconds are the
  // whole passes': shard 0 carries them, so that merging the pieces counts them once.
  if (shard != 0)
    for (std::size_t j = 0; j + 1 < raysPer.size(); ++j) raysPer[j] = 0, secondsPer[j] = 0;
  BakedTransfer t;
  s.rows = rows;
  t.recipe = s;
  TransferShape rs = passes.resultShape();
  rs.rows = rows;
  t.transfer = passes.resultIsSum() ? Transfer::dense(rs, FloatArray(std::move(sum))) : out;
  t.stats = passes.stats(raysPer, secondsPer, variance, secs, maxThreads());
  t.stats.vertices = rows.count;
  report(t);
  refuseNonFinite(mesh, t);
  file.transfers.push_back(std::move(t));
  writeBake(a.output, file);
  info(fmt::format("wrote {} (last pass, {}{} vertices {}..{})", a.output,
                   file.complete() ? "" : "partial: ", rows.count, rows.first, rows.end() - 1));
  writeReport(a, file, 0,
              {{"index", k},
               {"count", count},
               {"name", p.name},
               {"first", rows.first},
               {"end", rows.end()},
               {"rays", rays},
               {"seconds", secs},
               {"shard", shard},
               {"shards", shards}});
}

void runBake(const BakeArgs& a) {
  // A job array's tasks are separate by design (--shard); other copies must join over MPI.
  if (a.shard.empty()) refuseUnjoinedCopies("prt bake");
#if PRT_HAVE_MPI
  if (distributed::launchedByMpi()) {
    runBakeMpi(a);
    return;
  }
#endif
  if (!a.checkpoint.empty())
    throw Error(
        "--checkpoint keeps the finished chunks of an MPI run: start prt under mpirun "
        "(mpirun -np 1 works)" +
        std::string(kMpiNote));
  BakePlan plan = planOf(a);
  Material& material = plan.recipe.material;
  if (a.pass < 0 && fileExtension(a.output) != "glb" && !isStandardOutput(a.output))
    throw Error(a.output + ": the bake file must end in .glb");
  refuseModesAsInputs(a);
  std::vector<NamedPath> inputs;
  for (const std::string& in : a.inputs) inputs.push_back({"input", in});
  if (!a.previous.empty()) inputs.push_back({"--previous", a.previous});
  checkOutputs({{"-o", a.output}}, inputs);
  checkWritable(a.output);
  Report("bake", a.json).check({{"-o", a.output}}, inputs);

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
  // kd replaces the whole diffuse colour, the base-colour texture with it.
  if (material.diffuse) {
    file.mesh.albedo.assign(file.mesh.vertexCount(), *material.diffuse);
    file.mesh.baseColour.reset();
  }
  if (plan.texels) chooseTexelUvs(file.mesh, *plan.texels);
  const Mesh& mesh = file.mesh;
  const double loadSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::size_t domainRows =
      plan.texels ? std::size_t(plan.texels->resolution) * plan.texels->resolution
                  : mesh.vertexCount();
  RowRange rows = a.range.empty()
                      ? RowRange{0, domainRows}
                      : parseRange(a.range, domainRows, plan.texels ? "texel" : "vertex");
  std::size_t shard = 0, shards = 1;
  if (!a.shard.empty()) std::tie(shard, shards) = parseShard(a.shard);
  if (plan.texels && plan.texels->seamFix && (rows.count < domainRows || shards > 1))
    throw Error(
        "--seam-fix needs the whole lightmap (a seam joins texels of other ranges): bake the "
        "pieces without it, then prt merge --seam-fix");
  const bool multiPass =
      plan.recipe.bounces > 0 && std::find(plan.modes.begin(), plan.modes.end(),
                                           TransferMode::Interreflected) != plan.modes.end();
  if (a.pass >= 0 && (plan.modes.size() != 1 || !multiPass))
    throw Error(
        "--pass bakes one pass of an interreflected bake with bounces: give one --mode "
        "interreflected (the other modes bake in one pass: --shard alone splits them)");
  if (a.pass < 0 && !a.previous.empty()) throw Error("--previous goes with --pass");
  if (a.pass < 0 && !a.shard.empty() && multiPass && !plan.texels)
    throw Error(
        "--shard of an interreflected bake shards its passes one at a time: add --pass 0, "
        "prt merge the pieces, then --pass 1 --previous MERGED.prtpass, and so on (prt "
        "bake --help, docs/distributed.md)");
  if (a.pass < 0 && shards > 1) rows = shardOf(rows, shard, shards);

  const auto t1 = std::chrono::steady_clock::now();
  const auto occluder = makeEmbreeOccluder(mesh);
  const double bvhSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  info(fmt::format("{}: {} vertices, {} triangles, {} part(s); loaded in {}, BVH in {}",
                   mesh.source, mesh.vertexCount(), mesh.triangleCount(), mesh.parts.size(),
                   seconds(loadSeconds), seconds(bvhSeconds)));

  if (a.pass >= 0) {
    BakeSettings s;
    static_cast<BakeRecipe&>(s) = plan.recipe;
    s.mode = plan.modes.front();
    s.layout = plan.layout;
    s.bands = a.bands;
    s.rows = rows;
    runPassBake(a, file, *occluder, s, shard, shards);
    return;
  }
  for (TransferMode mode : plan.modes) {
    BakeSettings s;
    static_cast<BakeRecipe&>(s) = plan.recipe;
    s.mode = mode;
    s.bounces = s.effectiveBounces();  // what the file records: 0 unless inter-reflected
    s.layout = plan.layout;
    s.bands = a.bands;
    s.rows = rows;
    BakedTransfer t;
    t.recipe = s;
    if (plan.texels) {
      const TexelPlan& tp = *plan.texels;
      announceTexels(mesh, s, tp, a.output);
      TexelBake tb =
          bakeTexels(mesh, *occluder, s, mesh.lightmapUvs, tp.resolution, tp.resolution, tp.padding,
                     &t.stats, progressBar(std::string("bake ") + toString(mode)));
      info(
          fmt::format("{}: {} texels sampled ({} of them inside geometry, refilled from their "
                      "neighbours)",
                      toString(mode), tb.samples.samples.size(), tb.invalid.size()));
      t.transfer = std::move(tb.transfer);
    } else {
      announce(mesh, s, a.output);
      t.transfer =
          bake(mesh, *occluder, s, &t.stats, progressBar(std::string("bake ") + toString(mode)));
    }
    report(t);
    refuseNonFinite(mesh, t);
    file.transfers.push_back(std::move(t));
  }
  if (plan.texels && plan.texels->seamFix) fixBakeSeams(file, a.output);
  writeBake(a.output, file);
  info(fmt::format("wrote {} ({}{} {} {}..{})", a.output, file.complete() ? "" : "partial: ",
                   rows.count, plan.texels ? "texels" : "vertices", rows.first, rows.end() - 1));
  writeReport(a, file);
}

}  // namespace

void addBakeCommand(CLI::App& root) {
  auto args = std::make_shared<BakeArgs>();
  auto* cmd = root.add_subcommand(
      "bake", "Bake SH transfer of a mesh or scene (per vertex or per texel) into a .glb");
  cmd->add_option(
         "inputs", args->inputs,
         "Mesh files (OBJ, PLY, OFF, glTF) or builtin:NAME; several are baked as one scene")
      ->required();
  cmd->add_option("--mode", args->modes,
                  "unshadowed | shadowed | interreflected; several in one file: repeat it "
                  "(--mode shadowed --mode interreflected) or list them (--mode "
                  "shadowed,interreflected)")
      ->required()
      ->type_name("MODE")
      ->allow_extra_args(false)
      ->delimiter(',');
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
                  "Bake only vertices (texels) FIRST:END (split bakes; merge later)");
  cmd->add_option("--domain", args->domain,
                  "vertices (transfer per vertex) | texels (per texel of a lightmap over the "
                  "mesh's lightmap UVs)")
      ->capture_default_str();
  cmd->add_option("--resolution", args->resolution,
                  "--domain texels: the lightmap's side in texels (default 512)")
      ->check(intRange(1, kMaxLightmapSide));
  cmd->add_option("--uv", args->uv,
                  "--domain texels: the UV set: auto (the lightmap set, glTF TEXCOORD_1, else the "
                  "texture set when it has no overlaps, else an atlas made as prt unwrap makes "
                  "it) | 1 | 0");
  cmd->add_option("--padding", args->padding,
                  "--domain texels: gutter texels dilated around the charts (default 2)")
      ->check(intRange(0, kMaxLightmapPadding));
  cmd->add_flag("--seam-fix", args->seamFix,
                "--domain texels: the least-squares seam fix (Sylvan 2015): texels on the two "
                "sides of a UV seam agree under bilinear filtering");
  cmd->add_option("-o,--output", args->output,
                  "Output bake file (.glb); with --pass K before the last, a pass file "
                  "(.prtpass)")
      ->required();
  cmd->add_option("--checkpoint", args->checkpoint,
                  "MPI: keep finished chunks in this folder; a rerun with the same settings "
                  "resumes from them");
  cmd->add_option("--chunk", args->chunk,
                  "MPI: vertices per chunk handed to a rank (default 256; matrices 1024/B^2)")
      ->check(unsignedInt(1u << 30));
  cmd->add_option("--shard", args->shard,
                  "Job arrays: bake shard I of N (I/N; auto: from SLURM_ARRAY_TASK_ID and "
                  "_COUNT, or JOB_COMPLETION_INDEX with auto/N); prt merge joins the pieces");
  cmd->add_option("--pass", args->pass,
                  "Job arrays: bake pass K only of an interreflected bake (0: direct; the last "
                  "writes the bake), its shard with --shard")
      ->check(intRange(0, 64));
  cmd->add_option("--previous", args->previous,
                  "With --pass K >= 1: the merged pass file of pass K-1");
  addJsonOption(cmd, args->json);
  cmd->footer(R"(On a cluster (docs/distributed.md):
  mpirun --hostfile hosts -np 4 --bind-to none prt bake scene.obj --mode interreflected -j 32 \
         --checkpoint /shared/ckpt -o scene.glb
    hosts: one line per node, "node01 slots=1": one rank per node (or socket), -j its cores.
  Slurm, a batch script (sbatch bake.sbatch):
    #SBATCH --nodes=8 --ntasks-per-node=1 --cpus-per-task=32 --mem=16G
    srun --mpi=pmix prt bake scene.obj --mode interreflected -j "$SLURM_CPUS_PER_TASK" -o scene.glb
  One bake across MPI ranks, bit-identical to one process: every rank loads the scene and builds
  its BVH; rank 0 hands out chunks of vertices (--chunk) to the ranks, whose threads share each
  chunk; each bounce pass is all-gathered; rank 0 writes the file. Memory per rank: the mesh,
  its BVH and two full-mesh passes (rank 0 also the output), as one process. A rank that dies
  ends the job with one line naming it and its chunk, no output; --checkpoint DIR resumes.
  prt reference and prt validate run across ranks the same way.
  Job arrays without MPI: --shard I/N (or auto) per task, then prt merge; interreflected bakes
  shard one --pass at a time, each reading the merged one before (--previous PASS.prtpass).)");
  cmd->callback([args] { runBake(*args); });
}

}  // namespace prt::cli
