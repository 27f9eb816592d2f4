#pragma once
// Running the real `prt` binary from tests: a fresh scratch directory per test, the command's
// exit code, stdout and stderr, and the check every failure path must pass (one line naming the
// problem, non-zero exit, nothing left in out/).

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "common/scratch.hpp"

namespace prt::testing {

namespace fs = std::filesystem;

struct Result {
  int rc = -1;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
/// Replaces a file's bytes with `bytes` (tests that damage files).
inline void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

/// Runs `PREFIX prt ARGS` in `dir`, capturing stdout and stderr there.
inline Result runPrt(const fs::path& dir, const std::string& args, const std::string& prefix = "") {
  const std::string cmd = "cd '" + dir.string() + "' && " + prefix + "'" + PRT_CLI_PATH + "' " +
                          args + " > stdout.txt 2> stderr.txt";
  Result r;
  const int status = std::system(cmd.c_str());
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir / "stdout.txt");
  r.err = slurp(dir / "stderr.txt");
  return r;
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_ = std::make_unique<ScratchDir>();
    dir_ = scratch_->path();
    fs::create_directories(dir_ / "out");
  }
  void TearDown() override { scratch_.reset(); }

  /// Runs `PREFIX prt ARGS` in the test directory.
  Result prt(const std::string& args, const std::string& prefix = "") const {
    return runPrt(dir_, args, prefix);
  }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// A failing command: non-zero exit, exactly one stderr line naming the verb and the problem,
  /// no file left in out/.
  void expectCleanFailure(const std::string& args, const std::string& mention) const {
    SCOPED_TRACE(args);
    const Result r = prt("-q " + args);
    EXPECT_NE(r.rc, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos)
        << "expected '" << mention << "' in: " << r.err;
    EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "output left behind";
  }

  std::unique_ptr<ScratchDir> scratch_;
  fs::path dir_;
};

}  // namespace prt::testing
