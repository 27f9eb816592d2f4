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

// What the SIGTERM handler and the watch read: plain arrays set up once by the session, each
// rank's activity line double-buffered so that a handler never reads one being written.
constexpr std::size_t kLine = 400;
struct WatchState {
  int size = 0;
  std::vector<long> pid;
  std::vector<char> local;  ///< on the root's host
  std::vector<char> lines;  ///< size × 2 × kLine
  std::unique_ptr<std::atomic<int>[]> which;
  char prefix[160] = {};
  FatalFn fatal;
};
WatchState* g_watch = nullptr;
std::atomic<bool> g_reported{false};

const char* activityOf(int r) {
  const WatchState& w = *g_watch;
  return &w.lines[(static_cast<std::size_t>(r) * 2 + w.which[r].load()) * kLine];
}

// Async-signal-safe pieces for the handler: write(2) of fixed buffers and integers.
void put(const char* s) {
  const ssize_t ignored = ::write(STDERR_FILENO, s, std::strlen(s));
  (void)ignored;
}
void putInt(long v) {
  char buf[24];
  int i = 23;
  buf[i] = 0;
  const bool neg = v < 0;
  unsigned long u = neg ? static_cast<unsigned long>(-v) : static_cast<unsigned long>(v);
  do {
    buf[--i] = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u && i > 1);
  if (neg) buf[--i] = '-';
  put(buf + i);
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

/// The runtime (mpirun, srun) ends the job with SIGTERM when a rank dies: name the rank that
/// died if it ran on this host, else every rank's work, in one line; then leave.
extern "C" void onTerminate(int) {
  if (!g_watch || g_reported.exchange(true)) ::_exit(143);
  const WatchState& w = *g_watch;
  for (int r = 1; r < w.size; ++r)
    if (w.local[r] && processGone(w.pid[r])) {
      put(w.prefix);
      put("rank ");
      putInt(r);
      put(" (pid ");
      putInt(w.pid[r]);
      put(") died while ");
      put(activityOf(r));
      put("; stopped, no output written\n");
      ::_exit(1);
    }
  put(w.prefix);
  put("the MPI runtime stopped the job (a rank on another host died, or the job was killed):");
  for (int r = 0; r < w.size && r < 64; ++r) {
    put(r ? "; rank " : " rank ");
    putInt(r);
    put(" was ");
    put(activityOf(r));
  }
  put("; no output written\n");
  ::_exit(143);
}

std::uint64_t hostHash() {
  char name[256] = {};
  ::gethostname(name, sizeof name - 1);
  Fnv1a h;
  h.add(name, std::strlen(name));
  return h.value();
}

}  // namespace

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
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = onTerminate;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGTERM, &sa, nullptr);
  }
}

Session::~Session() {
  if (std::uncaught_exceptions() > uncaught_ && !agreedFailure_) return;  // see the header
  if (rank_ == 0) {
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_DFL;
    ::sigaction(SIGTERM, &sa, nullptr);
  }
  MPI_Finalize();
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
  if (!g_watch) return;
  const WatchState& w = *g_watch;
  for (int r = 1; r < w.size; ++r) {
    if (!w.local[r] || !processGone(w.pid[r])) continue;
    if (g_reported.exchange(true)) ::_exit(1);
    const std::string line = "rank " + std::to_string(r) + " (pid " + std::to_string(w.pid[r]) +
                             ") died while " + activityOf(r) + "; stopped, no output written";
    if (w.fatal)
      w.fatal(line);
    else
      std::fprintf(stderr, "%s%s\n", w.prefix, line.c_str());
    std::fflush(stderr);
    ::_exit(1);
  }
}

}  // namespace prt::distributed
