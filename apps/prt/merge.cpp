// prt merge: split bakes (prt bake --range) → one complete bake.
//
//   prt bake scene.obj --mode shadowed --range 0:50000 -o part0.glb      (machine A)
//   prt bake scene.obj --mode shadowed --range 50000: -o part1.glb       (machine B)
//   prt merge part0.glb part1.glb -o scene.glb
//
// The pieces must share the mesh, modes and settings and tile a vertex range without gaps or
// overlaps (in any order); the result is bit-identical to a bake of the union range, because a
// vertex's transfer depends only on the inputs, the seed and its global index.

#include <fmt/format.h>

#include "cli.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_file.hpp"

namespace prt::cli {

namespace {

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string output;
};

void runMerge(const MergeArgs& a) {
  if (a.inputs.size() < 2) throw Error("prt merge needs at least two bake files");
  if (fileExtension(a.output) != "glb") throw Error(a.output + ": the bake file must end in .glb");
  for (const std::string& in : a.inputs)
    if (in == a.output) throw Error(a.output + ": the output is also an input");
  checkWritable(a.output);
  std::vector<BakeFile> pieces;
  pieces.reserve(a.inputs.size());
  for (const std::string& in : a.inputs) pieces.push_back(readBake(in));
  const BakeFile merged = mergeBakes(std::move(pieces));
  writeBake(a.output, merged);
  info(fmt::format("wrote {} ({} vertices {}..{}{}, {} mode(s))", a.output, merged.vertexCount,
                   merged.firstVertex, merged.firstVertex + merged.vertexCount - 1,
                   merged.complete() ? ", complete" : ", still partial", merged.transfers.size()));
}

}  // namespace

void addMergeCommand(CLI::App& root) {
  auto args = std::make_shared<MergeArgs>();
  auto* cmd = root.add_subcommand("merge", "Merge split bakes (prt bake --range) into one");
  cmd->add_option("inputs", args->inputs, "Bake pieces (.glb), in any order")->required();
  cmd->add_option("-o,--output", args->output, "Output bake file (.glb)")->required();
  cmd->callback([args] { runMerge(*args); });
}

}  // namespace prt::cli
