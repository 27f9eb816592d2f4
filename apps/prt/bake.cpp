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
//            -o pass1-3.prtpass                                        (a job array's bounces:
//                                                                       bake_passes.cpp)
//
// The options become one BakeRequest (bake_setup.cpp), baked by the library's one pass driver on
// an executor — this process's threads, or the ranks of an MPI job when mpirun started prt —
// with no branch on the domain or on MPI here.

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>

#include "bake_setup.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "mpi_verb.hpp"
#include "prt/transport/bake.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/parallel.hpp"
#include "prt/geometry/texel_sampling.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transport/bake_request.hpp"
#include "report.hpp"
#include "denoise.hpp"
#include "seam_fix.hpp"
#include "transfer_options.hpp"

namespace prt::cli {

void runPassBake(const BakeArgs& a);  // bake_passes.cpp

namespace {

/// Where an MPI run keeps its checkpoints and spills (docs/distributed.md): rank 0 keeps a
/// matrix transfer that would not fit its memory in a mapped scratch file beside the output
/// (PRT_MPI_SPILL_ABOVE=BYTES lowers the threshold, for tests).
RankOptions rankOptions(const BakeArgs& a) {
  RankOptions o;
  o.chunkRows = a.chunk;
  o.checkpoint = a.checkpoint;
  if (!isStandardOutput(a.output)) {
    const std::string parent = std::filesystem::path(a.output).parent_path().string();
    o.spillFolder = parent.empty() ? "." : parent;
  }
  if (const char* v = std::getenv("PRT_MPI_SPILL_ABOVE")) o.spillAbove = std::stoull(v);
  return o;
}

}  // namespace

void runBake(const BakeArgs& a) {
  if (a.pass >= 0) {
    runPassBake(a);
    return;
  }
  // A job array's tasks are separate by design (--shard); other copies must join over MPI.
  MpiVerb mpi("prt bake", a.shard.empty());
  mpi.run([&] {
    BakeRequest request;
    BakeFile file;
    RowRange rows;
    bool emptyShard = false;
    std::unique_ptr<Occluder> occluder;
    mpi.collective([&] {
      if (mpi.active() && !a.shard.empty())
        throw Error(
            "--shard splits a bake for job arrays without MPI; under mpirun the ranks share the "
            "work (drop it)");
      if (!mpi.active() && !a.checkpoint.empty())
        throw Error(
            "--checkpoint keeps the finished chunks of an MPI run: start prt under mpirun "
            "(mpirun -np 1 works)" +
            std::string(PRT_HAVE_MPI ? ""
                                     : "; this prt was built without MPI (scripts/setup.sh "
                                       "installs Open MPI; rebuild)"));
      if (!a.previous.empty()) throw Error("--previous goes with --pass");
      request = requestOf(a);
      if (fileExtension(a.output) != "glb" && !isStandardOutput(a.output))
        throw Error(a.output + ": the bake file must end in .glb");
      if (mpi.root()) {
        std::vector<NamedPath> inputs;
        for (const std::string& in : a.inputs) inputs.push_back({"input", in});
        checkOutputs({{"-o", a.output}}, inputs);
        checkWritable(a.output);
        Report("bake", a.json).check({{"-o", a.output}}, inputs);
      }
      const auto t0 = std::chrono::steady_clock::now();
      loadBakeScene(a, request, file);
      const auto [shard, shards] = shardOf(a);
      rows = shardRows(rangeOf(a, request, file.mesh), shard, shards);
      // (--shard runs without MPI: this process alone.)
      emptyShard = skipEmptyShard(
          a, rows, shard, shards, request.domain,
          domainRows(file.mesh, bakeSettings(request, file.mesh, request.modes.front())));
      if (emptyShard) return;
      request.rows = rows;
      checkBakeRequest(request, OptionSpelling::Cli);
      const bool bounces =
          request.bounces > 0 && std::find(request.modes.begin(), request.modes.end(),
                                           TransferMode::Interreflected) != request.modes.end();
      if (shards > 1 && bounces)
        throw Error(
            "--shard of an interreflected bake shards its passes one at a time: add --pass 0, "
            "prt merge the pieces, then --pass 1 --previous MERGED.prtpass, and so on (prt "
            "bake --help, docs/distributed.md)");
      const double loadSeconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const auto t1 = std::chrono::steady_clock::now();
      occluder = makeEmbreeOccluder(file.mesh);
      const double bvhSeconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      const Mesh& mesh = file.mesh;
      info(fmt::format("{}: {} vertices, {} triangles, {} part(s); loaded in {}, BVH in {}",
                       mesh.source, mesh.vertexCount(), mesh.triangleCount(), mesh.parts.size(),
                       secondsText(loadSeconds), secondsText(bvhSeconds)));
    });
    if (emptyShard) return;
    if (mpi.active()) info(fmt::format("{} MPI ranks x {} threads", mpi.size(), maxThreads()));
    const std::unique_ptr<PassExecutor> executor = mpi.bakeExecutor(rankOptions(a));
    BakeObserver observer;
    observer.starting = [&](const BakeSettings& s) { announce(file.mesh, s, a.output); };
    observer.progress = [&](const BakeSettings& s) {
      return mpi.root() ? progressBar(std::string("bake ") + toString(s.mode)) : ProgressFn{};
    };
    observer.finished = [&](const BakeResult& r) {
      if (!mpi.root()) return;
      for (const std::string& line : mpi.bakeExchange(*executor))
        info(fmt::format("{}: {}", toString(r.settings.mode), line));
      if (r.texelsSampled > 0)
        info(
            fmt::format("{}: {} texels sampled ({} of them inside geometry, refilled from "
                        "their neighbours)",
                        toString(r.settings.mode), r.texelsSampled, r.texelsInside));
      BakedTransfer t;
      t.recipe = r.settings;
      t.transfer = r.transfer;
      t.stats = r.stats;
      report(t);
      file.transfers.push_back(std::move(t));
    };
    bake(request, file.mesh, *occluder, *executor, observer);
    if (!mpi.root()) return;
    if (request.lightmap.denoise) denoiseBake(file, a.output, DenoiseSettings{});
    if (request.lightmap.seamFix) fixBakeSeams(file, a.output);
    writeBake(a.output, file);
    info(fmt::format("wrote {} ({}{} {} {}..{})", a.output, file.complete() ? "" : "partial: ",
                     rows.count, toString(request.domain), rows.first, rows.end() - 1));
    writeReport(a, file, mpi.active() ? mpi.size() : 0);
  });
}

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
                  "SH bands B (B² coefficients; the course's SHOrder 2 = 3 bands); --basis "
                  "haar --mode interreflected: the bands of each row's bounce, 1..5")
      ->capture_default_str();
  cmd->add_option("--samples", args->samples,
                  "Directions per vertex (default 1024); --basis haar: rays per cube texel "
                  "(default 1)");
  cmd->add_option("--basis", args->basis,
                  "sh (spherical harmonics of --bands bands) | haar (all-frequency: Haar "
                  "wavelets over a cube map of --resolution² texels per face, each row pruned "
                  "to its --terms largest coefficients; Ng et al. 2003)")
      ->capture_default_str();
  cmd->add_option("--cube-resolution", args->cubeResolution,
                  "--basis haar: the cube's side, 2..256, a power of two (default 32; per "
                  "vertex --resolution says it too)")
      ->check(intRange(1, kMaxLightmapSide));
  cmd->add_option("--terms", args->terms,
                  "--basis haar: wavelet coefficients kept per row, vertex or texel (default 64; 4 "
                  "bytes each in the file)");
  cmd->add_option("--bounces", args->bounces, "Inter-reflection bounces (interreflected mode)")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Random seed (results are identical for any thread count)")
      ->check(unsignedInt())
      ->capture_default_str();
  cmd->add_option(
         "--sampling", args->sampling,
         "cosine (cosine-weighted Sobol'; also: sobol) | uniform (the course's uniform random)")
      ->capture_default_str();
  cmd->add_option("--target-error", args->targetError,
                  "Adaptive sampling: each row casts a pilot of 64 directions, then as many as "
                  "its standard error of radiance under the unit sky needs to reach this (a "
                  "power of two, at most --samples); deterministic. 0: off (every row casts "
                  "--samples)")
      ->type_name("E");
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
                  "mesh's lightmap UVs) | probes (a grid in space: prt probes)")
      ->capture_default_str();
  cmd->add_option("--resolution", args->resolution,
                  "--domain texels: the lightmap's side in texels (default 512); --basis haar "
                  "per vertex: the cube's side, 2..256, a power of two (default 32; per texel: "
                  "--cube-resolution)")
      ->check(intRange(1, kMaxLightmapSide));
  cmd->add_option("--uv", args->uv,
                  "--domain texels: the UV set: auto (the lightmap set, glTF TEXCOORD_1, else the "
                  "texture set when it has no overlaps, else an atlas made as prt unwrap makes "
                  "it) | 1 | 0");
  cmd->add_option("--padding", args->padding,
                  "--domain texels: gutter texels dilated around the charts (default 2)")
      ->check(intRange(0, kMaxLightmapPadding));
  cmd->add_flag("--denoise", args->denoise,
                "--domain texels: filter the lightmap's noise (an edge-avoiding a-trous filter "
                "within each chart, prt denoise --help), before any --seam-fix");
  cmd->add_flag("--seam-fix", args->seamFix,
                "--domain texels: the least-squares seam fix (Sylvan 2015): texels on the two "
                "sides of a UV seam agree under bilinear filtering");
  cmd->add_option("--grid", args->grid,
                  "--domain probes: auto | NXxNYxNZ probes per axis (prt probes --help)");
  cmd->add_option("--bounds", args->bounds,
                  "--domain probes: x0,y0,z0:x1,y1,z1, the box the grid fills (default: the "
                  "scene's bounds)");
  cmd->add_option("-o,--output", args->output,
                  "Output bake file (.glb); with --pass K before the last, a pass file "
                  "(.prtpass)")
      ->required();
  cmd->add_option("--checkpoint", args->checkpoint,
                  "MPI: keep finished chunks in this folder; a rerun with the same settings "
                  "resumes from them");
  cmd->add_option("--chunk", args->chunk,
                  "MPI: rows (vertices or texels) per chunk handed to a rank (default 256; "
                  "matrices 1024/B^2)")
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
  its BVH; rank 0 hands out chunks of rows (--chunk) to the ranks, whose threads share each
  chunk; each bounce pass is all-gathered; rank 0 writes the file. Memory per rank: the mesh,
  its BVH and two full-mesh passes (rank 0 also the output), as one process. A rank that dies
  ends the job with one line naming it and its chunk, no output; --checkpoint DIR resumes.
  prt reference and prt validate run across ranks the same way.
  Job arrays without MPI: --shard I/N (or auto) per task, then prt merge; interreflected bakes
  shard one --pass at a time, each reading the merged one before (--previous PASS.prtpass).)");
  cmd->callback([args] { runBake(*args); });
}

}  // namespace prt::cli
