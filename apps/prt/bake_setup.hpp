#pragma once
// prt bake's options and what every way of running it shares (bake.cpp: one process or MPI
// ranks; bake_passes.cpp: one pass of a job array): the options as a BakeRequest, the scene
// loaded and prepared for it, the rows (--range, --shard), and the reports.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "prt/core/json.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/transport/bake_request.hpp"

namespace prt::cli {

struct BakeArgs {
  std::vector<std::string> inputs;
  std::vector<std::string> modes;
  int bands = 3;
  long long samples = -1;  // −1: not given (the basis's default); wide, so absurd counts get
                           // our message
  std::string basis = "sh";
  int terms = 0;  ///< Haar: terms kept per row; 0: not given (the request's default)
  int cubeResolution = 0;  ///< --cube-resolution: the Haar cube's side; 0: not given
  int bounces = 1;
  std::uint64_t seed = 0;
  std::string sampling = "cosine";
  double targetError = 0;  ///< --target-error: adaptive sampling (0: off)
  std::string albedo;
  std::string transfer = "vector";
  std::string material;
  std::string range;
  std::string output;
  // Per-texel transfer (docs/transport.md): the lightmap and the UV set it is over.
  std::string domain = "vertices";
  int resolution = 0;    ///< 0: not given (the request's default)
  std::string uv;        ///< "": not given (auto)
  int padding = -1;      ///< −1: not given (the request's default)
  bool seamFix = false;  ///< --seam-fix
  bool denoise = false;  ///< --denoise
  // Probes (prt probes, --domain probes): the grid and the box it fills.
  std::string grid;    ///< "auto" or NXxNYxNZ; "": not given (auto)
  std::string bounds;  ///< "x0,y0,z0:x1,y1,z1"; "": the scene's bounds
  // Distributed and split bakes (docs/distributed.md).
  std::string checkpoint;  ///< MPI: folder of finished chunks
  std::size_t chunk = 0;   ///< MPI: rows per chunk (0: the default)
  std::string shard;       ///< I/N, auto, auto/N: one shard of the work (job arrays)
  int pass = -1;           ///< one pass of a multi-pass bake (job arrays)
  std::string previous;    ///< the merged pass file of pass K − 1
  std::string json;        ///< --json: the report
};

/// Runs prt bake with these options (bake.cpp): prt probes is prt bake over a probe grid.
void runBake(const BakeArgs& a);

/// The options as a request (its rows still the whole domain), checked before anything is
/// loaded: one line naming the option on the first problem.
BakeRequest requestOf(const BakeArgs& a);

/// Loads the scene into file.mesh and prepares it for the request (prepareBakeMesh: material,
/// albedo, lightmap UVs; per texel with --uv auto and no set that can hold the lightmap, prt
/// unwrap's atlas), telling what it chose.
void loadBakeScene(const BakeArgs& a, const BakeRequest& request, BakeFile& file);

/// The rows --range names of the request's domain on `mesh` (the whole domain without it).
RowRange rangeOf(const BakeArgs& a, const BakeRequest& request, const Mesh& mesh);
/// --shard: (I, N), or (0, 1) without it.
std::pair<std::size_t, std::size_t> shardOf(const BakeArgs& a);
/// Shard i of n of rows: [first + ⌊i·count/n⌋, first + ⌊(i+1)·count/n⌋).
RowRange shardRows(RowRange rows, std::size_t i, std::size_t n);
/// A shard with no rows (more shards than rows: N > count): says so, writes the --json report
/// (rows first..first, no output) and returns true; the caller then writes nothing and exits 0,
/// and prt merge joins the other shards' pieces. False for a shard that holds rows.
bool skipEmptyShard(const BakeArgs& a, RowRange rows, std::size_t shard, std::size_t shards,
                    TransferDomain domain, std::size_t domainRows, int pass = -1);

/// States the memory of one mode's bake before the work, and refuses, naming `output`, what a
/// bake file cannot hold.
void announce(const Mesh& mesh, const BakeSettings& s, const std::string& output);
/// The bake's rays, timings and Monte Carlo error, in two lines.
void report(const BakedTransfer& t);
/// --json: the written bake (or pass file) and how it was made. `ranks` > 0 for an MPI run.
void writeReport(const BakeArgs& a, const BakeFile& file, int ranks = 0, Json pass = nullptr);

/// The time `s` (seconds) as a short string: "850 ms", "2.31 s".
std::string secondsText(double s);

}  // namespace prt::cli
