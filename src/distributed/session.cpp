#include "prt/distributed/session.hpp"

#include <mpi.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <fcntl.h>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
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

// The line: each rank on the root's host holds a socket to the root's watch thread, opened at
// start-up. A rank that leaves in order says how first, one byte; a line that drops without a
// word is a death, seen by the watch thread the moment the process ends (the kernel closes the
// socket) — before the runtime has noticed it, let alone begun to stop the other ranks.
constexpr char kSaidLeaving = 'B';  ///< finalizing: the job ended, or every rank agreed it failed
constexpr char kSaidQuiet = 'Q';    ///< failing as rank 0 presumably is, leaving the report to it
constexpr char kSaidStopped = 'T';  ///< stopped by SIGTERM: the runtime ending the job

// Who reports the end (the watch thread, the coordinator's watch() or the SIGTERM handler):
// the first to claim it, so that one line is printed.
enum Report : int { kNotReported = 0, kReporting = 1, kReported = 2 };

struct WatchState {
  int size = 0;
  std::vector<long> pid;
  std::vector<char> local;   ///< on the root's host
  std::vector<char> onLine;  ///< holds a line to the watch thread (the others: their pid polled)
  std::vector<char> lines;   ///< size × 2 × kLine
  std::unique_ptr<std::atomic<int>[]> which;
  std::unique_ptr<std::atomic<int>[]> said;  ///< what rank r said on its line (0: nothing yet)
  std::atomic<int> firstDied{-1};            ///< the first rank whose line dropped without a word
  std::atomic<int> report{kNotReported};
  char prefix[kPrefix] = {};
  FatalFn fatal;
  int listenFd = -1;
  int stopFd[2] = {-1, -1};
  std::thread thread;
};
WatchState* g_watch = nullptr;
static_assert(std::atomic<int>::is_always_lock_free, "the handlers read `which`, `said`, ...");
/// On the other ranks: this rank's end of its line to the root's watch (-1: none).
std::atomic<int> g_line{-1};
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

/// The watch's socket: an abstract Unix socket (no file to leave behind) named by the root's
/// pid and a nonce the root draws, both sent to the other ranks at start-up. Linux only; the
/// address's length, or 0 where there is none.
socklen_t lineAddress(sockaddr_un& addr, long rootPid, std::uint64_t nonce) {
#ifdef __linux__
  std::memset(&addr, 0, sizeof addr);
  addr.sun_family = AF_UNIX;
  const int n =
      std::snprintf(addr.sun_path + 1, sizeof addr.sun_path - 1, "prtkit-watch-%ld-%016llx",
                    rootPid, static_cast<unsigned long long>(nonce));
  return static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + static_cast<std::size_t>(n));
#else
  (void)addr, (void)rootPid, (void)nonce;
  return 0;
#endif
}

/// Claims the report; false when another path has.
bool claimReport(WatchState& w) {
  int expected = kNotReported;
  return w.report.compare_exchange_strong(expected, kReporting);
}

/// Passes the line naming dead rank r to the FatalFn, once, with SIGTERM blocked in this
/// thread: the handler, which waits for a report being written, must run on another.
void reportDeath(WatchState& w, int r) {
  if (!w.fatal || !claimReport(w)) return;
  sigset_t term, old;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &term, &old);
  char buf[kLine + 128];
  LineWriter line(buf, sizeof buf);
  addDeadRank(line, r);
  const std::size_t n = line.finish(false);
  w.fatal(std::string(buf, n));
  w.report.store(kReported);
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
}

/// A local rank whose process has ended without saying it would (lowest first), for where no
/// line told: ranks without one, and the handler's last look. -1 if none.
int goneSilently(const WatchState& w, bool onLineToo) {
  for (int r = 1; r < w.size; ++r) {
    if (!w.local[r] || (w.onLine[r] && !onLineToo)) continue;
    const int said = w.said[r].load();
    if (said == kSaidLeaving || said == kSaidStopped) continue;
    if (processGone(w.pid[r])) return r;
  }
  return -1;
}

/// The root's watch thread: waits on the lines (poll, no timeout), records what each rank
/// says, and reports the first that drops without a word. Ends when stopFd is written.
void watchLines(WatchState* wp) {
  WatchState& w = *wp;
  struct Peer {
    int rank = -1;  ///< -1 until its 4 bytes came
    unsigned char id[4] = {};
    int idBytes = 0;
  };
  std::vector<pollfd> fds = {{w.stopFd[0], POLLIN, 0}, {w.listenFd, POLLIN, 0}};
  std::vector<Peer> peers(2);
  for (;;) {
    for (pollfd& p : fds) p.revents = 0;
    if (::poll(fds.data(), fds.size(), -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    if (fds[0].revents) return;
    if (fds[1].revents & POLLIN) {
      const int fd = ::accept4(w.listenFd, nullptr, nullptr, SOCK_CLOEXEC);
      if (fd >= 0) {
        fds.push_back({fd, POLLIN, 0});
        peers.emplace_back();
      }
    }
    for (std::size_t i = 2; i < fds.size();) {
      if (!fds[i].revents) {
        ++i;
        continue;
      }
      unsigned char buf[64];
      const ssize_t n = ::read(fds[i].fd, buf, sizeof buf);
      if (n < 0 && (errno == EINTR || errno == EAGAIN)) {
        ++i;
        continue;
      }
      Peer& peer = peers[i];
      for (ssize_t k = 0; k < n; ++k) {
        if (peer.idBytes < 4) {
          peer.id[peer.idBytes++] = buf[k];
          if (peer.idBytes == 4) {
            std::int32_t r;
            std::memcpy(&r, peer.id, 4);
            peer.rank = r >= 1 && r < w.size ? r : -1;
          }
        } else if (peer.rank > 0) {
          w.said[peer.rank].store(buf[k]);
        }
      }
      if (n > 0) {
        ++i;
        continue;
      }
      // The line dropped: the process ended (or closed it after saying goodbye).
      const int r = peer.rank;
      ::close(fds[i].fd);
      fds.erase(fds.begin() + static_cast<std::ptrdiff_t>(i));
      peers.erase(peers.begin() + static_cast<std::ptrdiff_t>(i));
      if (r <= 0 || w.said[r].load() != 0) continue;
      int none = -1;
      if (w.firstDied.compare_exchange_strong(none, r)) reportDeath(w, r);
    }
  }
}

/// One byte on a line; never raises SIGPIPE (the root may be gone). Async-signal-safe.
void say(int fd, char what) {
  [[maybe_unused]] const ssize_t n = ::send(fd, &what, 1, MSG_NOSIGNAL);
}

/// The root: listens for the lines of the ranks on its host; the socket (or -1), and its
/// nonce in `nonce` (0 when none).
int listenForLines(std::uint64_t& nonce) {
  nonce = 0;
#ifdef __linux__
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  const auto t =
      static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  const std::uint64_t candidate =
      ((t * 0x9E3779B97F4A7C15ULL) ^ static_cast<std::uint64_t>(::getpid())) | 1;
  sockaddr_un addr;
  const socklen_t length = lineAddress(addr, static_cast<long>(::getpid()), candidate);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), length) != 0 ||
      ::listen(fd, SOMAXCONN) != 0) {
    ::close(fd);
    return -1;
  }
  nonce = candidate;
  return fd;
#else
  return -1;
#endif
}

/// The other ranks on the root's host: opens this rank's line and names the rank on it; the
/// socket, or -1 (then the root polls this rank's pid).
int connectLine(long rootPid, std::uint64_t nonce, int rank) {
  sockaddr_un addr;
  const socklen_t length = lineAddress(addr, rootPid, nonce);
  if (length == 0) return -1;
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  int rc;
  do rc = ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), length);
  while (rc != 0 && errno == EINTR);
  const std::int32_t id = rank;
  if (rc != 0 || ::send(fd, &id, sizeof id, MSG_NOSIGNAL) != static_cast<ssize_t>(sizeof id)) {
    ::close(fd);
    return -1;
  }
  return fd;
}

/// Starts the root's watch thread, with SIGTERM blocked in it (the handler runs elsewhere).
/// Without it (no pipe, no thread) the lines are closed and every rank's pid polled.
void startWatchThread(WatchState& w) {
  if (::pipe2(w.stopFd, O_CLOEXEC) == 0) {
    sigset_t term, old;
    sigemptyset(&term);
    sigaddset(&term, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &term, &old);
    try {
      w.thread = std::thread(watchLines, &w);
    } catch (...) {  // no thread: the pids are polled, as below
    }
    pthread_sigmask(SIG_SETMASK, &old, nullptr);
  }
  if (w.thread.joinable()) return;
  ::close(w.listenFd);
  w.listenFd = -1;
}

void stopWatchThread() {
  WatchState* w = g_watch;
  if (!w || !w->thread.joinable()) return;
  const char stop = 0;
  [[maybe_unused]] const ssize_t n = ::write(w->stopFd[1], &stop, 1);
  w->thread.join();
  ::close(w->listenFd);
  w->listenFd = -1;
}

}  // namespace

Termination describeTermination(char* buffer, std::size_t size) noexcept {
  LineWriter line(buffer, size);
  Termination t;
  if (!g_watch) return t;
  WatchState& w = *g_watch;
  if (!claimReport(w)) {
    // Another thread is writing the report (SIGTERM is blocked there, so it is not this one):
    // give it time to finish — its FatalFn normally ends the process — rather than end the
    // process under it with nothing printed.
    const timespec ms = {0, 1000 * 1000};
    for (int i = 0; i < 3000 && w.report.load() == kReporting; ++i) ::nanosleep(&ms, nullptr);
    return t;
  }
  line.add(w.prefix);
  // The rank whose line dropped first; else (no line, or the watch thread has not run since)
  // one on this host that ended without saying it would.
  int dead = w.firstDied.load();
  if (dead < 0) dead = goneSilently(w, true);
  if (dead > 0) {
    addDeadRank(line, dead);
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

void noteStopped() noexcept {
  const int fd = g_line.load();
  if (fd < 0) return;
  const char said = kSaidStopped;
  [[maybe_unused]] const ssize_t n = ::write(fd, &said, 1);
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
  // Who runs where: process ids and hosts, for the watch, and the nonce naming the root's watch
  // socket (0: none).
  std::uint64_t nonce = 0;
  const int listenFd = rank_ == 0 && size_ > 1 ? listenForLines(nonce) : -1;
  std::int64_t mine[3] = {static_cast<std::int64_t>(::getpid()),
                          static_cast<std::int64_t>(hostHash()), static_cast<std::int64_t>(nonce)};
  std::vector<std::int64_t> all(3 * static_cast<std::size_t>(size_));
  MPI_Allgather(mine, 3, MPI_INT64_T, all.data(), 3, MPI_INT64_T, MPI_COMM_WORLD);
  WatchState* w = nullptr;
  if (rank_ == 0) {
    w = new WatchState;  // lives to the end of the process (the handler reads it)
    w->size = size_;
    w->fatal = std::move(fatal);
    for (int r = 0; r < size_; ++r) {
      w->pid.push_back(static_cast<long>(all[3 * r]));
      w->local.push_back(all[3 * r + 1] == all[1]);
    }
    w->onLine.assign(static_cast<std::size_t>(size_), 0);
    w->lines.assign(static_cast<std::size_t>(size_) * 2 * kLine, 0);
    w->which.reset(new std::atomic<int>[static_cast<std::size_t>(size_)]);
    w->said.reset(new std::atomic<int>[static_cast<std::size_t>(size_)]);
    for (int r = 0; r < size_; ++r) {
      w->which[r] = 0;
      w->said[r] = 0;
      std::snprintf(&w->lines[static_cast<std::size_t>(r) * 2 * kLine], kLine, "starting");
    }
    std::snprintf(w->prefix, sizeof w->prefix, "%s: error: ", verb.c_str());
    g_watch = w;
    w->listenFd = listenFd;
    if (listenFd >= 0) startWatchThread(*w);
  } else if (all[2] != 0 && all[3 * static_cast<std::size_t>(rank_) + 1] == all[1]) {
    g_line.store(connectLine(static_cast<long>(all[0]), static_cast<std::uint64_t>(all[2]), rank_));
  }
  // Which ranks hold a line (the root polls the others' pids).
  const int lined = g_line.load() >= 0 ? 1 : 0;
  std::vector<int> linedAll(rank_ == 0 ? static_cast<std::size_t>(size_) : 1);
  MPI_Gather(&lined, 1, MPI_INT, linedAll.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (w && w->thread.joinable())
    for (int r = 1; r < size_; ++r) w->onLine[r] = static_cast<char>(linedAll[r]);
}

Session::~Session() {
  const bool finalize = willFinalize();
  if (rank_ == 0) {
    // What ends from now on (the ranks leaving, or stopped after this rank failed alone) is no
    // death to report.
    stopWatchThread();
  } else if (finalize) {
    // Said before MPI_Finalize, so that the root, maybe still writing the output, does not take
    // this process's end for a death. (Failing alone, the line stays open to the process's
    // end: the root names the rank, as it does one that died.)
    const int fd = g_line.exchange(-1);
    if (fd >= 0) {
      say(fd, kSaidLeaving);
      ::close(fd);
    }
  }
  if (!finalize) return;  // see the header
  MPI_Finalize();
}

void Session::leaveQuietly() {
  if (rank_ == 0) return;
  const int fd = g_line.load();
  if (fd >= 0) say(fd, kSaidQuiet);
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
  WatchState& w = *g_watch;
  // The watch thread has normally reported a dead rank already (or is reporting it: then this
  // claim fails); this looks at the ranks with no line, by their pids.
  int r = w.firstDied.load();
  if (r < 0) r = goneSilently(w, false);
  if (r > 0) reportDeath(w, r);
}

}  // namespace prt::distributed
