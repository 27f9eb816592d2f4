#include "bake_setup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "prt/core/error.hpp"
#include "prt/core/units.hpp"
#include "prt/geometry/load.hpp"
#include "prt/transport/bake.hpp"
#include "prt/unwrap/unwrap.hpp"
#include "report.hpp"

namespace prt::cli {

namespace {

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

/// --grid: "auto", or NXxNYxNZ probes per axis (1..kMaxProbeSide each).
std::array<int, 3> parseGrid(const std::string& s) {
  if (s.empty() || s == "auto") return {0, 0, 0};
  std::array<int, 3> n{};
  char x1, x2, tail;
  if (std::sscanf(s.c_str(), "%d%c%d%c%d%c", &n[0], &x1, &n[1], &x2, &n[2], &tail) != 5 ||
      (x1 != 'x' && x1 != 'X') || (x2 != 'x' && x2 != 'X'))
    throw Error("--grid '" + s + "': expected auto or NXxNYxNZ probes per axis, e.g. 16x8x16");
  for (int v : n)
    if (v < 1 || v > kMaxProbeSide)
      throw Error(fmt::format("--grid {}: each count must lie in 1..{}", s, kMaxProbeSide));
  return n;
}

/// --bounds: "x0,y0,z0:x1,y1,z1", the low and high corners of the box the probes fill.
std::pair<Vec3f, Vec3f> parseBounds(const std::string& s) {
  Vec3f lo, hi;
  char colon, tail;
  if (std::sscanf(s.c_str(), "%f,%f,%f%c%f,%f,%f%c", &lo.x, &lo.y, &lo.z, &colon, &hi.x, &hi.y,
                  &hi.z, &tail) != 7 ||
      colon != ':')
    throw Error("--bounds '" + s + "': expected x0,y0,z0:x1,y1,z1 (the box's low and high corners)");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || lo[a] > hi[a])
      throw Error("--bounds " + s + ": the corners must be finite, low <= high on every axis");
  return {lo, hi};
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

}  // namespace

std::string secondsText(double s) {
  return s < 1 ? fmt::format("{:.0f} ms", s * 1e3) : fmt::format("{:.2f} s", s);
}

BakeRequest requestOf(const BakeArgs& a) {
  BakeRequest r;
  for (const std::string& m : a.modes) r.modes.push_back(parseTransferMode(m));
  r.layout = parseTransferLayout(a.transfer);
  r.bands = a.bands;
  r.basis = parseTransferBasis(a.basis);
  r.samples = a.samples >= 0 ? a.samples : defaultSamples(r.basis);
  r.bounces = a.bounces;
  r.seed = a.seed;
  r.sampling = parseSampling(a.sampling);
  r.targetError = a.targetError;
  if (!a.material.empty()) r.material = parseMaterial(a.material);
  if (!a.albedo.empty()) r.albedo = parseAlbedo(a.albedo);
  r.domain = parseTransferDomain(a.domain);
  const bool cubeResolution = r.basis == TransferBasis::Haar && r.domain != TransferDomain::Texels;
  if (r.basis == TransferBasis::Haar) {
    // The cube's side: --cube-resolution, or per vertex --resolution (per texel the lightmap's).
    if (a.cubeResolution && a.resolution && cubeResolution)
      throw Error(
          "--resolution and --cube-resolution both give the Haar cube's side of a "
          "per-vertex bake: give one");
    if (a.cubeResolution) r.haar.resolution = a.cubeResolution;
    if (a.resolution && cubeResolution) r.haar.resolution = a.resolution;
    if (a.terms) r.haar.terms = a.terms;
  } else if (a.terms || a.cubeResolution) {
    throw Error(std::string(a.terms ? "--terms is the Haar transfer's budget per row"
                                    : "--cube-resolution is the Haar cube's side") +
                ": add --basis haar");
  }
  if (r.domain == TransferDomain::Texels) {
    if (a.resolution) r.lightmap.resolution = a.resolution;
    if (a.padding >= 0) r.lightmap.padding = a.padding;
    if (!a.uv.empty()) r.lightmap.uv = parseUvSetOption(a.uv);
  } else if ((a.resolution && !cubeResolution) || a.padding >= 0 || !a.uv.empty()) {
    throw Error(
        "--resolution, --uv, --padding, --seam-fix and --denoise shape a lightmap: add --domain "
        "texels");
  }
  r.lightmap.seamFix = a.seamFix;
  r.lightmap.denoise = a.denoise;
  if (r.domain == TransferDomain::Probes) {
    r.probes.count = parseGrid(a.grid);
    if (!a.bounds.empty()) r.probes.bounds = parseBounds(a.bounds);
  } else if (!a.grid.empty() || !a.bounds.empty()) {
    throw Error("--grid and --bounds place probes: use prt probes (or --domain probes)");
  }
  checkBakeRequest(r, OptionSpelling::Cli);  // again with the rows, once they are known
  refuseModesAsInputs(a);
  return r;
}

void loadBakeScene(const BakeArgs& a, const BakeRequest& request, BakeFile& file) {
  LoadReport loadReport;
  file.mesh = loadScene(a.inputs, &loadReport);
  for (const auto& w : loadReport.warnings) warn(w);
  Mesh& mesh = file.mesh;
  BakeMeshPreparation prep = prepareBakeMesh(mesh, request);
  if (!prep.lightmapUvsFound) {
    // --uv auto, and no UV set of the mesh's own can hold the lightmap: prt unwrap's atlas at
    // this resolution and padding; the bake is of the unwrapped mesh, which the file keeps.
    UnwrapSettings us;
    us.resolution = request.lightmap.resolution;
    us.padding = request.lightmap.padding;
    UnwrapResult u = unwrap(mesh, us, progressBar("unwrap"),
                            [](const UnwrapFootprint& f) { info(describe(f)); });
    std::string why;
    for (const std::string& r : prep.uvSetsRefused) why += (why.empty() ? "" : "; ") + r;
    info(
        fmt::format("{}: no UV set of its own can hold the lightmap ({}): unwrapped it, {} charts "
                    "({} cut), {:.1f}% of the texels wasted, L2 stretch {:.3f}, in {} (prt "
                    "unwrap makes the same atlas)",
                    mesh.source, why, u.stats.charts, u.splitCharts, 100 * u.stats.wastedTexels,
                    u.stats.stretchL2, secondsText(u.stats.seconds)));
    u.mesh.source = mesh.source;
    mesh = std::move(u.mesh);
    BakeRequest atlas = request;
    atlas.lightmap.uv = UvSetOption::Lightmap;
    prep = prepareBakeMesh(mesh, atlas);
    prep.notes = {fmt::format("{}: a {} x {} lightmap over its atlas (prt unwrap) (padding {})",
                              mesh.source, us.resolution, us.resolution, us.padding)};
  }
  for (const std::string& n : prep.notes) info(n);
}

RowRange rangeOf(const BakeArgs& a, const BakeRequest& request, const Mesh& mesh) {
  const std::size_t rows = domainRows(mesh, bakeSettings(request, mesh, request.modes.front()));
  return a.range.empty() ? RowRange{0, rows} : parseRange(a.range, rows, rowName(request.domain));
}

std::pair<std::size_t, std::size_t> shardOf(const BakeArgs& a) {
  return a.shard.empty() ? std::pair<std::size_t, std::size_t>{0, 1} : parseShard(a.shard);
}

RowRange shardRows(RowRange rows, std::size_t i, std::size_t n) {
  const std::size_t lo = rows.count * i / n, hi = rows.count * (i + 1) / n;
  return {rows.first + lo, hi - lo};
}

bool skipEmptyShard(const BakeArgs& a, RowRange rows, std::size_t shard, std::size_t shards,
                    TransferDomain domain, std::size_t domainRows, int pass) {
  if (rows.count > 0) return false;
  const std::string what = pass >= 0 ? fmt::format("pass {} of shard", pass) : "shard";
  info(fmt::format("{} {} of {} holds none of the {} {} (more shards than {}): nothing to bake, "
                   "{} not written; prt merge joins the other shards' pieces",
                   what, shard, shards, domainRows, toString(domain), toString(domain), a.output));
  Report r("bake", a.json);
  if (r.wanted()) {
    for (const std::string& in : a.inputs) r.input(in);
    r["rows"] = {{"first", rows.first}, {"end", rows.first}, {"complete", false}};
    r["shard"] = {{"index", shard}, {"count", shards}, {"empty", true}};
    if (pass >= 0) r["pass"] = {{"index", pass}};
    r.write();
  }
  return true;
}

void announce(const Mesh& mesh, const BakeSettings& s, const std::string& output) {
  const char* row = rowName(s.domain);
  const std::string what = fmt::format("{} {}", toString(s.mode), toString(s.layout));
  const BakeFootprint fp = bakeFootprint(mesh, s);
  const RowRange rows{s.rows.first,
                      s.rows.count ? s.rows.count : domainRows(mesh, s) - s.rows.first};
  info(fmt::format("{}: {} per {}, {} in all{}", what, bytesText(fp.bytesPerRow), row,
                   bytesText(fp.transferBytes),
                   fp.workingBytes ? " + " + bytesText(fp.workingBytes) + " working" : ""));
  if (s.glossyBounces(s.layout))
    info(fmt::format(
        "{}: the bounces follow the material's lobe ({}): {} matrix passes over every {}", what,
        s.material.spec(), s.bounces + 1, row));
  else if (s.bounces > 0 && s.material.glossy())
    info(
        fmt::format("{}: its bounces treat every surface as diffuse (kd); --transfer matrix "
                    "bounces the light off the lobe too",
                    what));
  if (s.effectiveBounces() > 0 && rows.count < domainRows(mesh, s))
    info(fmt::format("{}: the bounces read every {}: a range bakes the earlier passes whole", what,
                     row));
  // The mesh and the JSON take a little of the file too: a margin of 64 MiB.
  const std::uint64_t fileRoom = kMaxBakeFileBytes - (std::uint64_t(1) << 26);
  if (fp.transferBytes > fileRoom)
    throw Error(output,
                fmt::format("{} transfer of {} {} at {} bands is {}, more than a bake file holds "
                            "({}); use fewer bands, fewer rows (--resolution per texel) or split "
                            "the bake with --range",
                            what, rows.count, toString(s.domain), s.bands,
                            bytesText(fp.transferBytes), bytesText(fileRoom)));
}

/// The bake's rays, timings and Monte Carlo error, in two lines.
void report(const BakedTransfer& t) {
  const BakeStats& st = t.stats;
  const char* mode = toString(t.mode());
  std::string bounces;
  for (std::size_t k = 0; k < st.secondsBounce.size(); ++k)
    bounces += fmt::format(", bounce {} {}", k + 1, secondsText(st.secondsBounce[k]));
  // Two rates, each over the time it divides by (issue 37): the whole bake's, over the time
  // printed beside it, and the ray-casting passes' own (BakeStats::raysPerSecond).
  info(fmt::format("{}: {} rays in {} ({:.3g} Mrays/s; {:.3g} Mrays/s while casting, {} threads); "
                   "direct {}{}",
                   mode, st.rays, secondsText(st.secondsTotal),
                   raysPerSecondOf(st.rays, st.secondsTotal) / 1e6, st.raysPerSecond / 1e6,
                   st.threads, secondsText(st.secondsDirect), bounces));
  info(
      fmt::format("{}: Monte Carlo std. error of T00 mean {:.2e} max {:.2e}; of white-sky "
                  "radiance mean {:.2e} max {:.2e}; {} channel(s)",
                  mode, st.stdErrT0Mean, st.stdErrT0Max, st.stdErrConstMean, st.stdErrConstMax,
                  t.transfer.channels()));
  if (t.recipe.adaptive())
    info(
        fmt::format("{}: adaptive sampling to a standard error of {:g}: {:.1f} rays per row and "
                    "pass on average ({} pilot, at most {})",
                    mode, t.recipe.targetError, st.raysPerRowAndPass(),
                    std::min(t.recipe.samples, kAdaptivePilotSamples), t.recipe.samples));
}

/// --json: the written bake (or pass file) and how it was made. `ranks` > 0 for an MPI run.
void writeReport(const BakeArgs& a, const BakeFile& file, int ranks, Json pass) {
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

}  // namespace prt::cli
