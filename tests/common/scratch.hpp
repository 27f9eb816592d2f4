#pragma once
// One scratch folder per running test: <tmp>/prt_<Suite>_<Test>_<pid>, created empty on
// construction and removed on destruction. Named after the running gtest and the process, so
// tests that run in parallel (ctest -j runs each test in its own process) never share a folder,
// and a leftover folder says which test left it.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace prt::testing {

class ScratchDir {
 public:
  /// `tag` distinguishes several scratch folders within one test.
  explicit ScratchDir(const std::string& tag = "") {
    std::string name = "prt";
    // Appends one piece at a time (GCC 12 warns, wrongly, on "_" + std::string temporaries).
    const auto add = [&name](const std::string& part) {
      name += '_';
      name += part;
    };
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
      add(info->test_suite_name());
      add(info->name());
    }
    if (!tag.empty()) add(tag);
    add(std::to_string(::getpid()));
    for (char& c : name)  // parameterised tests have '/' in their names
      if (c == '/' || c == ' ') c = '_';
    path_ = std::filesystem::temp_directory_path() / name;
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// The path of `name` inside the folder.
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string operator/(const std::string& name) const { return file(name); }
  /// Writes `bytes` to `name` inside the folder and returns its path.
  std::string write(const std::string& name, std::string_view bytes) const {
    const std::string p = file(name);
    std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return p;
  }

 private:
  std::filesystem::path path_;
};

/// One scratch folder for a whole test program, for fixtures its tests share:
/// <tmp>/prt_test_<program>_<pid>, created empty on first use (the first call's `program`
/// names it). Remove it at the end with `registerProgramScratchCleanup()`.
inline const std::filesystem::path& programScratch(const std::string& program) {
  static const std::filesystem::path dir = [&program] {
    std::filesystem::path d = std::filesystem::temp_directory_path() /
                              ("prt_test_" + program + "_" + std::to_string(::getpid()));
    std::error_code ec;
    std::filesystem::remove_all(d, ec);
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

/// Registers a gtest environment that removes programScratch's folder when the program's tests
/// are done; call it from a namespace-scope initialiser (before RUN_ALL_TESTS). Returns true.
inline bool registerProgramScratchCleanup(const std::string& program) {
  struct Cleanup : ::testing::Environment {
    std::string program;
    explicit Cleanup(std::string p) : program(std::move(p)) {}
    void TearDown() override {
      std::error_code ec;
      std::filesystem::remove_all(programScratch(program), ec);
    }
  };
  ::testing::AddGlobalTestEnvironment(new Cleanup(program));
  return true;
}

}  // namespace prt::testing
