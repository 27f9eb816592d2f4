// Writers that never destroy (issue 16, docs/robustness.md), through the real binary: outputs
// that are links, FIFOs, character devices and standard output; stale temporaries of a killed
// run removed by the next; prt web replacing only its own folder; a failure part-way leaving no
// partial folder and no frames.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli_harness.hpp"
#include "common/fifo_reader.hpp"
#include "prt/core/file.hpp"
#include "prt/io/bake_file.hpp"

namespace prt {
namespace {

using namespace prt::testing;

constexpr const char* kSphere = "'builtin:sphere?subdiv=1'";  // 42 vertices

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

std::size_t lines(const std::string& s) {
  return std::count(s.begin(), s.end(), '\n');
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

/// The id of a process that has exited and been reaped.
long deadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return pid;
}

class WritersCli : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const Result r =
        prt(std::string("-q bake ") + kSphere + " --mode shadowed --samples 16 -o b.glb");
    ASSERT_EQ(r.rc, 0) << r.err;
    ASSERT_EQ(prt("-q export b.glb -o plain.txt").rc, 0);
    plain_ = slurp(dir_ / "plain.txt");
    ASSERT_GT(plain_.size(), 8192u);
  }
  /// A prt web run works here (its page is built); else the test is skipped by the caller.
  bool webBuilt() const {
    const Result r = prt("-q web b.glb -o probe-web");
    std::error_code ec;
    fs::remove_all(dir_ / "probe-web", ec);
    return r.rc == 0;
  }
  std::string plain_;
};

TEST_F(WritersCli, LinkedOutputsWriteTheirTargetsAndStayLinks) {
  fs::create_directories(dir_ / "real");
  fs::create_symlink("real/t.txt", dir_ / "t.txt");  // dangling: the target is made
  Result r = prt("-q export b.glb -o t.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(typeOf(dir_ / "t.txt"), S_IFLNK);
  EXPECT_EQ(slurp(dir_ / "real/t.txt"), plain_);
  // Again, over an existing target, and for a bake and an image.
  ASSERT_EQ(prt("-q export b.glb -o t.txt").rc, 0);
  EXPECT_EQ(typeOf(dir_ / "t.txt"), S_IFLNK);
  fs::create_symlink("real/c.glb", dir_ / "c.glb");
  fs::create_symlink("real/i.png", dir_ / "i.png");
  r = prt("-q compress b.glb --clusters 2 --pca 2 -o c.glb");
  ASSERT_EQ(r.rc, 0) << r.err;
  r = prt("-q render b.glb --size 16x12 -o i.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(typeOf(dir_ / "c.glb"), S_IFLNK);
  EXPECT_EQ(typeOf(dir_ / "i.png"), S_IFLNK);
  EXPECT_TRUE(readBake(path("real/c.glb")).transfers.at(0).transfer.compressed());
  EXPECT_EQ(names(dir_ / "real"), (std::set<std::string>{"c.glb", "i.png", "t.txt"}));
  // A link to a folder is refused in one line, the folder untouched.
  fs::create_symlink("real", dir_ / "to-dir");
  expectCleanFailure("export b.glb -o to-dir", "to-dir: links to the directory");
  expectCleanFailure("export b.glb -o real", "real: is a directory");
  EXPECT_EQ(names(dir_ / "real"), (std::set<std::string>{"c.glb", "i.png", "t.txt"}));
}

TEST_F(WritersCli, FifosAndCharacterDevicesAreWrittenAndStayWhatTheyAre) {
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  FifoReader reader(fifo.string());
  ASSERT_TRUE(reader.opened());
  const Result r = prt("-q export b.glb -o pipe");
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(reader.finish(), plain_);
  EXPECT_EQ(typeOf(fifo), S_IFIFO);

  // A private null device node first, so a writer that replaces device nodes harms no one;
  // the machine's /dev/null only once that passed (the issue: "replaced /dev/null").
  const fs::path node = dir_ / "null";
  if (::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
    GTEST_SKIP() << "cannot make a device node here (" << std::strerror(errno) << ")";
  EXPECT_EQ(prt("-q export b.glb -o null").rc, 0);
  ASSERT_EQ(typeOf(node), S_IFCHR) << "prt replaced a device node with a file";
  EXPECT_EQ(prt("-q export b.glb -o /dev/null").rc, 0);
  EXPECT_EQ(typeOf("/dev/null"), S_IFCHR);
  // /dev/stdout: the open file it names (here the harness's stdout.txt).
  const Result s = prt("-q export b.glb -o /dev/stdout");
  EXPECT_EQ(s.rc, 0) << s.err;
  EXPECT_EQ(s.out, plain_);
  EXPECT_EQ(typeOf(dir_ / "stdout.txt"), S_IFREG);
}

TEST_F(WritersCli, AFifoNoProcessReadsIsRefusedNotWaitedOnForever) {
  // The issue: every verb blocked forever in open() on a FIFO with no reader. Now each waits
  // kFifoReaderWaitSeconds for one, then exits 1 naming the FIFO; the FIFO stays a FIFO.
  const fs::path fifo = dir_ / "nobody.glb";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  const auto t0 = std::chrono::steady_clock::now();
  const Result r = prt("-q export b.glb -o nobody.glb");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.rc, 1) << r.err;
  EXPECT_NE(r.err.find("nobody.glb: is a FIFO that no process reads"), std::string::npos)
      << r.err;
  EXPECT_LT(seconds, prt::kFifoReaderWaitSeconds + 20);
  EXPECT_EQ(typeOf(fifo), S_IFIFO);
  // A reader that comes while the writer waits gets the whole file.
  std::atomic<bool> written{false};
  std::string got;
  bool opened = false;
  std::thread late([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    FifoReader reader(fifo.string());
    opened = reader.opened();
    while (!written) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    got = reader.finish();
  });
  const Result ok = prt("-q export b.glb -o nobody.glb");
  written = true;
  late.join();
  EXPECT_TRUE(opened);
  EXPECT_EQ(ok.rc, 0) << ok.err;
  EXPECT_EQ(got, plain_);
}

TEST_F(WritersCli, DashWritesStandardOutputByteForByte) {
  // One-file outputs: the bytes on stdout are the file's, and nothing else is there.
  Result r = prt("-q export b.glb -o -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, plain_);
  ASSERT_EQ(prt("-q light builtin:sky --bands 3 -o l.json").rc, 0);
  r = prt("-q light builtin:sky --bands 3 -o -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, slurp(dir_ / "l.json"));
  ASSERT_EQ(prt("-q render b.glb --size 16x12 -o r.png").rc, 0);
  r = prt("-q render b.glb --size 16x12 -o -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, slurp(dir_ / "r.png"));
  ASSERT_EQ(prt("-q reference b.glb --light builtin:sky --samples 8 -o ref.json").rc, 0);
  r = prt("-q reference b.glb --light builtin:sky --samples 8 -o -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, slurp(dir_ / "ref.json"));
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere + " --mode shadowed --samples 8 --range 0:20 " +
                "-o p0.glb")
                .rc,
            0);
  ASSERT_EQ(prt(std::string("-q bake ") + kSphere +
                " --mode shadowed --samples 8 --range 20: " + "-o p1.glb")
                .rc,
            0);
  ASSERT_EQ(prt("-q merge p0.glb p1.glb -o m.glb").rc, 0);
  r = prt("-q merge p0.glb p1.glb -o -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, slurp(dir_ / "m.glb"));
  // A bake and a compressed bake (their files hold timings, so compared decoded).
  r = prt(std::string("-q bake ") + kSphere + " --mode shadowed --samples 16 -o -");
  ASSERT_EQ(r.rc, 0) << r.err;
  {
    const BakeFile piped =
        decodeBake(std::vector<unsigned char>(r.out.begin(), r.out.end()), "stdout");
    const BakeFile stored = readBake(path("b.glb"));
    const FloatArray& a = piped.transfers.at(0).transfer.values();
    const FloatArray& b = stored.transfers.at(0).transfer.values();
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
  }
  r = prt("-q compress b.glb --clusters 2 --pca 2 -o -");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_TRUE(decodeBake(std::vector<unsigned char>(r.out.begin(), r.out.end()), "stdout")
                  .transfers.at(0)
                  .transfer.compressed());
  EXPECT_NE(r.err.find("relative RMS error"), std::string::npos) << "the table moves to stderr";

  // Outputs that are not one stream refuse "-" in one line and write nothing.
  expectCleanFailure("render b.glb --size 16x12 --turntable 2 -o -", "-o -: --turntable");
  expectCleanFailure("web b.glb -o -", "standard output");
  expectCleanFailure("demo --mesh " + std::string(kSphere) + " -o -", "standard output");
  // Two outputs on one stream are refused (the report and the bake both on standard output).
  expectCleanFailure("compress b.glb --clusters 2 --pca 1 -o - --json -",
                     "both name standard output");
  // A file literally named "-" is still reachable as ./-.
  r = prt("-q export b.glb -o ./-");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "-"), plain_);
}

TEST_F(WritersCli, StaleTemporariesOfOurNamingAreRemovedAndSaid) {
  const std::string dead = std::to_string(deadPid()), live = std::to_string(::getpid());
  const std::string stale = ".t.txt.prt-tmp-" + dead + "-0badf00d";
  write(stale, "half of a killed run's output");
  const std::vector<std::string> kept = {
      ".t.txt.prt-tmp-" + live + "-0badf00d",  // a run still going
      ".u.txt.prt-tmp-" + dead + "-0badf00d",  // another output's
      "t.txt.tmp123456",                       // not our naming
      ".t.txt.prt-tmp-" + dead + "-notours"};
  for (const std::string& k : kept) write(k, "keep");
  write("precious", "keep");
  fs::create_symlink("precious", dir_ / (".t.txt.prt-tmp-" + dead + "-feedf00d"));
  const std::set<std::string> before = names(dir_);

  const Result r = prt("-q export b.glb -o t.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "t.txt"), plain_);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("prt: note: removed stale temporary "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(stale + " (left by process " + dead + ", which no longer runs)"),
            std::string::npos)
      << r.err;
  std::set<std::string> expected = before;
  expected.erase(stale);
  expected.insert("t.txt");
  EXPECT_EQ(names(dir_), expected);
  for (const std::string& k : kept) EXPECT_EQ(slurp(dir_ / k), "keep") << k;
  EXPECT_EQ(slurp(dir_ / "precious"), "keep");
}

TEST_F(WritersCli, AKilledWriteLeavesNoOutputAndTheNextRunRemovesItsTemporary) {
  // Killed by a signal in the middle of writing one file (SIGXFSZ at a 4 KiB file size limit:
  // deterministic, and like kill -9 it leaves no chance to clean up).
  const std::set<std::string> before = names(dir_);
  Result r = prt("export b.glb -o t.txt", "ulimit -c 0; ulimit -f 8; exec ");
  EXPECT_NE(r.rc, 0);
  EXPECT_FALSE(fs::exists(dir_ / "t.txt")) << "a half-written output is in place";
  std::set<std::string> left = names(dir_);
  for (const std::string& b : before) left.erase(b);
  ASSERT_EQ(left.size(), 1u) << "expected the killed run's temporary";
  const std::string tmp = *left.begin();
  r = prt("-q export b.glb -o t.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("prt: note: removed stale temporary"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(tmp), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir_ / "t.txt"), plain_);
  std::set<std::string> after = before;
  after.insert("t.txt");
  EXPECT_EQ(names(dir_), after);

  // kill -9 during a turntable: the frames wait in temporaries until the last is rendered, so
  // the kill leaves no frame in place; the next run removes every temporary and says so.
  const std::string turntable = "-q render b.glb --size 96x72 --spp 4 --turntable 12 -o out/t.png";
  const std::string cmd = "cd '" + dir_.string() + "' && exec '" + PRT_CLI_PATH + "' " + turntable +
                          " > kill-out.txt 2> kill-err.txt";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Kill it the moment anything appears in out/.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (fs::is_empty(dir_ / "out") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "prt finished before it was killed";
  const std::set<std::string> killed = names(dir_ / "out");
  ASSERT_FALSE(killed.empty());
  for (const std::string& n : killed) EXPECT_NE(n.rfind("t_", 0), 0u) << n << " is in place";
  r = prt(turntable);
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(count(r.err, "prt: note: removed stale temporary"), killed.size()) << r.err;
  std::set<std::string> frames;
  for (int k = 0; k < 12; ++k)
    frames.insert((k < 10 ? "t_00" : "t_0") + std::to_string(k) + ".png");
  EXPECT_EQ(names(dir_ / "out"), frames);
}

TEST_F(WritersCli, WebReplacesOnlyAFolderItMade) {
  if (!webBuilt()) GTEST_SKIP() << "the browser viewer's page is not built";
  // A folder of the user's: refused in one line, nothing written into it or beside it.
  fs::create_directories(dir_ / "out/mine");
  write("out/mine/index.html", "the user's page");
  Result r = prt("-q web b.glb -o out/mine");
  EXPECT_NE(r.rc, 0);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("out/mine: exists, is not empty and is not a prt web folder"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(names(dir_ / "out"), (std::set<std::string>{"mine"}));
  EXPECT_EQ(names(dir_ / "out/mine"), (std::set<std::string>{"index.html"}));
  EXPECT_EQ(slurp(dir_ / "out/mine/index.html"), "the user's page");
  // A bake named index.html in the folder it would write.
  fs::copy_file(dir_ / "b.glb", dir_ / "out/mine/bake.glb");
  fs::remove(dir_ / "out/mine/index.html");
  fs::rename(dir_ / "out/mine/bake.glb", dir_ / "out/mine/index.html");
  r = prt("-q web out/mine/index.html -o out/mine");
  EXPECT_NE(r.rc, 0);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("holds the input out/mine/index.html"), std::string::npos) << r.err;
  EXPECT_EQ(names(dir_ / "out"), (std::set<std::string>{"mine"}));
  EXPECT_EQ(names(dir_ / "out/mine"), (std::set<std::string>{"index.html"}));
  EXPECT_EQ(slurp(dir_ / "out/mine/index.html"), slurp(dir_ / "b.glb"));
  fs::remove_all(dir_ / "out/mine");

  // Its own folder: made whole, then replaced whole (a file added since is gone).
  r = prt("-q web b.glb -o out/w");
  ASSERT_EQ(r.rc, 0) << r.err;
  const std::set<std::string> made = names(dir_ / "out/w");
  for (const char* f : {"index.html", "prt-web.js", "prt-data.js", ".prt-output"})
    EXPECT_TRUE(made.count(f)) << f;
  write("out/w/added.txt", "x");
  r = prt("-q web b.glb --env 'builtin:constant?value=0.5' -o out/w/");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(names(dir_ / "out/w"), made);
  EXPECT_NE(slurp(dir_ / "out/w/prt-data.js").find("builtin:constant?value=0.5"),
            std::string::npos);
  EXPECT_EQ(names(dir_ / "out"), (std::set<std::string>{"w"}));
  // An input inside its own folder is refused too (the folder is replaced as a whole).
  fs::copy_file(dir_ / "b.glb", dir_ / "out/w/b.glb");
  r = prt("-q web out/w/b.glb -o out/w");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("holds the input out/w/b.glb"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out/w/b.glb"));
  // Through a link to its folder: the folder is replaced, the link stays.
  fs::remove(dir_ / "out/w/b.glb");
  fs::create_symlink("w", dir_ / "out/link");
  r = prt("-q web b.glb -o out/link");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(typeOf(dir_ / "out/link"), S_IFLNK);
  EXPECT_EQ(names(dir_ / "out"), (std::set<std::string>{"link", "w"}));
}

TEST_F(WritersCli, AFailurePartWayLeavesNoPartialFolderAndNoFrames) {
  // A file size limit makes a write fail part-way, as a full disk does (SIGXFSZ ignored, so the
  // write returns EFBIG and prt fails cleanly).
  const auto limited = [](std::size_t bytes) {
    return "trap '' XFSZ; ulimit -f " + std::to_string((bytes + 511) / 512) + "; ";
  };
  // Turntable frames and their contact sheet: the sheet (larger than any frame) fails.
  const std::string tt = "render b.glb --size 24x18 --spp 1 --turntable 6 ";
  Result r = prt("-q " + tt + "--contact-sheet sheet.png -o f.png");
  ASSERT_EQ(r.rc, 0) << r.err;
  std::size_t frame = 0;
  for (int k = 0; k < 6; ++k)
    frame =
        std::max<std::size_t>(frame, fs::file_size(dir_ / ("f_00" + std::to_string(k) + ".png")));
  const std::size_t sheet = fs::file_size(dir_ / "sheet.png");
  ASSERT_GT(sheet, (frame + 511) / 512 * 512 + 512) << "the sheet must exceed the limit";
  r = prt("-q " + tt + "--contact-sheet out/sheet.png -o out/f.png", limited(frame));
  EXPECT_NE(r.rc, 0);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("out/sheet.png: write failed (File too large)"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "frames or temporaries left behind";

  if (!webBuilt()) GTEST_SKIP() << "the browser viewer's page is not built";
  // prt web: its large script fails; no folder is made, and an earlier one stays as it was.
  const std::size_t small = 64 * 1024;  // index.html fits, prt-web.js does not
  r = prt("-q web b.glb -o out/new", limited(small));
  EXPECT_NE(r.rc, 0);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("out/new/prt-web.js: write failed"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "a partial folder was left";
  ASSERT_EQ(prt("-q web b.glb -o out/w").rc, 0);
  const std::string data = slurp(dir_ / "out/w/prt-data.js");
  const std::set<std::string> made = names(dir_ / "out/w");
  r = prt("-q web b.glb --env 'builtin:constant?value=0.5' -o out/w", limited(small));
  EXPECT_NE(r.rc, 0);
  EXPECT_EQ(names(dir_ / "out"), (std::set<std::string>{"w"}));
  EXPECT_EQ(names(dir_ / "out/w"), made);
  EXPECT_EQ(slurp(dir_ / "out/w/prt-data.js"), data);
}

}  // namespace
}  // namespace prt
