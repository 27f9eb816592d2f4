#include "prt/core/file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <random>
#include <sstream>
#include <system_error>

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"

namespace prt {

namespace fs = std::filesystem;

namespace {

std::string why(int err) {
  return std::generic_category().message(err);
}

// --- notes ----------------------------------------------------------------------------------

std::mutex& noteMutex() {
  static std::mutex m;
  return m;
}
FileNoteFn& noteHandler() {
  static FileNoteFn h;
  return h;
}
void note(const std::string& line) {
  FileNoteFn h;
  {
    std::lock_guard<std::mutex> lock(noteMutex());
    h = noteHandler();
  }
  if (h) h(line);
}

// --- our names ------------------------------------------------------------------------------
// .NAME.prt-tmp-PID-RANDOM beside the target (NAME cut to 200 bytes, so the whole stays under
// the 255 a file name may have); RANDOM is 8 lower-case hex digits.

constexpr std::string_view kTmpTag = ".prt-tmp-";
constexpr std::string_view kPartialTag = ".prt-partial-";
constexpr std::size_t kMaxStem = 200;

std::string stemOf(const fs::path& target) {
  std::string name = target.filename().string();
  if (name.size() > kMaxStem) name.resize(kMaxStem);
  return "." + name;
}

fs::path ourName(const fs::path& target, std::string_view tag) {
  static thread_local std::mt19937 rng{std::random_device{}()};
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(rng()));
  return target.parent_path() /
         (stemOf(target) + std::string(tag) + std::to_string(::getpid()) + "-" + hex);
}

/// The process id in `name` when it is exactly STEM TAG PID - 8 hex digits; else 0.
long ourPid(std::string_view name, std::string_view stem, std::string_view tag) {
  if (name.substr(0, stem.size()) != stem) return 0;
  name.remove_prefix(stem.size());
  if (name.substr(0, tag.size()) != tag) return 0;
  name.remove_prefix(tag.size());
  const std::size_t dash = name.find('-');
  if (dash == 0 || dash == std::string_view::npos || dash > 9) return 0;
  const std::string_view pid = name.substr(0, dash), rnd = name.substr(dash + 1);
  if (rnd.size() != 8) return 0;
  for (char c : pid)
    if (c < '0' || c > '9') return 0;
  for (char c : rnd)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return 0;
  return std::stol(std::string(pid));
}

/// A process that we may not signal (EPERM) still runs.
bool processRuns(long pid) {
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

// --- resolving ------------------------------------------------------------------------------

/// True for a path inside /proc, whose links (/proc/self/fd/1, what /dev/stdout names) are the
/// kernel's handles on open files, not names to follow: "pipe:[1234]" is no file.
bool inProc(const fs::path& p) {
  const fs::path a = fs::absolute(p).lexically_normal();
  auto it = a.begin();
  return it != a.end() && ++it != a.end() && *it == "proc";
}

/// Where a chain of symbolic links ends.
struct Followed {
  fs::path path;         ///< the first path that is not a link, or the first inside /proc
  bool links = false;    ///< at least one link was followed
  bool viaProc = false;  ///< stopped inside /proc
};

/// Follows `p` while it is a symbolic link (relative links from the link's folder). The end may
/// not exist (a dangling link's target is created). With `stopAtProc`, stops at the first path
/// inside /proc, whose links the kernel must follow itself.
Followed followLinks(fs::path p, const std::string& asGiven, bool stopAtProc) {
  Followed f;
  for (int hops = 0;; ++hops) {
    // The folder part with its own links resolved (/dev/fd/1 is /proc/self/fd/1).
    if (p.has_filename()) {
      std::error_code ec;
      const fs::path dir = fs::weakly_canonical(
          fs::absolute(p.parent_path().empty() ? fs::path(".") : p.parent_path()), ec);
      if (!ec) p = dir / p.filename();
    }
    f.path = p;
    if (stopAtProc && inProc(p)) {
      f.viaProc = true;
      return f;
    }
    struct stat st;
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return f;
    if (hops == 40) throw Error(asGiven, "too many levels of symbolic links");
    std::error_code ec;
    const fs::path link = fs::read_symlink(p, ec);
    if (ec)
      throw Error(asGiven, "cannot read the symbolic link " + p.string() + ": " + ec.message());
    p = link.is_absolute() ? link : p.parent_path() / link;
    f.links = true;
  }
}

bool namedThroughProc(const std::string& path) {
  return followLinks(path, path, true).viaProc;
}

bool writeAll(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

/// An output stream buffer over a file descriptor that remembers the first write error.
class FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd), buf_(std::size_t(1) << 16) {
    setp(buf_.data(), buf_.data() + buf_.size());
  }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n < static_cast<std::streamsize>(buf_.size())) return std::streambuf::xsputn(s, n);
    if (!drain() || !writeAll(fd_, s, static_cast<std::size_t>(n))) {
      if (!error_) error_ = errno;
      return 0;
    }
    return n;
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (error_) return false;
    const std::size_t n = static_cast<std::size_t>(pptr() - pbase());
    if (n > 0 && !writeAll(fd_, pbase(), n)) {
      error_ = errno;
      return false;
    }
    setp(buf_.data(), buf_.data() + buf_.size());
    return true;
  }
  int fd_;
  std::vector<char> buf_;
  int error_ = 0;
};

/// Opens a FIFO, a character device or a file named through /proc for writing. A FIFO's open()
/// blocks until a reader opens it, forever if none comes: it is opened non-blocking instead
/// (ENXIO while no reader has it open), retried for kFifoReaderWaitSeconds, then refused by name;
/// once open, writes block again (the reader drains the pipe at its own pace).
int openForWriting(const std::string& path, const std::string& target) {
  constexpr int flags = O_WRONLY | O_APPEND | O_NOCTTY | O_CLOEXEC;
  struct stat st;
  if (::stat(target.c_str(), &st) != 0 || !S_ISFIFO(st.st_mode)) {
    const int fd = ::open(target.c_str(), flags);
    if (fd < 0) throw Error(path, "cannot open for writing (" + why(errno) + ")");
    return fd;
  }
  constexpr int kPollMs = 50;
  for (int waited = 0;; waited += kPollMs) {
    const int fd = ::open(target.c_str(), flags | O_NONBLOCK);
    if (fd >= 0) {
      const int fl = ::fcntl(fd, F_GETFL);
      if (fl < 0 || ::fcntl(fd, F_SETFL, fl & ~O_NONBLOCK) != 0) {
        const int err = errno;
        ::close(fd);
        throw Error(path, "cannot open for writing (" + why(err) + ")");
      }
      return fd;
    }
    if (errno != ENXIO && errno != EINTR)
      throw Error(path, "cannot open for writing (" + why(errno) + ")");
    if (waited >= kFifoReaderWaitSeconds * 1000)
      throw Error(path, "is a FIFO that no process reads (waited " +
                            std::to_string(kFifoReaderWaitSeconds) +
                            " s); start its reader first, or write a file");
    ::usleep(kPollMs * 1000);
  }
}

/// Writes a whole output to standard output or to a FIFO / character device.
void writeDirect(const std::string& path, const ResolvedOutput& out, std::string_view bytes) {
  if (out.kind == OutputKind::Stdout) {
    std::cout.flush();
    std::fflush(stdout);
    if (!writeAll(STDOUT_FILENO, bytes.data(), bytes.size()))
      throw Error("standard output", "write failed (" + why(errno) + ")");
    return;
  }
  const int fd = openForWriting(path, out.target);
  struct stat st;
  // What was opened must still be what was resolved: never write into a file without the
  // rename, unless it is an open file named through /proc.
  if (::fstat(fd, &st) != 0 || !(S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode) ||
                                 (S_ISREG(st.st_mode) && namedThroughProc(path)))) {
    ::close(fd);
    throw Error(path, "changed while being written; not writing it");
  }
  const bool ok = writeAll(fd, bytes.data(), bytes.size());
  const int err = errno;
  if (::close(fd) != 0 && ok) throw Error(path, "write failed (" + why(errno) + ")");
  if (!ok) throw Error(path, "write failed (" + why(err) + ")");
}

/// Creates a new, empty temporary beside `target` (exclusively: never an existing name).
int createTemporary(const fs::path& target, const std::string& path, fs::path& tmp) {
  for (int attempt = 0;; ++attempt) {
    tmp = ourName(target, kTmpTag);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST || attempt == 16)
      throw Error(path, "cannot create a temporary file beside it (" + why(errno) + ")");
  }
}

OutputBatch*& activeBatch() {
  static thread_local OutputBatch* batch = nullptr;
  return batch;
}

/// The folder a FolderOutput writes: absolute, without a trailing separator, links followed.
fs::path folderTarget(const std::string& destination) {
  if (destination.empty()) throw Error("output folder is empty");
  if (isStandardOutput(destination))
    throw Error("-", "a folder cannot be written to standard output; name a folder");
  fs::path p = fs::absolute(destination).lexically_normal();
  if (!p.has_filename() && p != p.root_path()) p = p.parent_path();
  p = followLinks(p, destination, false).path;
  if (!p.is_absolute()) p = fs::absolute(p);
  p = p.lexically_normal();
  if (!p.has_filename() && p != p.root_path()) p = p.parent_path();
  if (p == p.root_path() || p.filename() == "." || p.filename() == "..")
    throw Error(destination, "is not a folder that can be written as a whole; name a sub-folder");
  return p;
}

/// The first line of DIR/.prt-output when it is a regular file; "" otherwise.
std::string markOf(const fs::path& dir) {
  const fs::path mark = dir / FolderOutput::kMarkName;
  struct stat st;
  if (::lstat(mark.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return "";
  std::ifstream in(mark);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

// --- the policy -----------------------------------------------------------------------------

ResolvedOutput resolveOutput(const std::string& path) {
  if (path.empty()) throw Error("output path is empty");
  if (isStandardOutput(path)) return {OutputKind::Stdout, "-"};
  const Followed followed = followLinks(path, path, true);
  const bool viaProc = followed.viaProc, link = followed.links;
  const fs::path& target = followed.path;
  const std::string t = viaProc ? path : target.string();
  struct stat st;
  // Through /proc (/dev/stdout, /dev/fd/3) the kernel follows its own links: the open file
  // they name is written directly, appended to (a shell's "> file" left it empty).
  if (viaProc ? ::stat(path.c_str(), &st) != 0 : ::lstat(target.c_str(), &st) != 0) {
    if (viaProc) throw Error(path, "cannot be opened (" + why(errno) + ")");
    if (!target.has_filename()) throw Error(path, "names a folder; expected a file name");
    return {OutputKind::File, t, link};  // not there yet (or its folder is missing: checkWritable)
  }
  if (S_ISREG(st.st_mode)) return {viaProc ? OutputKind::Special : OutputKind::File, t, link};
  if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) return {OutputKind::Special, t, link};
  if (S_ISDIR(st.st_mode))
    throw Error(path, link ? "links to the directory " + t : "is a directory");
  const std::string what = S_ISBLK(st.st_mode) ? "a block device" : "a socket";
  throw Error(path, (link ? "links to " + what + ", " + t : "is " + what) +
                        "; prt writes files, FIFOs, character devices and - (standard output)");
}

FileNoteFn setFileNoteHandler(FileNoteFn handler) {
  std::lock_guard<std::mutex> lock(noteMutex());
  std::swap(noteHandler(), handler);
  return handler;
}

void checkWritable(const std::string& path) {
  const ResolvedOutput r = resolveOutput(path);
  if (r.kind == OutputKind::Stdout) return;
  if (r.kind == OutputKind::Special) {
    if (::access(r.target.c_str(), W_OK) != 0)
      throw Error(path, "cannot be written (" + why(errno) + ")");
    return;
  }
  // The folder the temporary goes in: the link target's, else the one the user named.
  const fs::path t(r.viaLink ? r.target : path);
  const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw Error(path, "directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw Error(path, "directory " + dir.string() + " is not writable");
}

int removeStaleTemporaries(const std::string& target) {
  const fs::path t(target);
  const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
  const std::string stem = stemOf(t);
  struct Stale {
    fs::path path;
    long pid;
    bool folder;
  };
  std::vector<Stale> stale;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    for (const std::string_view tag : {kTmpTag, kPartialTag}) {
      const long pid = ourPid(name, stem, tag);
      if (pid <= 0 || processRuns(pid)) continue;
      // The entry itself, never what a link points at: only a regular file for a temporary
      // and a real folder for a partial folder are ours to remove.
      struct stat st;
      if (::lstat(it->path().c_str(), &st) != 0) continue;
      const bool folder = tag == kPartialTag;
      if (folder ? !S_ISDIR(st.st_mode) : !S_ISREG(st.st_mode)) continue;
      stale.push_back({it->path(), pid, folder});
    }
  }
  int removed = 0;
  for (const Stale& s : stale) {
    std::error_code e;
    if (s.folder)
      fs::remove_all(s.path, e);
    else
      fs::remove(s.path, e);
    if (e) continue;
    ++removed;
    note("removed stale " + std::string(s.folder ? "partial folder " : "temporary ") +
         s.path.string() + " (left by process " + std::to_string(s.pid) +
         ", which no longer runs)");
  }
  return removed;
}

// --- writing --------------------------------------------------------------------------------

struct OutputBatch::Pending {
  std::string path;  // as given, for messages
  ResolvedOutput out;
  std::string temporary;  // File: the complete temporary beside the target
  std::string bytes;      // Stdout, Special: the whole output
};

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  checkWritable(path);
  const ResolvedOutput out = resolveOutput(path);
  OutputBatch* batch = activeBatch();
  if (out.kind != OutputKind::File) {
    // Made whole in memory first, so a failure while making it writes nothing.
    std::ostringstream os;
    write(os);
    if (!os) throw Error(path, "cannot make the output");
    if (batch) {
      batch->pending_.push_back({path, out, "", std::move(os).str()});
      return;
    }
    writeDirect(path, out, std::move(os).str());
    return;
  }
  const fs::path target(out.target);
  removeStaleTemporaries(out.target);
  fs::path tmp;
  int fd = createTemporary(target, path, tmp);
  try {
    {
      FdBuf buf(fd);
      std::ostream os(&buf);
      write(os);
      os.flush();
      if (buf.error()) throw Error(path, "write failed (" + why(buf.error()) + ")");
      if (!os) throw Error(path, "write failed");
    }
    // Replacing a file keeps its permission bits (a 0600 file stays private).
    struct stat st;
    if (::stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) ::fchmod(fd, st.st_mode & 07777);
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0) throw Error(path, "write failed (" + why(errno) + ")");
    if (batch) {
      batch->pending_.push_back({path, out, tmp.string(), ""});
      return;
    }
    if (::rename(tmp.c_str(), target.c_str()) != 0)
      throw Error(path, "cannot move the temporary file into place (" + why(errno) + ")");
  } catch (...) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
}

OutputBatch::OutputBatch() : previous_(activeBatch()) {
  activeBatch() = this;
}

OutputBatch::~OutputBatch() {
  activeBatch() = previous_;
  if (committed_) return;
  for (const Pending& p : pending_)
    if (!p.temporary.empty()) ::unlink(p.temporary.c_str());
}

void OutputBatch::commit() {
  PRT_CHECK(!committed_, "OutputBatch committed twice");
  activeBatch() = previous_;  // what follows is written at once again
  committed_ = true;
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    Pending& p = pending_[k];
    try {
      if (p.out.kind == OutputKind::File) {
        if (::rename(p.temporary.c_str(), p.out.target.c_str()) != 0)
          throw Error(p.path, "cannot move the temporary file into place (" + why(errno) + ")");
        p.temporary.clear();
      } else {
        writeDirect(p.path, p.out, p.bytes);
      }
    } catch (...) {
      for (std::size_t j = k; j < pending_.size(); ++j)
        if (!pending_[j].temporary.empty()) ::unlink(pending_[j].temporary.c_str());
      throw;
    }
  }
}

// --- folders --------------------------------------------------------------------------------

namespace {
/// Whether folders can be made in `dir`, by making one and removing it: access() says yes to
/// root everywhere (and /proc takes no folders), a probe says what mkdir will say later.
void probeFolderWritable(const std::string& destination, const fs::path& dir) {
  const fs::path probe = ourName(dir / "prt-probe", kPartialTag);
  if (::mkdir(probe.c_str(), 0777) != 0)
    throw Error(destination, "folder cannot be written: " + dir.string() + " (" + why(errno) + ")");
  ::rmdir(probe.c_str());
}
}  // namespace

void checkFolderReplaceable(const std::string& destination, const std::string& maker) {
  const fs::path p = folderTarget(destination);
  struct stat st;
  if (::lstat(p.c_str(), &st) != 0) {
    if (errno != ENOENT && errno != ENOTDIR)
      throw Error(destination, "cannot inspect the folder (" + why(errno) + ")");
    // To be made: the nearest existing ancestor must be a folder we can write.
    fs::path up = p.parent_path();
    while (::stat(up.c_str(), &st) != 0 && up != up.root_path()) up = up.parent_path();
    if (!S_ISDIR(st.st_mode))
      throw Error(destination, "folder cannot be created: " + up.string() + " is not a folder");
    probeFolderWritable(destination, up);
    return;
  }
  if (!S_ISDIR(st.st_mode))
    throw Error(destination, "exists and is not a folder (-o names the folder to write)");
  probeFolderWritable(destination, p.parent_path());
  std::error_code ec;
  if (fs::is_empty(p, ec) && !ec) return;
  if (markOf(p) == maker) return;
  throw Error(destination, "exists, is not empty and is not a " + maker + " folder (it has no " +
                               FolderOutput::kMarkName + " mark naming " + maker +
                               "); not replacing it: choose a new folder, or empty this one");
}

FolderOutput::FolderOutput(const std::string& destination, const std::string& maker)
    : given_(destination), maker_(maker) {
  checkFolderReplaceable(destination, maker);
  const fs::path dest = folderTarget(destination);
  destination_ = dest.string();
  std::error_code ec;
  fs::create_directories(dest.parent_path(), ec);
  if (ec) throw Error(destination, "cannot create its parent folder (" + ec.message() + ")");
  removeStaleTemporaries(destination_);
  for (int attempt = 0;; ++attempt) {
    partial_ = ourName(dest, kPartialTag).string();
    if (::mkdir(partial_.c_str(), 0777) == 0) break;
    if (errno != EEXIST || attempt == 16)
      throw Error(destination, "cannot create the folder beside it (" + why(errno) + ")");
  }
}

FolderOutput::~FolderOutput() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(partial_, ec);
}

std::string FolderOutput::file(const std::string& relative) const {
  return (fs::path(partial_) / relative).string();
}

void FolderOutput::write(const std::string& relative, std::string_view bytes) const {
  try {
    writeFileAtomically(file(relative), bytes);
  } catch (const Error& e) {
    const std::string m = e.what();
    if (m.rfind(partial_, 0) != 0) throw;
    std::string shown = given_;
    while (shown.size() > 1 && shown.back() == '/') shown.pop_back();
    throw Error(shown + m.substr(partial_.size()));
  }
}

void FolderOutput::commit() {
  PRT_CHECK(!committed_, "FolderOutput committed twice");
  // The mark: what lets a later run of the same maker replace the folder.
  const std::string mark = file(kMarkName);
  const std::string text = maker_ + "\nThis folder was made by " + maker_ +
                           ", which replaces it as a whole when it writes here again.\n";
  const int fd = ::open(mark.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (fd < 0) throw Error(destination_, "cannot write its mark (" + why(errno) + ")");
  const bool written = writeAll(fd, text.data(), text.size());
  const int err = errno;
  if (::close(fd) != 0 || !written)
    throw Error(destination_, "write failed (" + why(written ? errno : err) + ")");
  struct stat st;
  if (::lstat(destination_.c_str(), &st) != 0) {
    if (::rename(partial_.c_str(), destination_.c_str()) != 0)
      throw Error(destination_, "cannot move the folder into place (" + why(errno) + ")");
    committed_ = true;
    return;
  }
  // An earlier folder: still one we may replace (it may have changed since we began).
  checkFolderReplaceable(destination_, maker_);
  std::error_code ec;
#ifdef RENAME_EXCHANGE
  // One step: the new folder takes the name, the old one takes the partial folder's, then goes.
  if (::renameat2(AT_FDCWD, partial_.c_str(), AT_FDCWD, destination_.c_str(), RENAME_EXCHANGE) ==
      0) {
    committed_ = true;
    fs::remove_all(partial_, ec);  // a leftover is ours, removed by the next run
    return;
  }
  if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP)
    throw Error(destination_, "cannot move the folder into place (" + why(errno) + ")");
#endif
  // Without an atomic exchange: the old folder aside under our name, the new one in, the old out.
  const fs::path dest(destination_);
  const fs::path old = ourName(dest, kPartialTag);
  if (::rename(destination_.c_str(), old.c_str()) != 0)
    throw Error(destination_, "cannot move the earlier folder aside (" + why(errno) + ")");
  if (::rename(partial_.c_str(), destination_.c_str()) != 0) {
    const int err = errno;
    ::rename(old.c_str(), destination_.c_str());
    throw Error(destination_, "cannot move the folder into place (" + why(err) + ")");
  }
  committed_ = true;
  fs::remove_all(old, ec);
}

// --- reading --------------------------------------------------------------------------------

std::vector<unsigned char> readFileBytes(const std::string& path) {
  return readFileBytes(path, limits().maxFileBytes, "PRT_MAX_FILE_BYTES");
}

namespace {

/// A regular file opened for reading (never a pipe, device or socket: a FIFO with no writer
/// would block in open() forever, and a pipe or device has no size to check against a cap).
void refuseIrregularFile(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_directory(st)) throw Error(path, "is a directory, expected a file");
  if (fs::exists(st) && !fs::is_regular_file(st))
    throw Error(path, "is not a regular file (a pipe, device or socket); give a file");
}

std::ifstream openRegularFile(const std::string& path) {
  refuseIrregularFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open (does it exist and is it readable?)");
  return in;
}

}  // namespace

std::vector<unsigned char> readFileHead(const std::string& path, std::size_t bytes) {
  std::ifstream in = openRegularFile(path);
  // Never more than the file holds (a header may claim any length).
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size < 0) throw Error(path, "cannot read");
  in.seekg(0, std::ios::beg);
  std::vector<unsigned char> data(std::min<std::uint64_t>(bytes, static_cast<std::uint64_t>(size)));
  in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size()));
  if (in.bad()) throw Error(path, "read failed");
  data.resize(static_cast<std::size_t>(in.gcount()));
  return data;
}

std::vector<unsigned char> readFileBytes(const std::string& path, std::uint64_t maxBytes,
                                         const char* capName) {
  std::ifstream in = openRegularFile(path);
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size < 0) throw Error(path, "cannot read");
  checkLimit(path, "file size", static_cast<std::uint64_t>(size), maxBytes, capName);
  in.seekg(0, std::ios::beg);
  std::vector<unsigned char> data(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(data.data()), size))
    throw Error(path, "read failed");
  return data;
}

MappedFile::~MappedFile() {
  if (size_ > 0) ::munmap(const_cast<unsigned char*>(data_), size_);
}

void MappedFile::adviseRandomAccess() const {
  if (size_ > 0) ::madvise(const_cast<unsigned char*>(data_), size_, MADV_RANDOM);
}

std::shared_ptr<const MappedFile> mapFile(const std::string& path, std::uint64_t maxBytes,
                                          const char* capName) {
  refuseIrregularFile(path);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(path, "cannot open (does it exist and is it readable?)");
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw Error(path, "cannot read");
  }
  const std::uint64_t size = static_cast<std::uint64_t>(st.st_size);
  try {
    checkLimit(path, "file size", size, maxBytes, capName);
  } catch (...) {
    ::close(fd);
    throw;
  }
  // An empty file maps nothing (mmap refuses a length of 0): its reader finds it truncated.
  void* p = size == 0 ? nullptr : ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  const int err = errno;
  ::close(fd);  // the mapping keeps the file
  if (p == MAP_FAILED) throw Error(path, "cannot map (" + why(err) + ")");
  return std::shared_ptr<const MappedFile>(
      new MappedFile(static_cast<const unsigned char*>(p), static_cast<std::size_t>(size)));
}

std::string fileExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace prt
