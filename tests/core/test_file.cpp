// The output policy of prt/core/file.hpp (docs/robustness.md, "Writers that never destroy"):
// links are written through, FIFOs and character devices written and kept, folders, block
// devices and sockets refused, "-" is standard output, stale temporaries of our naming (and only
// those, and only a dead process's) removed and reported, several outputs and whole folders all
// or nothing.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/fifo_reader.hpp"
#include "common/scratch.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"

namespace prt {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void put(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

std::set<std::string> names(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

mode_t typeOf(const fs::path& p) {
  struct stat st;
  EXPECT_EQ(::lstat(p.c_str(), &st), 0) << p;
  return st.st_mode & S_IFMT;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

/// The id of a process that has exited and been reaped.
long deadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return pid;
}

/// Captures the notes the writers send while alive.
struct Notes {
  std::vector<std::string> lines;
  FileNoteFn previous;
  Notes() {
    previous = setFileNoteHandler([this](const std::string& l) { lines.push_back(l); });
  }
  ~Notes() { setFileNoteHandler(previous); }
};

TEST(OutputPolicy, SymbolicLinksAreWrittenThroughAndStayLinks) {
  const prt::testing::ScratchDir s;
  fs::create_directories(s.path() / "real");
  put(s.path() / "real/target.txt", "old");
  // A chain of two relative links: out.txt -> hop -> real/target.txt.
  fs::create_symlink("real/target.txt", s.path() / "hop");
  fs::create_symlink("hop", s.path() / "out.txt");
  writeFileAtomically(s / "out.txt", std::string_view("new bytes"));
  EXPECT_EQ(typeOf(s.path() / "out.txt"), S_IFLNK);
  EXPECT_EQ(typeOf(s.path() / "hop"), S_IFLNK);
  EXPECT_EQ(fs::read_symlink(s.path() / "out.txt"), "hop");
  EXPECT_EQ(slurp(s.path() / "real/target.txt"), "new bytes");
  EXPECT_EQ(names(s.path()), (std::set<std::string>{"hop", "out.txt", "real"}));
  EXPECT_EQ(names(s.path() / "real"), (std::set<std::string>{"target.txt"}));
  // A dangling link: its target is created, the link kept.
  fs::create_symlink("real/new.txt", s.path() / "dangling");
  writeFileAtomically(s / "dangling", std::string_view("made"));
  EXPECT_EQ(typeOf(s.path() / "dangling"), S_IFLNK);
  EXPECT_EQ(slurp(s.path() / "real/new.txt"), "made");
  // A loop is refused, naming the path.
  fs::create_symlink("loop2", s.path() / "loop1");
  fs::create_symlink("loop1", s.path() / "loop2");
  EXPECT_NE(errorOf([&] {
              writeFileAtomically(s / "loop1", std::string_view("x"));
            }).find("loop1: too many levels of symbolic links"),
            std::string::npos);
}

TEST(OutputPolicy, FifoIsWrittenDirectlyAndStaysAFifo) {
  const prt::testing::ScratchDir s;
  const fs::path fifo = s.path() / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  prt::testing::FifoReader reader(fifo.string());
  ASSERT_TRUE(reader.opened());
  const std::string bytes(300000, 'p');  // more than a pipe holds: the reader must drain it
  writeFileAtomically(fifo.string(), bytes);
  EXPECT_EQ(reader.finish(), bytes);
  EXPECT_EQ(typeOf(fifo), S_IFIFO);
  EXPECT_EQ(names(s.path()), (std::set<std::string>{"pipe"}));
  EXPECT_EQ(resolveOutput(fifo.string()).kind, OutputKind::Special);
}

TEST(OutputPolicy, CharacterDevicesAreWrittenNotReplaced) {
  const prt::testing::ScratchDir s;
  // A private node of the null device (1, 3) when we may make one, so a writer that replaces
  // device nodes cannot harm the machine's /dev/null; /dev/null itself only after that passed.
  const fs::path node = s.path() / "null";
  if (::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
    GTEST_SKIP() << "cannot make a device node here (" << std::strerror(errno) << ")";
  writeFileAtomically(node.string(), std::string_view("discarded"));
  ASSERT_EQ(typeOf(node), S_IFCHR) << "the device node was replaced";
  EXPECT_EQ(names(s.path()), (std::set<std::string>{"null"}));
  writeFileAtomically("/dev/null", std::string_view("discarded"));
  EXPECT_EQ(typeOf("/dev/null"), S_IFCHR);
  // Through a link to it, too.
  fs::create_symlink(node, s.path() / "to-null");
  writeFileAtomically(s / "to-null", std::string_view("discarded"));
  EXPECT_EQ(typeOf(node), S_IFCHR);
  EXPECT_EQ(typeOf(s.path() / "to-null"), S_IFLNK);
}

TEST(OutputPolicy, FoldersBlockDevicesAndSocketsAreRefusedAndKept) {
  const prt::testing::ScratchDir s;
  fs::create_directories(s.path() / "dir");
  EXPECT_NE(errorOf([&] {
              writeFileAtomically(s / "dir", std::string_view("x"));
            }).find("dir: is a directory"),
            std::string::npos);
  EXPECT_TRUE(fs::is_directory(s.path() / "dir"));
  EXPECT_NE(errorOf([&] { checkWritable(s / "nowhere/x"); }).find("does not exist"),
            std::string::npos);
  // A socket.
  const fs::path sock = s.path() / "sock";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, sock.c_str(), sizeof addr.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  EXPECT_NE(errorOf([&] {
              writeFileAtomically(sock.string(), std::string_view("x"));
            }).find("is a socket"),
            std::string::npos);
  EXPECT_EQ(typeOf(sock), S_IFSOCK);
  ::close(fd);
  // A block device: a node of a loop device number no one uses (never opened either way).
  const fs::path blk = s.path() / "disk";
  if (::mknod(blk.c_str(), S_IFBLK | 0600, makedev(7, 250)) == 0) {
    EXPECT_NE(errorOf([&] {
                writeFileAtomically(blk.string(), std::string_view("x"));
              }).find("is a block device"),
              std::string::npos);
    EXPECT_EQ(typeOf(blk), S_IFBLK);
  }
}

TEST(OutputPolicy, DashIsStandardOutput) {
  const prt::testing::ScratchDir s;
  const std::string bytes = std::string("binary\0bytes\n", 13) + std::string(100000, 'x');
  // Standard output pointed at a file for the duration.
  std::fflush(stdout);
  const int saved = ::dup(STDOUT_FILENO);
  const int fd = ::open(s.file("captured").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ASSERT_GE(fd, 0);
  ::dup2(fd, STDOUT_FILENO);
  ::close(fd);
  writeFileAtomically("-", bytes);
  // A failure while making it writes nothing.
  EXPECT_THROW(writeFileAtomically("-",
                                   [](std::ostream& o) {
                                     o << "half";
                                     throw Error("boom");
                                   }),
               Error);
  ::dup2(saved, STDOUT_FILENO);
  ::close(saved);
  EXPECT_EQ(slurp(s.path() / "captured"), bytes);
  EXPECT_EQ(resolveOutput("-").kind, OutputKind::Stdout);
  checkWritable("-");
}

TEST(OutputPolicy, ReplacingAFileKeepsItsPermissionBits) {
  const prt::testing::ScratchDir s;
  put(s.path() / "secret", "old");
  fs::permissions(s.path() / "secret", fs::perms::owner_read | fs::perms::owner_write);
  writeFileAtomically(s / "secret", std::string_view("new"));
  EXPECT_EQ(slurp(s.path() / "secret"), "new");
  EXPECT_EQ(fs::status(s.path() / "secret").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
}

TEST(OutputPolicy, AFailedWriteNamesTheFileAndLeavesNothing) {
  const prt::testing::ScratchDir s;
  put(s.path() / "out.bin", "earlier");
  // A file size limit (as a full disk would): the write fails with EFBIG, not a signal.
  struct rlimit old {};
  ::getrlimit(RLIMIT_FSIZE, &old);
  const auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 4096;
  ::setrlimit(RLIMIT_FSIZE, &small);
  const std::string e =
      errorOf([&] { writeFileAtomically(s / "out.bin", std::string(100000, 'z')); });
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, oldHandler);
  EXPECT_NE(e.find("out.bin: write failed (File too large)"), std::string::npos) << e;
  EXPECT_EQ(slurp(s.path() / "out.bin"), "earlier");
  EXPECT_EQ(names(s.path()), (std::set<std::string>{"out.bin"}));
}

TEST(StaleTemporaries, OnlyOursOfADeadProcessAreRemovedAndEachIsReported) {
  const prt::testing::ScratchDir s;
  const fs::path d = s.path();
  const std::string dead = std::to_string(deadPid()), live = std::to_string(::getpid());
  const std::string staleFile = ".out.bin.prt-tmp-" + dead + "-0123abcd";
  const std::string staleFolder = ".out.bin.prt-partial-" + dead + "-89abcdef";
  put(d / staleFile, "killed mid-write");
  fs::create_directories(d / staleFolder / "inner");
  put(d / staleFolder / "inner/x", "half a folder");
  // Not ours to remove: a live process's, another target's, names not exactly ours, a link of
  // our naming (and what it points at), a folder where a file is expected, the old naming.
  put(d / "precious", "keep");
  const std::vector<std::string> kept = {
      ".out.bin.prt-tmp-" + live + "-0123abcd",  ".other.bin.prt-tmp-" + dead + "-0123abcd",
      ".out.bin.prt-tmp-" + dead + "-0123ABCD",  ".out.bin.prt-tmp-" + dead + "-0123abcd.x",
      ".out.bin.prt-tmp-" + dead + "-012",       "out.bin.prt-tmp-" + dead + "-0123abcd",
      ".out.bin.prt-tmp-x" + dead + "-0123abcd", "out.bin.tmp123456"};
  for (const std::string& k : kept) put(d / k, "keep");
  fs::create_symlink("precious", d / (".out.bin.prt-tmp-" + dead + "-fedcba98"));
  fs::create_directories(d / (".out.bin.prt-tmp-" + dead + "-aaaaaaaa"));
  const prt::testing::ScratchDir elsewhere("elsewhere");
  fs::create_directories(elsewhere.path() / "victim");
  put(elsewhere.path() / "victim/file", "keep");
  fs::create_symlink(elsewhere.path() / "victim",
                     d / (".out.bin.prt-partial-" + dead + "-bbbbbbbb"));

  const std::set<std::string> before = names(d);
  Notes notes;
  writeFileAtomically(s / "out.bin", std::string_view("fresh"));
  EXPECT_EQ(slurp(d / "out.bin"), "fresh");
  std::set<std::string> expected = before;
  expected.erase(staleFile);
  expected.erase(staleFolder);
  expected.insert("out.bin");
  EXPECT_EQ(names(d), expected);
  for (const std::string& k : kept) EXPECT_EQ(slurp(d / k), "keep") << k;
  EXPECT_EQ(slurp(d / "precious"), "keep");
  EXPECT_EQ(slurp(elsewhere.path() / "victim/file"), "keep");
  ASSERT_EQ(notes.lines.size(), 2u);
  std::string all = notes.lines[0] + "\n" + notes.lines[1];
  EXPECT_NE(all.find("removed stale temporary " + (d / staleFile).string() + " (left by process " +
                     dead + ", which no longer runs)"),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("removed stale partial folder " + (d / staleFolder).string()),
            std::string::npos)
      << all;
  // Nothing left to do the next time.
  EXPECT_EQ(removeStaleTemporaries(s / "out.bin"), 0);
}

TEST(OutputBatch, NothingIsInPlaceUnlessCommitted) {
  const prt::testing::ScratchDir s;
  put(s.path() / "a.txt", "earlier a");
  try {
    OutputBatch batch;
    writeFileAtomically(s / "a.txt", std::string_view("new a"));
    writeFileAtomically(s / "b.txt", std::string_view("new b"));
    EXPECT_EQ(slurp(s.path() / "a.txt"), "earlier a");  // not yet
    EXPECT_FALSE(fs::exists(s.path() / "b.txt"));
    throw Error("the third output failed");
  } catch (const Error&) {
  }
  EXPECT_EQ(names(s.path()), (std::set<std::string>{"a.txt"}));
  EXPECT_EQ(slurp(s.path() / "a.txt"), "earlier a");
  {
    OutputBatch batch;
    writeFileAtomically(s / "a.txt", std::string_view("new a"));
    writeFileAtomically(s / "b.txt", std::string_view("new b"));
    batch.commit();
    // After commit, writes go straight to their place again.
    writeFileAtomically(s / "c.txt", std::string_view("c"));
    EXPECT_TRUE(fs::exists(s.path() / "c.txt"));
  }
  EXPECT_EQ(slurp(s.path() / "a.txt"), "new a");
  EXPECT_EQ(slurp(s.path() / "b.txt"), "new b");
  EXPECT_EQ(names(s.path()), (std::set<std::string>{"a.txt", "b.txt", "c.txt"}));
}

TEST(FolderOutput, MakesAFolderAsAWholeAndReplacesOnlyItsOwn) {
  const prt::testing::ScratchDir s;
  const fs::path d = s.path();
  {
    FolderOutput f(s / "site", "prt test");
    f.write("index.html", "one");
    fs::create_directories(fs::path(f.path()) / "img");
    writeFileAtomically(f.file("img/a.png"), std::string_view("png"));
    EXPECT_FALSE(fs::exists(d / "site"));  // not before commit
    f.commit();
  }
  EXPECT_EQ(slurp(d / "site/index.html"), "one");
  EXPECT_EQ(slurp(d / "site/img/a.png"), "png");
  EXPECT_EQ(names(d), (std::set<std::string>{"site"}));
  EXPECT_EQ(slurp(d / "site" / FolderOutput::kMarkName).substr(0, 9), "prt test\n");

  // Its own earlier folder: replaced as a whole (img/ is gone).
  {
    FolderOutput f(s / "site/", "prt test");
    f.write("index.html", "two");
    f.commit();
  }
  EXPECT_EQ(slurp(d / "site/index.html"), "two");
  EXPECT_FALSE(fs::exists(d / "site/img"));
  EXPECT_EQ(names(d), (std::set<std::string>{"site"}));

  // A failure before commit: the earlier folder stays as it was, no partial folder left.
  try {
    FolderOutput f(s / "site", "prt test");
    f.write("index.html", "three");
    throw Error("failed half-way");
  } catch (const Error&) {
  }
  EXPECT_EQ(slurp(d / "site/index.html"), "two");
  EXPECT_EQ(names(d), (std::set<std::string>{"site"}));

  // Through a link to the folder: the target is replaced, the link kept.
  fs::create_symlink("site", d / "link");
  {
    FolderOutput f(s / "link", "prt test");
    f.write("index.html", "four");
    f.commit();
  }
  EXPECT_EQ(typeOf(d / "link"), S_IFLNK);
  EXPECT_EQ(slurp(d / "site/index.html"), "four");
  EXPECT_EQ(names(d), (std::set<std::string>{"link", "site"}));

  // An empty folder is taken.
  fs::create_directories(d / "empty");
  {
    FolderOutput f(s / "empty", "prt test");
    f.write("x", "x");
    f.commit();
  }
  EXPECT_EQ(slurp(d / "empty/x"), "x");
}

TEST(FolderOutput, RefusesWhatItDidNotMake) {
  const prt::testing::ScratchDir s;
  const fs::path d = s.path();
  fs::create_directories(d / "mine");
  put(d / "mine/index.html", "the user's page");
  const std::string e = errorOf([&] { FolderOutput f(s / "mine", "prt test"); });
  EXPECT_NE(e.find("mine: exists, is not empty and is not a prt test folder"), std::string::npos)
      << e;
  // Another maker's folder is not ours either.
  fs::create_directories(d / "other");
  put(d / "other" / FolderOutput::kMarkName, "prt other\n");
  EXPECT_NE(errorOf([&] {
              checkFolderReplaceable(s / "other", "prt test");
            }).find("is not a prt test folder"),
            std::string::npos);
  // A file where the folder should be; standard output; the root.
  put(d / "file", "x");
  EXPECT_NE(errorOf([&] {
              checkFolderReplaceable(s / "file", "prt test");
            }).find("exists and is not a folder"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { checkFolderReplaceable("-", "prt test"); }).find("standard output"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { checkFolderReplaceable("/", "prt test"); }), "(no error)");
  EXPECT_EQ(slurp(d / "mine/index.html"), "the user's page");
  EXPECT_EQ(names(d), (std::set<std::string>{"file", "mine", "other"}));
}

TEST(FolderOutput, RemovesAStalePartialFolderOfADeadProcess) {
  const prt::testing::ScratchDir s;
  const std::string stale = ".site.prt-partial-" + std::to_string(deadPid()) + "-00000000";
  fs::create_directories(s.path() / stale / "img");
  Notes notes;
  {
    FolderOutput f(s / "site", "prt test");
    f.commit();
  }
  EXPECT_EQ(names(s.path()), (std::set<std::string>{"site"}));
  ASSERT_EQ(notes.lines.size(), 1u);
  EXPECT_NE(notes.lines[0].find("removed stale partial folder"), std::string::npos);
}

}  // namespace
}  // namespace prt
