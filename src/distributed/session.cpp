#include "prt/distributed/session.hpp"

#include <mpi.h>
#include <signal.h>
#include <unistd.h>

#include <fcntl.h>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "mpi_util.hpp"
#include "prt/core/hash.hpp"
#include "prt/core/error.hpp"

namespace prt::distributed {

namespace {

// What describeTermination and the watch read: plain arrays set up once by the session, each
// rank's activity line double-buffered so that a signal handler never reads one being written.
constexpr std::size_t kLine = 400;    ///< bytes of a rank's activity line, NUL included
constexpr std::size_t kPrefix = 160;  ///< bytes of "prt bake: error: ", NUL included
constexpr int kNamedRanks = 64;       ///< ranks a "stopped" line names, so it stays readable
struct WatchState {
  int size = 0;
  std::vector<long> pid;
  std::vector<char> local;  ///< on the root's host
  std::vector<char> lines;  ///< size × 2 × kLine
  std::unique_ptr<std::atomic<int>[]> which;
  char prefix[kPrefix] = {};
  FatalFn fatal;
};
WatchState* g_watch = nullptr;
// Set by whoever reports the end first (the watch or the SIGTERM handler), so that one line is
// printed. atomic_flag: the one atomic type sure to be lock-free, hence usable in a handler.
std::atomic_flag g_reported = ATOMIC_FLAG_INIT;
static_assert(std::atomic<int>::is_always_lock_free, "the handler reads `which`");
// The longest "stopped" line: the prefix, the fixed words, and per named rank "; rank NN was "
// and its activity.
static_assert(kTerminationLineBytes >= kPrefix + 160 + kNamedRanks * (16 + kLine),
              "describeTermination's line must fit the room the header promises");

const char* activityOf(int r) {
  const WatchState& w = *g_watch;
  return &w.lines[(static_cast<std::size_t>(r) * 2 + w.which[r].load()) * kLine];
}

/// Builds a line in a caller's buffer with no allocation and no lock, so the SIGTERM handler
/// can use it; what does not fit is cut, keeping room for the newline and the NUL.
class LineWriter {
 public:
  LineWriter(char* out, std::size_t size) : out_(out), size_(size) {
    if (size_) out_[0] = 0;
  }
  void add(const char* s) {
    while (*s && n_ + 2 < size_) out_[n_++] = *s++;
  }
  void addInt(long v) {
    char buf[24];
    int i = 23;
    buf[i] = 0;
    const bool neg = v < 0;
    unsigned long u = neg ? 0UL - static_cast<unsigned long>(v) : static_cast<unsigned long>(v);
    do {
      buf[--i] = static_cast<char>('0' + u % 10);
      u /= 10;
    } while (u && i > 1);
    if (neg) buf[--i] = '-';
    add(buf + i);
  }
  /// Ends the line with a newline (when `newline`) and a NUL; returns its length, NUL excluded.
  std::size_t finish(bool newline) {
    if (size_ < 2) return 0;
    if (newline) out_[n_++] = '\n';
    out_[n_] = 0;
    return n_;
  }

 private:
  char* out_;
  std::size_t size_;
  std::size_t n_ = 0;
};

/// "rank R (pid P) died while ACTIVITY; stopped, no output written": the watch's line and the
/// handler's, one text.
void addDeadRank(LineWriter& line, int r) {
  const WatchState& w = *g_watch;
  line.add("rank ");
  line.addInt(r);
  line.add(" (pid ");
  line.addInt(w.pid[r]);
  line.add(") died while ");
  line.add(activityOf(r));
  line.add("; stopped, no output written");
}

/// Whether a local process has exited (gone, or a zombie not yet reaped by its launcher, which
/// still answers kill(pid, 0)). Async-signal-safe, so the watch and the SIGTERM handler share it.
bool processGone(long pid) {
  if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH) return true;
  char path[48] = "/proc/";
  char num[24];
  int i = 23;
  num[i] = 0;
  unsigned long u = static_cast<unsigned long>(pid);
  do {
    num[--i] = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u && i > 0);
  std::strcat(path, num + i);
  std::strcat(path, "/stat");
  const int fd = ::open(path, O_RDONLY);
  if (fd < 0) return true;
  char buf[512];
  const ssize_t n = ::read(fd, buf, sizeof buf - 1);
  ::close(fd);
  if (n <= 0) return true;
  buf[n] = 0;
  const char* paren = std::strrchr(buf, ')');
  return paren && paren[1] == ' ' && (paren[2] == 'Z' || paren[2] == 'X');
}

std::uint64_t hostHash() {
  char name[256] = {};
  ::gethostname(name, sizeof name - 1);
  Fnv1a h;
  h.add(name, std::strlen(name));
  return h.value();
}

}  // namespace

Termination describeTermination(char* buffer, std::size_t size) noexcept {
  LineWriter line(buffer, size);
  Termination t;
  if (!g_watch || g_reported.test_and_set()) return t;
  const WatchState& w = *g_watch;
  line.add(w.prefix);
  // The rank that died, if it ran on this host.
  for (int r = 1; r < w.size; ++r)
    if (w.local[r] && processGone(w.pid[r])) {
      addDeadRank(line, r);
      t.cause = Termination::Cause::RankDied;
      t.length = line.finish(true);
      return t;
    }
  // Else every rank's work: one of them, elsewhere, is the one that died.
  line.add("the MPI runtime stopped the job (a rank on another host died, or the job was killed):");
  for (int r = 0; r < w.size && r < kNamedRanks; ++r) {
    line.add(r ? "; rank " : " rank ");
    line.addInt(r);
    line.add(" was ");
    line.add(activityOf(r));
  }
  line.add("; no output written");
  t.cause = Termination::Cause::Stopped;
  t.length = line.finish(true);
  return t;
}

bool launchedByMpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE",
                        "MPI_LOCALNRANKS", "MV2_COMM_WORLD_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

Session::Session(const std::string& verb, FatalFn fatal)
    : verb_(verb), uncaught_(std::uncaught_exceptions()) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised) throw Error("MPI: one session per process");
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
    throw Error("MPI: MPI_Init_thread failed");
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw Error(
        "MPI: the library gives no MPI_THREAD_SERIALIZED support (rank 0's coordinator "
        "thread needs it)");
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  // Who runs where: process ids and hosts, for the watch.
  std::int64_t mine[2] = {static_cast<std::int64_t>(::getpid()),
                          static_cast<std::int64_t>(hostHash())};
  std::vector<std::int64_t> all(2 * static_cast<std::size_t>(size_));
  MPI_Allgather(mine, 2, MPI_INT64_T, all.data(), 2, MPI_INT64_T, MPI_COMM_WORLD);
  if (rank_ == 0) {
    auto* w = new WatchState;  // lives to the end of the process (the handler reads it)
    w->size = size_;
    w->fatal = std::move(fatal);
    for (int r = 0; r < size_; ++r) {
      w->pid.push_back(static_cast<long>(all[2 * r]));
      w->local.push_back(all[2 * r + 1] == all[1]);
    }
    w->lines.assign(static_cast<std::size_t>(size_) * 2 * kLine, 0);
    w->which.reset(new std::atomic<int>[static_cast<std::size_t>(size_)]);
    for (int r = 0; r < size_; ++r) {
      w->which[r] = 0;
      std::snprintf(&w->lines[static_cast<std::size_t>(r) * 2 * kLine], kLine, "starting");
    }
    std::snprintf(w->prefix, sizeof w->prefix, "%s: error: ", verb.c_str());
    g_watch = w;
  }
}

Session::~Session() {
  if (!willFinalize()) return;  // see the header
  MPI_Finalize();
}

bool Session::willFinalize() const {
  return std::uncaught_exceptions() <= uncaught_ || agreedFailure_;
}

void Session::agree(std::exception_ptr failure) {
  int mine = failure ? rank_ : size_, lowest = size_;
  MPI_Allreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (lowest == size_) {
    agreedOnce_ = true;
    return;
  }
  std::string message;
  if (rank_ == lowest) {
    try {
      std::rethrow_exception(failure);
    } catch (const std::exception& e) {
      message = e.what();
    } catch (...) {
      message = "unknown failure";
    }
  }
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, lowest, MPI_COMM_WORLD);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, lowest, MPI_COMM_WORLD);
  agreedFailure_ = true;
  if (rank_ == 0 && lowest == 0) std::rethrow_exception(failure);
  if (rank_ == 0) throw Error("rank " + std::to_string(lowest) + ": " + message);
  throw AgreedFailure();
}

void Session::barrier() {
  MPI_Request req;
  MPI_Ibarrier(MPI_COMM_WORLD, &req);
  detail::politeWait(&req, nullptr);
}

std::uint64_t Session::reserveChunks(std::size_t count) {
  const std::uint64_t first = nextChunk_;
  nextChunk_ += count;
  return first;
}

void Session::setActivity(int r, const std::string& what) {
  if (!g_watch || r < 0 || r >= g_watch->size) return;
  WatchState& w = *g_watch;
  const int next = 1 - w.which[r].load();
  char* line = &w.lines[(static_cast<std::size_t>(r) * 2 + next) * kLine];
  std::snprintf(line, kLine, "%s", what.c_str());
  w.which[r].store(next);
}

void Session::watch() {
  if (!g_watch || !g_watch->fatal) return;
  const WatchState& w = *g_watch;
  for (int r = 1; r < w.size; ++r) {
    if (!w.local[r] || !processGone(w.pid[r])) continue;
    // Reported already (by the SIGTERM handler, which then ends the process, or by an earlier
    // call whose FatalFn returned): one line is enough.
    if (g_reported.test_and_set()) return;
    char buf[kLine + 128];
    LineWriter line(buf, sizeof buf);
    addDeadRank(line, r);
    const std::size_t n = line.finish(false);
    w.fatal(std::string(buf, n));
    return;
  }
}

}  // namespace prt::distributed
