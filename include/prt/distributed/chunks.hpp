#pragma once
// The one scheduler every distributed verb runs on: a table of rows, computed in chunks that
// rank 0 hands out dynamically (the cost of a row varies a lot — an occluded vertex casts
// bounce rays, an open one none — so a static split would leave ranks idle), each chunk by all
// the threads of the rank that takes it, then all-gathered (every rank gets every row: the
// input of the next bake pass) or gathered to rank 0 (the last pass, which rank 0 writes).
//
// Rank 0 runs the coordinator on a thread of its own beside its share of the work; it answers
// each request with the next chunk, and between requests it watches the ranks on its host
// (Session::watch), so a rank that dies is named with the chunk it held. With a checkpoint
// folder, each finished chunk is written there (core/file.hpp: complete or not at all) and a
// rerun with the same settings loads the chunks it finds instead of computing them.
//
// Rows come out bit for bit whoever computes them (the jobs' compute functions are pure
// functions of the row index), so the result does not depend on the ranks, the threads, the
// order chunks are handed out in, or what a checkpoint held.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "prt/core/progress.hpp"
#include "prt/distributed/session.hpp"

namespace prt::distributed {

struct RowJob {
  std::string name;              ///< for messages: "pass 1 'bounce 1'"
  std::size_t rows = 0;          ///< rows [0, rows) of the job
  std::size_t firstRow = 0;      ///< the global index of row 0 (messages name global rows)
  std::string rowNoun = "rows";  ///< "vertices"
  std::size_t chunkRows = 256;   ///< rows per chunk
  std::size_t rowBytes = 0;      ///< bytes per row that are gathered
  std::size_t sideBytes = 0;     ///< bytes per row gathered to rank 0 only (error estimates)
  bool allGather = true;         ///< every rank gets every row; else rank 0 only
  /// Computes rows [lo, hi) into rows (hi − lo rows of rowBytes) and side (of sideBytes);
  /// returns the rays cast.
  std::function<std::uint64_t(std::size_t lo, std::size_t hi, unsigned char* rows,
                              unsigned char* side)>
      compute;
  std::string checkpoint;  ///< folder for this job's finished chunks ("" for none)
  /// What the job computes (a hash of the bake's identity and the pass): written into each
  /// checkpointed chunk, and a chunk whose identity differs is refused.
  std::uint64_t identity = 0;
};

struct JobStats {
  std::uint64_t rays = 0;           ///< all ranks' (on rank 0; this rank's elsewhere)
  double seconds = 0;               ///< wall time of the job, exchange included
  double exchangeSeconds = 0;       ///< of which the all-gather or gather
  std::uint64_t bytesReceived = 0;  ///< rows and side bytes, by this rank
  std::uint64_t rowBytesAll = 0;    ///< rows received by all ranks together (on rank 0)
  std::uint64_t sideBytesAll = 0;   ///< side bytes received by rank 0
  std::size_t chunks = 0;           ///< in the job
  std::size_t chunksHere = 0;       ///< computed by this rank
  std::size_t chunksResumed = 0;    ///< loaded from the checkpoint
};

/// Runs `job` over every rank of `session` (collective). `rows`: rows × rowBytes bytes on every
/// rank for an all-gather, on rank 0 for a gather (elsewhere it may be null); `side`: rows ×
/// sideBytes on rank 0 (may be null elsewhere). `progress` (rank 0) gets the share of chunks
/// done. The test hook PRT_TEST_EXIT_AT_CHUNK=R:C makes rank R exit at once (status 3, no
/// message: a crash) when it is handed its C-th chunk of the run (from 0).
JobStats runJob(Session& session, const RowJob& job, unsigned char* rows, unsigned char* side,
                const ProgressFn& progress = {});

}  // namespace prt::distributed
