// prt probes: a scene → relightable probes in the space around it → bake file (.glb) (issue 32).
//
//   prt probes builtin:cornell -o box-probes.glb                  (an automatic grid: 16 cells
//                                                                    along the longest side)
//   prt probes scene.obj --grid 32x16x16 --bounds -4,0,-4:4,3,4 --bands 3 -o probes.glb
//
// At each probe the transfer matrix from the distant light to the light arriving there from
// every direction: shadowed by the scene, with the light its surfaces send back (--bounces, their
// albedo) — Sloan, Kautz & Snyder 2002, §7 (prt/transfer/probe_grid.hpp). It is prt bake over the
// probe domain (--domain probes --transfer matrix): the same request, pass driver, determinism,
// ranges, shards, MPI ranks, progress and memory statement; only the defaults differ here.

#include <memory>

#include "bake_setup.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "prt/transfer/probe_grid.hpp"
#include "report.hpp"

namespace prt::cli {

void addProbesCommand(CLI::App& root) {
  auto args = std::make_shared<BakeArgs>();
  args->domain = "probes";
  args->transfer = "matrix";
  args->modes = {"interreflected"};
  auto* cmd = root.add_subcommand(
      "probes",
      "Bake relightable probes: the transfer of distant light to points of a grid in a scene "
      "(shadowed, with the light its surfaces bounce), for the objects that move through it");
  cmd->add_option(
         "inputs", args->inputs,
         "Mesh files (OBJ, PLY, OFF, glTF) or builtin:NAME; several are baked as one scene")
      ->required();
  cmd->add_option("--grid", args->grid,
                  "auto (" + std::to_string(kAutoProbeCells) +
                      " cells along the longest side) | NXxNYxNZ probes per axis; a probe at "
                      "each cell's centre")
      ->default_str("auto");
  cmd->add_option("--bounds", args->bounds,
                  "x0,y0,z0:x1,y1,z1: the box the grid fills (default: the scene's bounds)");
  cmd->add_option("--mode", args->modes,
                  "interreflected (default: shadowed and bounced light) | shadowed | unshadowed")
      ->type_name("MODE")
      ->allow_extra_args(false)
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--bands", args->bands, "SH bands B (a B² x B² matrix per probe)")
      ->capture_default_str();
  cmd->add_option("--samples", args->samples,
                  "Directions per probe (over the whole sphere; default 1024)");
  cmd->add_option("--bounces", args->bounces, "Inter-reflection bounces (interreflected mode)")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Random seed (results are identical for any thread count)")
      ->check(unsignedInt())
      ->capture_default_str();
  cmd->add_option("--albedo", args->albedo,
                  "Uniform albedo r,g,b of the surfaces the bounces leave (overrides the mesh's)");
  cmd->add_option("--range", args->range, "Bake only probes FIRST:END (split bakes; merge later)");
  cmd->add_option("-o,--output", args->output, "Output bake file (.glb)")->required();
  cmd->add_option("--checkpoint", args->checkpoint,
                  "MPI: keep finished chunks in this folder; a rerun resumes from them");
  cmd->add_option("--chunk", args->chunk, "MPI: probes per chunk handed to a rank")
      ->check(unsignedInt(1u << 30));
  cmd->add_option("--shard", args->shard,
                  "Job arrays: bake shard I of N (I/N or auto); prt merge joins the pieces "
                  "(shadowed: an interreflected bake shards one --pass at a time with prt bake)");
  addJsonOption(cmd, args->json);
  cmd->footer(R"(Probe (x, y, z) is row x + NX*(y + NY*z) of the bake, at the centre of its cell of the bounds.
Probes inside geometry (most rays meet the backs of surfaces) are refilled from their neighbours.
The same bake: prt bake SCENE --domain probes --transfer matrix --mode interreflected --grid ...
docs/probes.md: the grid, the matrices, relighting them, and what reads them.)");
  cmd->callback([args] { runBake(*args); });
}

}  // namespace prt::cli
