#pragma once
// Small fixture files written by the geometry tests into a fresh temporary directory.

#include "common/scratch.hpp"

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>

namespace prt::test {

/// A temporary directory of the running test, removed at its end (tests/common/scratch.hpp).
using TempDir = prt::testing::ScratchDir;

}  // namespace prt::test
