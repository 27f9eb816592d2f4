// prt denoise and prt bake --denoise (issue 35; transport/denoise_texels.hpp): the verb filters
// every transfer of a per-texel bake and says what it did; --denoise in the bake gives the same
// file; the lightmap says `denoised` (prt info); the filter brings a noisy bake closer to a
// converged one; and what it cannot filter is refused in one line naming the file, nothing
// written.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "prt/io/bake_file.hpp"

namespace prt {
namespace {

using namespace prt::testing;
using DenoiseCli = CliTest;

const std::string kBox = "'builtin:cornell?grid=6'";

/// Relative RMS of a − b over their rows (‖a − b‖ / ‖b‖).
double relRms(const Transfer& a, const Transfer& b) {
  double e = 0, r = 0;
  for (std::size_t i = 0; i < a.values().size(); ++i) {
    const double d = double(a.values()[i]) - b.values()[i];
    e += d * d, r += double(b.values()[i]) * b.values()[i];
  }
  return std::sqrt(e / r);
}

TEST_F(DenoiseCli, DenoiseFiltersEveryTransferAndBakeDenoiseIsTheSame) {
  const std::string bake = "bake " + kBox +
                           " --mode shadowed --mode interreflected --domain texels --resolution "
                           "48 --samples 64";
  ASSERT_EQ(prt("-q " + bake + " -o noisy.glb").rc, 0);
  const Result r = prt("denoise noisy.glb -o clean.glb --json report.json");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("a-trous filter, 3 levels, strength 2"), std::string::npos) << r.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(dir_ / "report.json"));
  EXPECT_EQ(report["verb"], "denoise");
  ASSERT_EQ(report["denoise"].size(), 2u);
  for (const nlohmann::json& t : report["denoise"]) {
    EXPECT_GT(t["texels"].get<int>(), 1000);
    EXPECT_LT(t["noiseAfter"].get<double>(), 0.5 * t["noiseBefore"].get<double>());
  }
  const Result info = prt("info clean.glb --json -");
  ASSERT_EQ(info.rc, 0) << info.err;
  EXPECT_TRUE(nlohmann::json::parse(info.out)["files"][0]["lightmap"]["denoised"].get<bool>());

  // prt bake --denoise: the same bytes as baking, then prt denoise.
  ASSERT_EQ(prt("-q " + bake + " --denoise -o baked.glb").rc, 0);
  const BakeFile a = readBake(path("clean.glb")), b = readBake(path("baked.glb"));
  ASSERT_EQ(a.transfers.size(), b.transfers.size());
  for (std::size_t i = 0; i < a.transfers.size(); ++i) {
    const FloatArray &x = a.transfers[i].transfer.values(), &y = b.transfers[i].transfer.values();
    ASSERT_EQ(x.size(), y.size());
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << i;
  }
  EXPECT_TRUE(b.lightmap().denoised);

  // Closer to a converged bake than the noisy one.
  ASSERT_EQ(prt("-q bake " + kBox +
                " --mode shadowed --mode interreflected --domain texels --resolution 48 "
                "--samples 4096 -o ref.glb")
                .rc,
            0);
  const BakeFile ref = readBake(path("ref.glb")), noisy = readBake(path("noisy.glb"));
  for (std::size_t i = 0; i < ref.transfers.size(); ++i) {
    const double before = relRms(noisy.transfers[i].transfer, ref.transfers[i].transfer),
                 after = relRms(a.transfers[i].transfer, ref.transfers[i].transfer);
    std::printf("%s: rel RMS against 4,096 samples %.4f -> %.4f\n",
                ref.transfers[i].describe().c_str(), before, after);
    EXPECT_LT(after, 0.6 * before);
  }
}

TEST_F(DenoiseCli, RefusesWhatItCannotFilterInOneLine) {
  ASSERT_EQ(prt("-q bake " + kBox + " --mode shadowed --samples 16 -o v.glb").rc, 0);
  ASSERT_EQ(prt("-q bake " + kBox +
                " --mode shadowed --domain texels --resolution 16 --samples 16 --range 0:100 "
                "-o part.glb")
                .rc,
            0);
  ASSERT_EQ(prt("-q bake " + kBox + " --mode shadowed --domain texels --resolution 16 "
                "--samples 16 -o t.glb")
                .rc,
            0);
  ASSERT_EQ(prt("-q compress t.glb --clusters 2 --pca 2 -o c.glb").rc, 0);
  expectCleanFailure("denoise v.glb -o out/x.glb", "v.glb: holds vertices transfer");
  expectCleanFailure("denoise part.glb -o out/x.glb", "part.glb");
  expectCleanFailure("denoise c.glb -o out/x.glb", "c.glb: holds compressed transfer");
  expectCleanFailure("denoise missing.glb -o out/x.glb", "missing.glb");
  expectCleanFailure("denoise t.glb -o out/x.png", "out/x.png: the bake file must end in .glb");
  expectCleanFailure("denoise t.glb --iterations 9 -o out/x.glb", "--iterations");
  expectCleanFailure("denoise t.glb -o t.glb", "t.glb");
  expectCleanFailure("bake " + kBox + " --mode shadowed --denoise -o out/x.glb",
                     "--denoise filters a lightmap: add --domain texels");
  expectCleanFailure("bake " + kBox +
                         " --mode shadowed --domain texels --resolution 16 --denoise --range 0:10 "
                         "-o out/x.glb",
                     "--denoise needs the whole lightmap");
  expectCleanFailure("probes " + kBox + " --grid 2x2x2 --denoise -o out/x.glb", "--denoise");
}

}  // namespace
}  // namespace prt
