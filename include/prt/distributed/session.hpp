#pragma once
// One MPI job (Open MPI, or any MPI-3 library): start-up and shut-down, who is who, agreeing on
// failures, and the watch over the other ranks that turns a dead rank into one line naming it
// and the chunk it held. Compiled only when CMake's find_package(MPI) finds MPI (target
// prt_distributed); nothing else in the library includes it. See docs/distributed.md.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>

namespace prt::distributed {

/// True when this process was started by an MPI launcher (mpirun/mpiexec of Open MPI, MPICH's
/// Hydra, Slurm's srun with PMI or PMIx): the environment names a rank and a world size.
bool launchedByMpi();

/// Called (once, from any thread) with one line when the job cannot go on: a rank died. It
/// should print the line; the session then ends the process (exit status 1), and the MPI
/// runtime ends the others.
using FatalFn = std::function<void(const std::string& line)>;

class Session {
 public:
  /// MPI_Init_thread (MPI_THREAD_SERIALIZED: one thread at a time calls MPI — the main thread,
  /// or rank 0's coordinator while its main thread computes); exchanges the ranks' process ids
  /// and hosts. `verb` ("prt bake") starts the lines a watch prints. Throws prt::Error when MPI
  /// does not start or gives less thread support. One session per process.
  Session(const std::string& verb, FatalFn fatal);
  /// MPI_Finalize after a normal end or an agreed failure; when unwinding an exception the
  /// others did not agree to (a failure on this rank alone) it leaves MPI as it is, so the
  /// process exits non-zero and the runtime ends the job.
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  /// Collective: every rank passes its failure (or null). When any rank failed, every rank
  /// throws: the failure of the lowest failing rank, as prt::Error with its message on the
  /// root, and AgreedFailure elsewhere (the root reports it; the others exit quietly).
  void agree(std::exception_ptr failure);
  /// True once agree() has passed: failures after it are this rank's own (the others are
  /// past the same point), failures before it most likely every rank's (the same inputs).
  bool agreedOnce() const { return agreedOnce_; }
  /// A Barrier that sleeps between polls instead of spinning, so waiting ranks leave the cores
  /// to working ones (ranks share cores when oversubscribed, and threads share them always).
  void barrier();
  /// Bytes this rank received from the others so far (all-gathers and gathers of chunks).
  std::uint64_t bytesReceived() const { return bytesReceived_; }
  void addBytesReceived(std::uint64_t n) { bytesReceived_ += n; }
  /// The first global number of the next job's chunks (chunks are numbered across the jobs of
  /// a run in order, for the fault-test hook and for messages); reserves `count`.
  std::uint64_t reserveChunks(std::size_t count);

  // The watch (root only): what each rank is doing, for the line that names a dead rank.
  /// Sets the line that names rank r's current work ("chunk 5 of 'bounce 1' (vertices
  /// 1280..1535)"); async-signal-safe to read.
  void setActivity(int r, const std::string& what);
  /// Checks the ranks on the root's host; when one has died, reports it through `fatal` and
  /// ends the process. Cheap (a kill(pid, 0) per local rank).
  void watch();
  const std::string& verb() const { return verb_; }

 private:
  int rank_ = 0, size_ = 1;
  std::string verb_;
  std::uint64_t bytesReceived_ = 0;
  std::uint64_t nextChunk_ = 0;
  bool agreedFailure_ = false;
  bool agreedOnce_ = false;
  int uncaught_ = 0;
};

/// Thrown on the ranks other than the root by Session::agree: the root reports the failure.
struct AgreedFailure : std::exception {
  const char* what() const noexcept override { return "failure reported by rank 0"; }
};

}  // namespace prt::distributed
