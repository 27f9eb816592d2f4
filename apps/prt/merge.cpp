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

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "guard.hpp"
#include "seam_fix.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_merge.hpp"
#include "prt/io/pass_file.hpp"
#include "report.hpp"

namespace prt::cli {

namespace {

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string output;
  bool seamFix = false;  ///< --seam-fix: of the merged per-texel bake
  std::string json;
};

/// --json's report of a merge (nothing when not wanted), checked before any work.
Report mergeReport(const MergeArgs& a, const std::vector<NamedPath>& inputs) {
  Report r("merge", a.json);
  r.check({{"-o", a.output}}, inputs);
  for (const std::string& in : a.inputs) r.input(in);
  r.output(a.output);
  return r;
}

/// Merges pieces (each with the file it came from) in the order of their first row, one at a time,
/// so that an error names the file that does not fit ("part1.glb: overlaps the previous range").
template <class Piece, class FirstRow, class MergeTwo>
Piece mergeInRowOrder(std::vector<std::pair<Piece, std::string>> pieces, FirstRow firstRow,
                      MergeTwo mergeTwo) {
  std::stable_sort(pieces.begin(), pieces.end(), [&](const auto& x, const auto& y) {
    return firstRow(x.first) < firstRow(y.first);
  });
  Piece merged = std::move(pieces.front().first);
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    std::vector<Piece> two;
    two.push_back(std::move(merged));
    two.push_back(std::move(pieces[k].first));
    try {
      merged = mergeTwo(std::move(two));
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      std::string msg = e.what();
      if (msg.rfind("merge: ", 0) == 0) msg.erase(0, 7);
      throw Error(pieces[k].second, msg);
    }
  }
  return merged;
}

/// Pass files (prt bake --pass K --shard I/N) merge into one pass file of the whole pass.
void runMergePasses(const MergeArgs& a) {
  if (fileExtension(a.output) != "prtpass")
    throw Error(a.output + ": merged pass files make a pass file (.prtpass)");
  std::vector<NamedPath> inputs;
  for (const std::string& in : a.inputs) inputs.push_back({"input", in});
  checkOutputs({{"-o", a.output}}, inputs);
  checkWritable(a.output);
  Report report = mergeReport(a, inputs);
  std::vector<std::pair<PassPiece, std::string>> pieces;
  for (const std::string& in : a.inputs) pieces.emplace_back(readPassPiece(in), in);
  const PassPiece merged = mergeInRowOrder(
      std::move(pieces), [](const PassPiece& p) { return p.shape.rows.first; },
      [](std::vector<PassPiece> two) { return mergePassPieces(std::move(two)); });
  writePassPiece(a.output, merged);
  const RowRange rows = merged.shape.rows;
  info(fmt::format("wrote {} (pass {} of {} '{}', {} {}..{})", a.output, merged.pass,
                   merged.passes, merged.name, toString(merged.shape.domain), rows.first,
                   rows.end() - 1));
  report["pass"] = {{"index", merged.pass},  {"count", merged.passes}, {"name", merged.name},
                    {"first", rows.first},   {"end", rows.end()},      {"rays", merged.rays},
                    {"seconds", merged.seconds}};
  report.write();
}

void runMerge(const MergeArgs& a) {
  const bool passFiles =
      !a.inputs.empty() && std::all_of(a.inputs.begin(), a.inputs.end(), [](const std::string& in) {
        return fileExtension(in) == "prtpass";
      });
  if (passFiles) {
    if (a.seamFix) throw Error("--seam-fix is of merged per-texel bakes, not pass files");
    runMergePasses(a);
    return;
  }
  if (a.inputs.size() < 2) throw Error("prt merge needs at least two bake files");
  if (fileExtension(a.output) != "glb" && !isStandardOutput(a.output))
    throw Error(a.output + ": the bake file must end in .glb");
  std::vector<NamedPath> inputs;
  for (const std::string& in : a.inputs) inputs.push_back({"input", in});
  checkOutputs({{"-o", a.output}}, inputs);
  checkWritable(a.output);
  Report report = mergeReport(a, inputs);
  // Read every piece, then merge them in vertex order (mergeInRowOrder).
  std::vector<std::pair<BakeFile, std::string>> pieces;
  pieces.reserve(a.inputs.size());
  for (const std::string& in : a.inputs) {
    pieces.emplace_back(readBake(in), in);
    for (const BakedTransfer& t : pieces.back().first.transfers)
      if (t.transfer.compressed())
        throw Error(in, "holds compressed transfer (" + t.describe() +
                            "), which cannot be merged: merge the uncompressed pieces, then "
                            "compress");
  }
  BakeFile merged = mergeInRowOrder(
      std::move(pieces), [](const BakeFile& f) { return f.rows().first; },
      [](std::vector<BakeFile> two) { return mergeBakes(std::move(two)); });
  if (a.seamFix) fixBakeSeams(merged, a.output);
  writeBake(a.output, merged);
  const RowRange rows = merged.rows();
  info(fmt::format("wrote {} ({} {} {}..{}{}, {} mode(s))", a.output, rows.count,
                   toString(merged.domain()), rows.first,
                   rows.end() - 1, merged.complete() ? ", complete" : ", still partial",
                   merged.transfers.size()));
  report["mesh"] = meshJson(merged.mesh);
  report["rows"] = {{"first", rows.first}, {"end", rows.end()}, {"complete", merged.complete()}};
  report["transfers"] = Json::array();
  for (const BakedTransfer& t : merged.transfers) report["transfers"].push_back(transferJson(t));
  report.write();
}

}  // namespace

void addMergeCommand(CLI::App& root) {
  auto args = std::make_shared<MergeArgs>();
  auto* cmd = root.add_subcommand("merge",
                                  "Merge split bakes (prt bake --range, --shard) into one, or the "
                                  "pass files of one pass (--pass K --shard I/N)");
  cmd->add_option("inputs", args->inputs,
                  "Bake pieces (.glb) or pass files (.prtpass), in any order")
      ->required();
  cmd->add_option("-o,--output", args->output, "Output bake file (.glb)")->required();
  cmd->add_flag("--seam-fix", args->seamFix,
                "Per-texel bakes: the least-squares seam fix of the merged lightmap (Sylvan "
                "2015; as prt bake --seam-fix)");
  addJsonOption(cmd, args->json);
  cmd->callback([args] { runMerge(*args); });
}

}  // namespace prt::cli
