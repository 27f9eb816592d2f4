#include "mpi_verb.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#if PRT_HAVE_MPI
#include <signal.h>
#include <unistd.h>
#endif

#include "cli.hpp"
#include "prt/core/error.hpp"
#include "stderr_line.hpp"

namespace prt::cli {

#if PRT_HAVE_MPI
namespace {

// A rank that dies ends the job with one line naming it and what it was doing, and no output
// (docs/distributed.md). The library writes that line; printing it and ending the process are
// ours. Two paths lead here, and the library lets only the first of them report: rank 0's
// watch (FatalFn, below), which sees a rank on its host die the moment it does, and the SIGTERM
// the runtime (mpirun, srun) sends when a rank exits. The other ranks' SIGTERM handler tells
// the watch they were stopped, so that the one named is the rank that died first.

constexpr int kExitRankDied = 1;
constexpr int kExitTerminated = 128 + SIGTERM;  // 143, as if SIGTERM had ended us

/// Writes all of [s, s + n) to stderr; async-signal-safe.
void writeAll(const char* s, std::size_t n) {
  while (n > 0) {
    const ssize_t k = ::write(STDERR_FILENO, s, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return;
    s += k;
    n -= static_cast<std::size_t>(k);
  }
}

// In static storage, not on the stack of whatever thread the signal lands on.
char g_terminationLine[distributed::kTerminationLineBytes];

/// Rank 0's SIGTERM handler: the line the library writes for the situation (the dead rank if it
/// ran on this host, else every rank's work), then leave at once. Only async-signal-safe calls:
/// describeTermination, write(2), _exit(2).
extern "C" void onTerminate(int) {
  const distributed::Termination t =
      distributed::describeTermination(g_terminationLine, sizeof g_terminationLine);
  writeAll(g_terminationLine, t.length);
  ::_exit(t.cause == distributed::Termination::Cause::RankDied ? kExitRankDied : kExitTerminated);
}

/// The other ranks' SIGTERM handler: tell the root's watch that this rank is being stopped (so
/// that it is never named as the rank that died), then end as SIGTERM does.
extern "C" void onStopped(int) {
  distributed::noteStopped();
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = SIG_DFL;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGTERM, &sa, nullptr);
  ::raise(SIGTERM);  // delivered as the handler returns
}

void setTerminateHandler(void (*handler)(int)) {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace
#endif

void refuseUnjoinedCopies(const std::string& verb) {
  const auto count = [](const char* name) {
    const char* v = std::getenv(name);
    return v ? std::atol(v) : 0L;
  };
  bool mpi = false;
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    mpi = mpi || std::getenv(v) != nullptr;
#if PRT_HAVE_MPI
  if (!mpi && count("SLURM_STEP_NUM_TASKS") > 1)
    throw Error(verb + " was started as " + std::to_string(count("SLURM_STEP_NUM_TASKS")) +
                " srun tasks without MPI wire-up (no PMI in the environment): each would do the "
                "whole work; use srun --mpi=pmix (or pmi2), or --shard for job arrays");
#else
  if ((mpi && count("OMPI_COMM_WORLD_SIZE") != 1) || count("SLURM_STEP_NUM_TASKS") > 1)
    throw Error(
        "this prt was built without MPI, so the copies a launcher started cannot share "
        "the work (each would do all of it): rebuild with Open MPI installed "
        "(scripts/setup.sh), or use --shard for job arrays");
#endif
}

MpiVerb::MpiVerb(const std::string& verb, bool refuseCopies) {
  if (refuseCopies) refuseUnjoinedCopies(verb);
#if PRT_HAVE_MPI
  if (!distributed::launchedByMpi()) return;
  // The watch calls this from rank 0's watch (or coordinator) thread while the main thread may
  // be computing: so _exit, not exit (no static destructors or atexit handlers, MPI's among
  // them, racing that thread); the runtime then ends the other ranks.
  session_ = std::make_unique<distributed::Session>(verb, [verb](const std::string& line) {
    printLine(verb + ": error: " + line);
    ::_exit(kExitRankDied);
  });
  if (session_->root()) {
    setTerminateHandler(onTerminate);
  } else {
    setTerminateHandler(onStopped);
    globals().quiet = globals().silent = true;
  }
#else
  (void)verb;
#endif
}

MpiVerb::~MpiVerb() {
#if PRT_HAVE_MPI
  // Taken down before MPI_Finalize: the ranks of a job that ends may be stopped, and that is no
  // failure to report. When the session leaves MPI as it is (this rank failed alone and is
  // unwinding), the handler stays: the job is failing, and a SIGTERM that ends it still says why.
  if (session_ && session_->willFinalize()) setTerminateHandler(SIG_DFL);
#endif
}

bool MpiVerb::active() const {
#if PRT_HAVE_MPI
  return session_ != nullptr;
#else
  return false;
#endif
}
bool MpiVerb::root() const {
  return rank() == 0;
}
int MpiVerb::rank() const {
#if PRT_HAVE_MPI
  if (session_) return session_->rank();
#endif
  return 0;
}
int MpiVerb::size() const {
#if PRT_HAVE_MPI
  if (session_) return session_->size();
#endif
  return 1;
}

void MpiVerb::run(const std::function<void()>& body) {
#if PRT_HAVE_MPI
  if (session_) {
    try {
      body();
    } catch (const distributed::AgreedFailure&) {
      // Every rank agreed on the failure, and rank 0 reports it. This rank leaves in order and
      // with status 0: one that exits non-zero makes the runtime (mpirun, srun) stop the others
      // at once, rank 0 among them, maybe before it has printed the failure — the job then
      // said nothing but the runtime's banner. Rank 0 exits 1, which is the job's status.
      return;
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      if (session_->root()) throw;
      // Before the ranks first agreed, a failure is most likely every rank's (the same inputs):
      // rank 0 reports it. After, it is this rank's own.
      if (!session_->agreedOnce()) {
        session_->leaveQuietly();
        throw QuietFailure();
      }
      throw Error("rank " + std::to_string(session_->rank()) + ": " + e.what());
    }
    return;
  }
#endif
  body();
}

void MpiVerb::collective(const std::function<void()>& fn) {
#if PRT_HAVE_MPI
  if (session_) {
    std::exception_ptr failure;
    try {
      fn();
    } catch (...) {
      failure = std::current_exception();
    }
    session_->agree(failure);
    return;
  }
#endif
  fn();
}

std::unique_ptr<PassExecutor> MpiVerb::bakeExecutor(const RankOptions& options) const {
#if PRT_HAVE_MPI
  if (session_) {
    distributed::RunOptions o;
    o.chunkRows = options.chunkRows;
    o.checkpoint = options.checkpoint;
    o.spillFolder = options.spillFolder;
    o.spillAbove = options.spillAbove;
    return std::make_unique<distributed::RankExecutor>(*session_, o);
  }
#else
  (void)options;
#endif
  return std::make_unique<ThreadExecutor>();
}

std::vector<std::string> MpiVerb::bakeExchange(const PassExecutor& executor) const {
  std::vector<std::string> lines;
#if PRT_HAVE_MPI
  const auto* ranks = dynamic_cast<const distributed::RankExecutor*>(&executor);
  if (!ranks || !root()) return lines;
  const distributed::RunReport& rep = ranks->report();
  if (rep.spilled)
    lines.push_back(
        "rank 0 kept the transfer in a mapped scratch file beside the output, not "
        "in memory");
  for (std::size_t j = 0; j < rep.jobs.size(); ++j) {
    const distributed::JobStats& js = rep.jobs[j];
    // What moved: each rank receives the rows it did not compute, (N − 1) × the pass's bytes
    // over all ranks for an all-gather (rank 0 alone, its share, for the last pass); rank 0
    // also receives each row's variance (8 B) for the error estimate.
    lines.push_back(fmt::format(
        "{}: {} chunks ({} on rank 0{}), {:.3f} s, exchange {:.3f} s; rows received {} B "
        "({:.2f} x the pass's {} B), variances {} B",
        rep.names[j], js.chunks, js.chunksHere,
        js.chunksResumed ? fmt::format(", {} from the checkpoint", js.chunksResumed)
                         : std::string(),
        js.seconds, js.exchangeSeconds, js.rowBytesAll,
        double(js.rowBytesAll) / double(std::max<std::uint64_t>(rep.passBytes[j], 1)),
        rep.passBytes[j], js.sideBytesAll));
  }
#else
  (void)executor;
#endif
  return lines;
}

render::ReferenceResult MpiVerb::reference(const Mesh& mesh, const Occluder& occluder,
                                           const envmap::Environment& env,
                                           const render::ReferenceSettings& settings,
                                           const ProgressFn& progress) {
#if PRT_HAVE_MPI
  if (session_)
    return distributed::renderReference(*session_, mesh, occluder, env, settings, {},
                                        session_->root() ? progress : ProgressFn{});
#endif
  return render::renderReference(mesh, occluder, env, settings, progress);
}

}  // namespace prt::cli
