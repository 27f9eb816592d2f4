// The fuzz targets as ordinary test programs (any compiler, no libFuzzer): feeds every file of
// the folders given to LLVMFuzzerTestOneInput, in name order, so the seed corpus (written by
// make_seeds at build time) and the committed regression inputs (fuzz/corpus/TARGET/) are
// replayed by ctest (label fuzz-replay) and a fixed finding stays fixed.
//
//   fuzz_replay_TARGET DIR...
//
// What counts as a failure is what scripts/fuzz.sh counts: a crash (the test dies), an exception
// other than prt::Error escaping, a single allocation over 1 GiB (-malloc_limit_mb=1024), an
// input taking over 10 s. Regression inputs can also state the outcome their fix promises by
// their name: reject_* must be refused with prt::Error (garbage once decoded silently), accept_*
// must be read without one.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <new>
#include <string>
#include <vector>

#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

constexpr std::size_t kMaxAllocation = std::size_t(1) << 30;

void* allocate(std::size_t n) {
  if (n > kMaxAllocation) {
    std::fprintf(stderr, "fuzz replay: an allocation of %zu bytes (over 1 GiB)\n", n);
    throw std::bad_alloc();
  }
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}

}  // namespace

// GCC cannot see that these new and delete are a matched malloc/free pair.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t n) {
  return allocate(n);
}
void* operator new[](std::size_t n) {
  return allocate(n);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s DIR...\n", argv[0]);
    return 2;
  }
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    std::error_code ec;
    if (!fs::is_directory(argv[i], ec)) {
      std::fprintf(stderr, "fuzz replay: %s is not a folder\n", argv[i]);
      return 2;
    }
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(argv[i]))
      if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "fuzz replay: no inputs in the folders given\n");
    return 2;
  }
  int failures = 0;
  for (const fs::path& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string name = f.filename().string();
    const auto t0 = std::chrono::steady_clock::now();
    prt::fuzz::rejected() = false;
    try {
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    } catch (const std::exception& e) {
      std::printf("FAIL %s: %s escaped (not prt::Error)\n", f.c_str(), e.what());
      ++failures;
      continue;
    } catch (...) {
      std::printf("FAIL %s: a non-standard exception escaped\n", f.c_str());
      ++failures;
      continue;
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const bool rejected = prt::fuzz::rejected();
    std::string verdict;
    if (s > 10) verdict = "took " + std::to_string(s) + " s (over 10 s)";
    if (name.rfind("reject_", 0) == 0 && !rejected) verdict = "was read, but must be refused";
    if (name.rfind("accept_", 0) == 0 && rejected) verdict = "was refused, but must be read";
    if (!verdict.empty()) {
      std::printf("FAIL %s: %s\n", f.c_str(), verdict.c_str());
      ++failures;
    } else {
      std::printf("ok   %s (%zu bytes, %s, %.3f s)\n", f.c_str(), bytes.size(),
                  rejected ? "refused" : "read", s);
    }
  }
  std::printf("%zu inputs, %d failures\n", files.size(), failures);
  return failures ? 1 : 0;
}
