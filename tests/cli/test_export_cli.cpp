// prt export of transfer matrices (issue 16, item 4): transport.txt holds diffuse vectors, so a
// matrix bake exports its diffuse part t = Mᵀ d(n) — what a diffuse surface relights with —
// never a slice of M.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_harness.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using ExportCli = CliTest;

/// The rows of a vertex-layout transport.txt (the first line is the vertex count).
std::vector<std::vector<double>> readTransport(const std::string& file) {
  std::ifstream in(file);
  std::size_t n = 0;
  in >> n;
  std::vector<std::vector<double>> rows(n, std::vector<double>(9));
  for (auto& r : rows)
    for (double& x : r) in >> x;
  EXPECT_TRUE(in) << file;
  return rows;
}

// Unshadowed, a convex sphere: the matrices' diffuse part is the hemisphere-restricted cosine
// lobe's projection, the vector bake the exact clamped cosine's. They agree except for the
// 3-band lobe's ringing below the horizon (under 1% of the largest coefficient), and the first
// coefficient is Y00 exactly (√(1/4π) = 0.282095) where row 0 of M would be ∫_H Y00² = 0.5.
TEST_F(ExportCli, MatrixBakeExportsItsDiffusePartNotARow) {
  const std::string sphere = "builtin:sphere?subdiv=2";
  ASSERT_EQ(prt("-q bake " + sphere + " --mode unshadowed --transfer matrix --bands 3 -o m.glb").rc,
            0);
  ASSERT_EQ(prt("-q bake " + sphere + " --mode unshadowed --bands 3 -o v.glb").rc, 0);
  const Result r = prt("export m.glb -o m.txt");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("exporting their diffuse part"), std::string::npos) << r.err;
  ASSERT_EQ(prt("-q export v.glb -o v.txt").rc, 0);
  const auto m = readTransport(path("m.txt")), v = readTransport(path("v.txt"));
  ASSERT_EQ(m.size(), v.size());
  ASSERT_GT(m.size(), 0u);
  double worst = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    EXPECT_NEAR(m[i][0], 0.28209479, 1e-6) << "vertex " << i;
    for (int k = 0; k < 9; ++k) worst = std::max(worst, std::abs(m[i][k] - v[i][k]));
  }
  EXPECT_LT(worst, 0.005);
  EXPECT_GT(worst, 0.0) << "the hemisphere-restricted lobe differs from the clamped cosine";
}

}  // namespace
}  // namespace prt
