#pragma once
// One MPI job (Open MPI, or any MPI-3 library): start-up and shut-down, who is who, agreeing on
// failures, and the watch over the other ranks that turns a dead rank into one line naming it
// and the chunk it held. Compiled only when CMake's find_package(MPI) finds MPI (target
// prt_distributed); nothing else in the library includes it. See docs/distributed.md.
//
// The library never prints and never ends the process: it keeps what the ranks are doing and
// writes the line; the app (apps/prt/mpi_verb.cpp) prints it and exits, from its FatalFn and
// from the SIGTERM handler it installs on the root (which calls describeTermination).

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

/// Called (once, from the root's watch thread, or its coordinator thread in Session::watch) with
/// one line when the job cannot go on: a rank on the root's host died ("rank 1 (pid 4242) died
/// while computing chunk 56 of ...; stopped, no output written"). The rank named is the first
/// whose process ended without saying it would (see Session): the watch thread sees each end
/// the moment it happens, before the runtime stops the other ranks. The session neither prints
/// the line nor ends the process: the caller should do both (prt prints the line and exits with
/// status 1, and the MPI runtime then ends the other ranks); SIGTERM is blocked in the calling
/// thread meanwhile. If it returns, the job waits for the runtime to end it.
using FatalFn = std::function<void(const std::string& line)>;

/// Room for the longest line describeTermination writes (its newline and NUL included).
inline constexpr std::size_t kTerminationLineBytes = 32 * 1024;

/// What the root can say when the MPI runtime ends the job with SIGTERM (describeTermination).
struct Termination {
  enum class Cause {
    Silent,    ///< nothing to say: no session's root here, or the end is already being reported
    RankDied,  ///< a rank on this host has died: the line names it and what it was doing
    Stopped,   ///< none here died (one on another host did, or the job was killed): the line
               ///< names what every rank was doing
  };
  Cause cause = Cause::Silent;
  std::size_t length = 0;  ///< bytes of the line written, its newline included (the NUL not)
};

/// For the root's SIGTERM handler, which the caller installs (the runtime, mpirun or srun,
/// ends the job with SIGTERM when a rank dies; the watch has normally reported it by then):
/// writes into `buffer` the one line that names the dead rank if it ran on this host — the
/// first the watch saw die, else one whose process ended without a word —, else every rank's
/// work ("prt bake: error: ..." and a newline, NUL-terminated, cut to `size`). It claims the
/// report, so that one line is printed however the watch and the handler race: Silent (and an
/// empty line) once the watch or an earlier call has claimed it — after waiting (up to 3 s) for
/// a report being written on another thread, whose FatalFn normally ends the process, so that
/// the caller does not end it first with nothing printed. Async-signal-safe: no allocation, no
/// lock, only kill(2), nanosleep(2), and open(2) and read(2) of /proc.
Termination describeTermination(char* buffer, std::size_t size) noexcept;

/// For the SIGTERM handler of the ranks other than the root, which the caller installs: tells
/// the root's watch that this rank is being stopped (the runtime ending the job after another
/// rank died), so that it is never the one named. The handler should then end the process as
/// SIGTERM would. Async-signal-safe (one send(2)).
void noteStopped() noexcept;

class Session {
 public:
  /// MPI_Init_thread (MPI_THREAD_SERIALIZED: one thread at a time calls MPI — the main thread,
  /// or rank 0's coordinator while its main thread computes); exchanges the ranks' process ids
  /// and hosts. `verb` ("prt bake") starts the lines a watch prints. Throws prt::Error when MPI
  /// does not start or gives less thread support. One session per process.
  ///
  /// The watch: the root starts a thread (it makes no MPI call) that holds a line, a Unix
  /// socket, to each rank on its host (Linux; elsewhere, or where a line cannot be opened, the
  /// root polls that rank's pid instead). A rank that leaves in order says so on its line first
  /// (~Session before MPI_Finalize, leaveQuietly, noteStopped); a line that drops without a word
  /// is a death, seen the moment the process ends, and reported through `fatal` at once.
  Session(const std::string& verb, FatalFn fatal);
  /// MPI_Finalize after a normal end or an agreed failure (on the other ranks, first telling the
  /// root's watch that this rank is leaving); when unwinding an exception the others did not
  /// agree to (a failure on this rank alone) it leaves MPI as it is, so the process exits
  /// non-zero and the runtime ends the job — and the root names this rank as one that died. On
  /// the root it first stops the watch thread.
  ~Session();
  /// On the ranks other than the root: this rank fails before the ranks first agreed, most
  /// likely as every rank does (the same inputs), and leaves the report to the root: the watch
  /// does not report this process's end as a death (the root's SIGTERM handler still names the
  /// rank if the root itself went on).
  void leaveQuietly();
  /// Whether destroying the session now would call MPI_Finalize (see ~Session), so that the
  /// caller can take down its SIGTERM handler first: the runtime may stop the other ranks as
  /// the job ends, and that is no failure to report.
  bool willFinalize() const;
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
  /// 1280..1535)"); async-signal-safe to read (describeTermination).
  void setActivity(int r, const std::string& what);
  /// Checks the ranks on the root's host that hold no line to the watch thread (by their pids);
  /// when one has died, passes the line naming it to `fatal` (once, and not after the watch
  /// thread or describeTermination has claimed the report; with no `fatal`, to no one). It
  /// neither prints nor exits: `fatal` does. Cheap (a kill(pid, 0) per such rank).
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
