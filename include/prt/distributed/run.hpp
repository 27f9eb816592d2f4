#pragma once
// The distributed verbs: one bake, reference or validation run across the ranks of an MPI job,
// bit-identical to the single-process run for any number of ranks and threads. Each is the
// chunk scheduler (chunks.hpp) driven over the library's own split of the work — the bake's
// passes (prt/transport/passes.hpp), the reference's vertex entries (render::ReferenceRows) —
// never a copy of the algorithm. See docs/distributed.md.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/distributed/chunks.hpp"
#include "prt/distributed/session.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/reference.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/transfer.hpp"
#include "prt/transport/passes.hpp"

namespace prt::distributed {

struct RunOptions {
  std::size_t chunkRows = 0;  ///< rows per chunk; 0: defaultChunkRows of each pass
  std::string checkpoint;     ///< folder keeping finished chunks ("" for none)
  /// Where rank 0 may keep the last pass of a matrix bake in a file-backed mapping instead of
  /// memory (a temporary there, unlinked at once, so nothing is left behind): when the
  /// transfer and the working buffers would take more than `spillAbove` bytes of its memory.
  /// "" keeps it in memory always.
  std::string spillFolder;
  std::size_t spillAbove = 0;  ///< 0: half of this machine's physical memory
};

/// Rows per chunk by default: enough work per chunk (tens of milliseconds at 1024 samples) that
/// handing it out costs nothing, small enough that the last chunks even out the ranks.
std::size_t defaultChunkRows(bool matrix, int bands);

/// What a distributed run did, per job (pass), on rank 0.
struct RunReport {
  std::vector<std::string> names;
  std::vector<JobStats> jobs;
  std::vector<std::uint64_t> passBytes;  ///< each pass's rows, 4 · rows · stride
  std::uint64_t bytesReceived = 0;       ///< by rank 0, all jobs
  int ranks = 1, threads = 0;            ///< threads: summed over the ranks
  bool spilled = false;  ///< rank 0 kept the last pass in a file-backed mapping
};

/// The ranks of an MPI job as a bake's executor (prt/transport/passes.hpp), collective: each
/// pass is computed in chunks the ranks take in turn (chunks.hpp), all-gathered when a later
/// pass reads it, the last gathered to rank 0, which gets the transfer and the statistics (as
/// bake() reports them, `threads` summed over the ranks); the other ranks get an empty Transfer.
/// Memory per rank: the passes a later pass reads, whole (as one process); the last pass, only
/// the rank's own chunks — on rank 0 the whole transfer, in memory or, beyond
/// RunOptions::spillAbove, in a file-backed mapping that the bake writer streams from. With a
/// checkpoint folder, each mode's finished chunks are kept in a folder of its own there, and a
/// rerun resumes from them. Throws what bake() throws, on every rank alike (Session::agree), and
/// prt::Error when the checkpoint folder holds another bake's or a rank lacks the memory (naming
/// it and the figure).
class RankExecutor : public PassExecutor {
 public:
  RankExecutor(Session& session, const RunOptions& options);
  BakePassOptions passOptions() const override;
  void begin(const BakePasses& passes) override;
  void agree(std::exception_ptr failure) override;
  Rows run(const BakePasses& passes, int k, const PassSource& input,
           const ProgressFn& progress) override;
  int threads() const override;
  /// Rows per chunk of a pass of `shape`.
  std::size_t chunkRows(const TransferShape& shape) const;
  /// What the last bake begun did (on rank 0).
  const RunReport& report() const { return report_; }

 private:
  Session& session_;
  RunOptions options_;
  int threads_;
  bool spill_ = false;
  std::string checkpoint_, claimPending_;
  std::string checkpointIdentity_;  ///< what each checkpointed chunk of this bake is hashed with
  RunReport report_;
};

/// bake() across the ranks (collective) with a RankExecutor.
Transfer bake(Session& session, const Mesh& mesh, const Occluder& occluder,
              const BakeSettings& settings, const RunOptions& options, BakeStats* stats = nullptr,
              RunReport* report = nullptr, const ProgressFn& progress = {});

/// render::renderReference across the ranks (collective); every rank gets the whole result.
render::ReferenceResult renderReference(Session& session, const Mesh& mesh,
                                        const Occluder& occluder, const envmap::Environment& env,
                                        const render::ReferenceSettings& settings,
                                        const RunOptions& options, const ProgressFn& progress = {});

}  // namespace prt::distributed
