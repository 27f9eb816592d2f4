// prt bake --pass K [--shard I/N] [--previous PASS.prtpass]: one pass of a multi-pass bake as a
// job-array task (docs/distributed.md), where no MPI joins the tasks. The library's one pass
// driver (prt/transport/passes.hpp) runs pass K on a shard executor from the state the merged
// pass K − 1 left (a pass file); the passes before the last write pass files, the last a bake
// piece that prt merge joins, bit for bit what one process bakes — per vertex or per texel.

#include <fmt/format.h>

#include <chrono>

#include "bake_setup.hpp"
#include "cli.hpp"
#include "guard.hpp"
#include "mpi_verb.hpp"
#include "prt/transport/bake.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/io/pass_file.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transport/bake_request.hpp"
#include "prt/transport/passes.hpp"
#include "report.hpp"

namespace prt::cli {

namespace {

/// One shard of a pass: the rows shardRows(pass rows, I, N) of the passes a later one reads;
/// the last pass whole (its passes were made with the shard of the bake's range as their range,
/// so that per texel it covers the shard widened by the dilation's reach).
class ShardExecutor : public ThreadExecutor {
 public:
  ShardExecutor(std::size_t shard, std::size_t shards) : shard_(shard), shards_(shards) {}
  Rows run(const BakePasses& passes, int k, const PassSource& input,
           const ProgressFn& progressFn) override {
    if (k == passes.count() - 1) return ThreadExecutor::run(passes, k, input, progressFn);
    const auto t0 = std::chrono::steady_clock::now();
    const BakePassInfo& p = passes.pass(k);
    TransferShape shape = p.shape;
    shape.rows = shardRows(p.shape.rows, shard_, shards_);
    Rows r;
    r.values = Transfer::zeros(shape);
    if (p.variance) r.variance.assign(shape.rows.count, 0.0);
    Progress progress(progressFn, shape.rows.count);
    r.rays = passes.compute(k, shape.rows, input, r.values.mutableValues(),
                            p.variance ? r.variance.data() : nullptr, &progress);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }

 private:
  std::size_t shard_, shards_;
};

/// The state the merged pass K − 1 left, from its pass file.
PassState stateOf(const PassPiece& piece) {
  PassState st;
  st.done = piece.pass + 1;
  st.previous = Transfer::dense(piece.shape, piece.values);
  if (piece.sumChannels) {
    TransferShape sum = piece.shape;
    sum.layout = TransferLayout::Vector;
    sum.channels = piece.sumChannels;
    st.sum = Transfer::dense(sum, piece.sum);
  }
  st.varianceRows = piece.shape.rows;
  st.variance = piece.variance;
  st.rays = piece.rays;
  st.seconds = piece.seconds;
  return st;
}

/// The pass file of a state after pass K (not the last).
PassPiece pieceOf(const PassState& st, const BakePasses& passes, const std::string& identity) {
  PassPiece piece;
  piece.identity = identity;
  piece.pass = st.done - 1;
  piece.passes = passes.count();
  piece.name = passes.pass(piece.pass).name;
  piece.shape = st.previous.shape();
  piece.values = st.previous.values();
  piece.sumChannels = st.sum.empty() ? 0 : st.sum.channels();
  if (!st.sum.empty()) piece.sum = st.sum.values();
  piece.variance = st.variance;
  piece.rays = st.rays;
  piece.seconds = st.seconds;
  return piece;
}

}  // namespace

void runPassBake(const BakeArgs& a) {
  MpiVerb mpi("prt bake", false);
  if (mpi.active())
    throw Error(
        "--pass splits a bake for job arrays without MPI; under mpirun the ranks share the "
        "work (drop --pass and --shard)");
  if (!a.checkpoint.empty()) throw Error("--checkpoint keeps the chunks of an MPI run, not --pass");
  const BakeRequest request = requestOf(a);
  if (request.modes.size() != 1 || request.modes[0] != TransferMode::Interreflected ||
      request.bounces == 0)
    throw Error(
        "--pass bakes one pass of an interreflected bake with bounces: give one --mode "
        "interreflected (the other modes bake in one pass: --shard alone splits them)");
  if (request.lightmap.seamFix)
    throw Error(
        "--seam-fix needs the whole lightmap: bake the passes without it, then prt merge "
        "--seam-fix the last pass's pieces");
  if (request.lightmap.denoise)
    throw Error(
        "--denoise needs the whole lightmap: bake the passes without it, merge the last pass's "
        "pieces, then prt denoise the merged bake");
  std::vector<NamedPath> inputs;
  for (const std::string& in : a.inputs) inputs.push_back({"input", in});
  if (!a.previous.empty()) inputs.push_back({"--previous", a.previous});
  checkOutputs({{"-o", a.output}}, inputs);
  checkWritable(a.output);
  Report("bake", a.json).check({{"-o", a.output}}, inputs);

  BakeFile file;
  loadBakeScene(a, request, file);
  const Mesh& mesh = file.mesh;
  const auto occluder = makeEmbreeOccluder(mesh);
  const auto [shard, shards] = shardOf(a);
  BakeSettings s = bakeSettings(request, mesh, request.modes[0]);
  s.rows = rangeOf(a, request, mesh);
  const std::string identity = bakeIdentity(mesh, s);
  const int k = a.pass;
  std::unique_ptr<BakePasses> passes = std::make_unique<BakePasses>(mesh, *occluder, s);
  const int count = passes->count();
  if (k >= count) throw Error(fmt::format("--pass {}: this bake has passes 0..{}", k, count - 1));
  const BakePassInfo p = passes->pass(k);  // (a copy: the passes of the last are remade)
  const bool last = k == count - 1;
  const std::string ext = fileExtension(a.output);
  if (!last && ext != "prtpass")
    throw Error(a.output, fmt::format("pass {} of {} ('{}') is written to a pass file (.prtpass); "
                                      "the last pass, {}, writes the bake",
                                      k, count, p.name, count - 1));
  if (last && ext != "glb") throw Error(a.output, "the last pass writes the bake (.glb)");
  const char* rowsNoun = toString(s.domain);
  PassState state;
  if (k > 0) {
    if (a.previous.empty())
      throw Error(
          fmt::format("--pass {} reads pass {}: give --previous PASS{}.prtpass (its merged pieces)",
                      k, k - 1, k - 1));
    const PassPiece prev = readPassPiece(a.previous);
    if (prev.identity != identity)
      throw Error(a.previous, "is a pass of another bake (" + prev.identity + ")");
    if (prev.pass != k - 1)
      throw Error(a.previous, fmt::format("is pass {}, not {}", prev.pass, k - 1));
    if (!(prev.shape.rows == passes->pass(k - 1).shape.rows))
      throw Error(a.previous,
                  fmt::format("holds {} {}..{} of pass {} only: merge all its pieces first",
                              rowsNoun, prev.shape.rows.first, prev.shape.rows.end() - 1, k - 1));
    state = stateOf(prev);
  } else {
    if (!a.previous.empty()) throw Error("--previous: pass 0 reads no earlier pass");
    state = startPasses(*passes);
  }
  if (skipEmptyShard(a, shardRows(last ? s.rows : p.shape.rows, shard, shards), shard, shards,
                     s.domain, domainRows(mesh, s), k))
    return;
  // The last pass of a shard is the bake of the shard of the range (per texel its rows widen
  // by the dilation's reach).
  if (last && shards > 1) {
    s.rows = shardRows(s.rows, shard, shards);
    passes = std::make_unique<BakePasses>(mesh, *occluder, s);
  }
  const RowRange rows = last ? passes->resultShape().rows : shardRows(p.shape.rows, shard, shards);
  info(fmt::format("pass {} of {} ('{}'): {} {}..{} (shard {} of {})", k, count, p.name, rowsNoun,
                   rows.first, rows.end() - 1, shard, shards));
  const auto t0 = std::chrono::steady_clock::now();
  ShardExecutor executor(shard, shards);
  runPass(*passes, executor, state, progressBar(std::string("bake ") + toString(s.mode)));
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::uint64_t rays = state.rays.back();
  const Json passJson = {{"index", k},          {"count", count},    {"name", p.name},
                         {"first", rows.first}, {"end", rows.end()}, {"rays", rays},
                         {"seconds", secs},     {"shard", shard},    {"shards", shards}};
  if (!last) {
    writePassPiece(a.output, pieceOf(state, *passes, identity));
    info(fmt::format("wrote {} (pass {} of {}, {} {}..{}, {} rays)", a.output, k, count, rowsNoun,
                     rows.first, rows.end() - 1, rays));
    if (!a.json.empty()) {
      Report r("bake", a.json);
      for (const std::string& in : a.inputs) r.input(in);
      if (k > 0) r.input(a.previous);
      r.output(a.output);
      r["mesh"] = meshJson(mesh);
      r["pass"] = passJson;
      r.write();
    }
    return;
  }
  // The last pass: a bake piece of these rows. The earlier passes' rays and seconds are the
  // whole passes': shard 0 carries them, so that merging the pieces counts them once.
  if (shard != 0)
    for (int j = 0; j + 1 < count; ++j) state.rays[j] = 0, state.seconds[j] = 0;
  BakedTransfer t;
  t.recipe = s;
  t.transfer = finishPasses(*passes, state, secs, executor.threads(), &t.stats);
  refuseNonFinite(mesh, s.mode, t.transfer);
  report(t);
  file.transfers.push_back(std::move(t));
  writeBake(a.output, file);
  info(fmt::format("wrote {} (last pass, {}{} {} {}..{})", a.output,
                   file.complete() ? "" : "partial: ", rows.count, rowsNoun, rows.first,
                   rows.end() - 1));
  writeReport(a, file, 0, passJson);
}

}  // namespace prt::cli
