// One bake, reference or validation across MPI ranks (docs/distributed.md), run as a user would:
// the real `prt` under the real `mpirun` (Open MPI; as root, OMPI_ALLOW_RUN_AS_ROOT, ranks
// oversubscribed on this machine's cores, loopback only), each result against the same command
// in one process:
//  * bakes on 1, 2, 3 and 4 ranks with 1 or 2 threads each — shadowed, inter-reflected with two
//    bounces (scalar and RGB), glossy matrices — equal the single-process file;
//  * a reference and a validation table through MPI equal the single-process ones;
//  * a rank that dies mid-bake (the test hook PRT_TEST_EXIT_AT_CHUNK) fails the job quickly with
//    one line naming it and its chunk and no output file; rerun with the same --checkpoint, the
//    bake resumes from the finished chunks and ends bit-identical;
//  * per-texel bakes (shadowed, bounces, a range, glossy matrices) through MPI equal the
//    single-process file, and per-texel bounces split pass by pass into job-array shards merge
//    bit-exactly;
//  * job-array shards (--shard I/N, and --pass K --previous for the bounces) merge bit-exactly.
//
// "Equal the single-process file": a bake file records its timings (seconds per pass, rays per
// second) and the thread count in each transfer's statistics, and those differ between any two
// runs, one process or many. So both files are decoded, those fields (and only those) are set
// to zero, and the two are encoded again and compared byte for byte: the mesh, every transfer
// value, the recipes, the rays and the error estimates must be identical bit for bit.
//
// The MPI tests skip, saying why, where mpirun is missing or prt was built without MPI.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <string>

#include "cli/cli_harness.hpp"
#include "prt/io/bake_file.hpp"

namespace prt::testing {
namespace {

/// The bake file's bytes with the statistics that vary from run to run (timings, threads)
/// zeroed: what must be identical between two bakes of the same inputs and settings.
std::string withoutTimings(const fs::path& path) {
  BakeFile f = readBake(path.string());
  for (BakedTransfer& t : f.transfers) {
    BakeStats& s = t.stats;
    s.secondsTotal = s.secondsDirect = s.raysPerSecond = 0;
    for (double& b : s.secondsBounce) b = 0;
    s.threads = 0;
  }
  return encodeBake(f);
}

/// The transfers' values and rays only: a merge of job-array pieces combines the error
/// estimates' means weighted by rows (combineBakeStats), which need not round as one bake does.
/// Per texel the rays are the work done: each piece's last pass also casts the rays of the
/// texels its dilation reads beyond its rows (the merged bake counts them, not fewer).
void expectSameTransfers(const fs::path& a, const fs::path& b) {
  const BakeFile fa = readBake(a.string()), fb = readBake(b.string());
  ASSERT_EQ(fa.transfers.size(), fb.transfers.size());
  for (std::size_t i = 0; i < fa.transfers.size(); ++i) {
    const Transfer& x = fa.transfers[i].transfer;
    const Transfer& y = fb.transfers[i].transfer;
    ASSERT_EQ(x.shape(), y.shape()) << fa.transfers[i].describe();
    ASSERT_EQ(x.values().size(), y.values().size());
    EXPECT_EQ(0, std::memcmp(x.values().data(), y.values().data(), x.values().size() * 4))
        << fa.transfers[i].describe() << ": values differ";
    EXPECT_TRUE(fa.transfers[i].recipe == fb.transfers[i].recipe);
    if (x.domain() == TransferDomain::Texels) {
      EXPECT_GE(fa.transfers[i].stats.rays, fb.transfers[i].stats.rays);
      continue;
    }
    EXPECT_EQ(fa.transfers[i].stats.rays, fb.transfers[i].stats.rays);
    EXPECT_EQ(fa.transfers[i].stats.raysBounce, fb.transfers[i].stats.raysBounce);
  }
}

bool haveMpirun() {
  return std::system("command -v mpirun > /dev/null 2>&1") == 0;
}

/// mpirun as the suite runs it: as root (CI), more ranks than cores, loopback only.
std::string mpirun(int ranks) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_tcp_if_include=lo "
         "OMPI_MCA_oob_tcp_if_include=lo mpirun --oversubscribe -np " +
         std::to_string(ranks) + " ";
}

class Mpi : public CliTest {
 protected:
  void SetUp() override {
#if !PRT_HAVE_MPI
    GTEST_SKIP() << "prt was built without MPI (find_package(MPI) found none; scripts/setup.sh "
                    "installs openmpi-bin and libopenmpi-dev)";
#endif
    if (!haveMpirun()) GTEST_SKIP() << "mpirun is not installed (Debian: openmpi-bin)";
    CliTest::SetUp();
  }
  fs::path dir() const {
    return dir_;
  }
};

constexpr const char* kVector =
    "bake builtin:sphere-plane --mode shadowed --mode interreflected --bounces 2 --samples 32";

TEST_F(Mpi, BakesOnOneToFourRanksEqualTheSingleProcessFile) {
  ASSERT_EQ(prt(std::string(kVector) + " -q -o one.glb").rc, 0);
  const std::string one = withoutTimings(dir() / "one.glb");
  for (int ranks = 1; ranks <= 4; ++ranks) {
    const std::string out = "mpi" + std::to_string(ranks) + ".glb";
    // 2 threads per rank on 1 and 3 ranks, 1 on 2 and 4; small chunks on 3, so that every rank
    // gets many and the order they come back in is scrambled.
    const std::string extra =
        std::string(ranks % 2 ? " -j 2" : " -j 1") + (ranks == 3 ? " --chunk 37" : "");
    const Result r = prt(std::string(kVector) + extra + " -o " + out, mpirun(ranks));
    ASSERT_EQ(r.rc, 0) << ranks << " ranks: " << r.err;
    EXPECT_NE(r.err.find(std::to_string(ranks) + " MPI ranks"), std::string::npos) << r.err;
    EXPECT_EQ(withoutTimings(dir() / out), one) << ranks << " ranks";
  }
}

TEST_F(Mpi, RgbBouncesAndGlossyMatricesEqualTheSingleProcessFile) {
  // The Cornell box's coloured walls make RGB bounces; glossy matrices bounce through the lobe
  // (three matrix passes, each all-gathered); diffuse-bounce matrices read the vector passes' sum.
  const std::string rgb = "bake builtin:cornell --mode interreflected --bounces 2 --samples 32";
  const std::string glossy =
      "bake builtin:sphere-plane --mode interreflected --bounces 2 --transfer matrix --bands 3 "
      "--samples 16 --material 'phong?exponent=8&ks=0.4,0.3,0.3'";
  const std::string diffuse =
      "bake builtin:cornell --mode interreflected --bounces 1 --transfer matrix --bands 3 "
      "--samples 16";
  // Inter-reflected Haar: the bounce's SH passes, then the Haar rows that read their sum.
  const std::string haar =
      "bake builtin:cornell --mode interreflected --bounces 2 --basis haar --resolution 8 "
      "--terms 16 --bands 2";
  int ranks = 2;
  for (const std::string& cmd : {rgb, glossy, diffuse, haar}) {
    ASSERT_EQ(prt(cmd + " -q -o one.glb").rc, 0) << cmd;
    // The matrix bakes as if they did not fit rank 0's memory: it gathers the last pass into a
    // mapped scratch file beside the output, which the writer streams from.
    const bool matrix = cmd.find("matrix") != std::string::npos;
    const Result r = prt(cmd + " -o out/mpi.glb",
                         std::string(matrix ? "PRT_MPI_SPILL_ABOVE=1 " : "") + mpirun(ranks));
    ASSERT_EQ(r.rc, 0) << cmd << ": " << r.err;
    EXPECT_EQ(matrix, r.err.find("in a mapped scratch file") != std::string::npos) << r.err;
    EXPECT_EQ(withoutTimings(dir() / "out/mpi.glb"), withoutTimings(dir() / "one.glb"))
        << cmd << " on " << ranks << " ranks";
    // Nothing but the bake is left beside it (the scratch file was unlinked when made).
    const auto files = std::distance(fs::directory_iterator(dir() / "out"), {});
    EXPECT_EQ(files, 1);
    ++ranks;
  }
}

// Adaptive sampling decides each row's rays from its own pilot, so any split of the rows among
// ranks and chunks gives the same file.
TEST_F(Mpi, AnAdaptiveBakeEqualsTheSingleProcessFile) {
  const std::string cmd =
      "bake builtin:cornell --mode interreflected --bounces 1 --samples 1024 --target-error 0.03";
  ASSERT_EQ(prt(cmd + " -q -o one.glb").rc, 0);
  const Result r = prt(cmd + " --chunk 37 -o mpi.glb", mpirun(3));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(withoutTimings(dir() / "mpi.glb"), withoutTimings(dir() / "one.glb"));
}

TEST_F(Mpi, ReferenceAndValidationEqualTheSingleProcessOnes) {
  ASSERT_EQ(prt("bake builtin:sphere-plane --mode interreflected --bounces 1 --samples 32 -q "
                "-o b.glb")
                .rc,
            0);
  const std::string ref = "reference b.glb --light builtin:sky --samples 16 --vertices 600 -q";
  ASSERT_EQ(prt(ref + " -o one.bin").rc, 0);
  const Result r = prt(ref + " -o mpi.bin", mpirun(3));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(slurp(dir() / "mpi.bin"), slurp(dir() / "one.bin"));

  const std::string val =
      "validate b.glb --light builtin:sky --reference-samples 16 --vertices 300 -q";
  const Result v1 = prt(val + " --json one.json");
  ASSERT_EQ(v1.rc, 0) << v1.err;
  const Result v2 = prt(val + " --json mpi.json", mpirun(2));
  ASSERT_EQ(v2.rc, 0) << v2.err;
  EXPECT_EQ(v2.out, v1.out);  // the table, printed by rank 0 alone
  // The report's JSON holds the reference's seconds: everything else must match.
  const auto strip = [](std::string s) {
    for (const char* key : {"\"referenceSeconds\"", "\"floorSeconds\""}) {
      const auto at = s.find(key);
      if (at != std::string::npos) s.erase(at, s.find('\n', at) - at);
    }
    return s;
  };
  EXPECT_EQ(strip(slurp(dir() / "mpi.json")), strip(slurp(dir() / "one.json")));
}

TEST_F(Mpi, AKilledRankFailsTheJobCleanlyAndACheckpointResumesBitIdentical) {
  const std::string bake =
      "bake builtin:sphere-plane --mode interreflected --bounces 2 --samples 32 -j 1 "
      "--checkpoint ck -o out/b.glb";
  const auto t0 = std::chrono::steady_clock::now();
  // Rank 1 exits (status 3, no message, as a crash would) when handed its fourth chunk.
  const Result dead = prt(bake, "PRT_TEST_EXIT_AT_CHUNK=1:3 " + mpirun(2));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_NE(dead.rc, 0);
  EXPECT_LT(seconds, 30) << "the job took " << seconds << " s to stop";
  // One line of ours names the rank and its chunk (mpirun adds its own banner around it).
  std::size_t lines = 0, at = 0;
  while ((at = dead.err.find("prt bake: error: ", at)) != std::string::npos) ++lines, ++at;
  EXPECT_EQ(lines, 1u) << dead.err;
  EXPECT_NE(dead.err.find("rank 1 (pid "), std::string::npos) << dead.err;
  EXPECT_NE(dead.err.find("died while computing chunk "), std::string::npos) << dead.err;
  EXPECT_NE(dead.err.find(" (vertices "), std::string::npos) << dead.err;
  EXPECT_TRUE(fs::is_empty(dir() / "out")) << "a partial output was left";

  const Result resumed = prt(bake, mpirun(2));
  ASSERT_EQ(resumed.rc, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("from the checkpoint"), std::string::npos) << resumed.err;
  ASSERT_EQ(prt("bake builtin:sphere-plane --mode interreflected --bounces 2 --samples 32 -q "
                "-o one.glb")
                .rc,
            0);
  EXPECT_EQ(withoutTimings(dir() / "out/b.glb"), withoutTimings(dir() / "one.glb"));

  // Another bake refuses the folder rather than mixing chunks.
  const Result other =
      prt("bake builtin:sphere-plane --mode interreflected --bounces 2 "
          "--samples 64 --checkpoint ck -o out/c.glb",
          mpirun(2));
  EXPECT_NE(other.rc, 0);
  EXPECT_NE(other.err.find("holds the checkpoint of another run"), std::string::npos) << other.err;
  EXPECT_FALSE(fs::exists(dir() / "out/c.glb"));
}

TEST_F(Mpi, ADamagedOrForeignCheckpointChunkIsRefusedByName) {
  // The issue: a flipped byte in a chunk, or a chunk copied in from a run with another seed,
  // was loaded silently (the transfer off by 0.017, exit 0). Each chunk now carries the run's
  // identity and a checksum of its rows.
  const auto bake = [&](const std::string& seed, const std::string& ck) {
    return prt("bake builtin:sphere-plane --mode shadowed --bands 3 --samples 16 -j 1 -q --seed " +
                   seed + " --checkpoint " + ck + " -o out/" + ck + ".glb",
               mpirun(2));
  };
  ASSERT_EQ(bake("1", "ck").rc, 0);
  ASSERT_EQ(bake("2", "other").rc, 0);
  const fs::path chunk = dir() / "ck/shadowed/pass-0/chunk-000001.bin";
  ASSERT_TRUE(fs::exists(chunk));
  const std::string good = slurp(chunk);
  // A rerun loads its own chunks.
  ASSERT_EQ(bake("1", "ck").rc, 0);

  std::string flipped = good;
  flipped[flipped.size() - 7] ^= 0x10;
  spit(chunk, flipped);
  const Result damaged = bake("1", "ck");
  EXPECT_NE(damaged.rc, 0);
  EXPECT_NE(damaged.err.find("chunk-000001.bin: is damaged (its checksum does not match its rows)"),
            std::string::npos)
      << damaged.err;

  spit(chunk, slurp(dir() / "other/shadowed/pass-0/chunk-000001.bin"));
  const Result foreign = bake("1", "ck");
  EXPECT_NE(foreign.rc, 0);
  EXPECT_NE(foreign.err.find("chunk-000001.bin: is a chunk of another run"), std::string::npos)
      << foreign.err;

  spit(chunk, good);
  EXPECT_EQ(bake("1", "ck").rc, 0);
}

/// How many times `needle` occurs in `s`.
std::size_t occurrences(const std::string& s, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = s.find(needle); at != std::string::npos; at = s.find(needle, at + 1)) ++n;
  return n;
}

TEST_F(Mpi, TheRankThatDiedFirstIsTheOneNamedOnFourRanks) {
  // The issue: on 4 ranks the line named the wrong rank, or none was printed (4 of 7 trials; on
  // 2 ranks always right). Rank 0 looked, when the runtime's SIGTERM came (a second after the
  // death), for any rank on its host that was gone — and by then the runtime was stopping the
  // others too (rank 1 first), or sent SIGKILL before rank 0 had written anything. Small chunks
  // and seconds of work left after the death keep rank 0's coordinator busy, so that only the
  // runtime's teardown would have ended the job; two threads a rank keep the cores busy, as a
  // loaded machine's are. Ranks 2 and 3 die, in turn.
  const std::string bake =
      "bake builtin:sphere-plane --mode shadowed --samples 4096 --chunk 16 -j 2 -o out/b.glb";
  const auto t0 = std::chrono::steady_clock::now();
  for (int trial = 0; trial < 4; ++trial) {
    const int rank = 2 + trial % 2;
    SCOPED_TRACE("trial " + std::to_string(trial) + ", rank " + std::to_string(rank) + " dies");
    const Result dead =
        prt(bake, "PRT_TEST_EXIT_AT_CHUNK=" + std::to_string(rank) + ":1 " + mpirun(4));
    EXPECT_NE(dead.rc, 0);
    EXPECT_EQ(occurrences(dead.err, "prt bake: error: "), 1u) << dead.err;
    EXPECT_NE(dead.err.find("prt bake: error: rank " + std::to_string(rank) + " (pid "),
              std::string::npos)
        << dead.err;
    EXPECT_NE(dead.err.find("died while computing chunk "), std::string::npos) << dead.err;
    EXPECT_TRUE(fs::is_empty(dir() / "out")) << "a partial output was left";
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 30) << "four killed jobs took " << seconds << " s to stop";
}

TEST_F(Mpi, ABadOptionOnFourRanksPrintsOurOneLineEveryTime) {
  // The issue: `mpirun -np 4 prt bake ... --mode bogus` sometimes printed only Open MPI's banner.
  // Every rank refuses the mode and they agree; the other ranks exited 1 at once, so mpirun
  // stopped rank 0 (SIGTERM) before it had printed the failure.
  for (int trial = 0; trial < 10; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Result r = prt("bake builtin:sphere --mode bogus -o out/x.glb", mpirun(4));
    EXPECT_NE(r.rc, 0);
    EXPECT_EQ(occurrences(r.err, "prt bake: error: "), 1u) << r.err;
    EXPECT_NE(r.err.find("prt bake: error: unknown transfer mode 'bogus'"), std::string::npos)
        << r.err;
    EXPECT_TRUE(fs::is_empty(dir() / "out"));
  }
}

// Job arrays need no MPI: these run wherever prt does.
TEST_F(Mpi, PerTexelBakesEqualTheSingleProcessFile) {
  // The texel domain through the same pass driver: shadowed and RGB bounces (each bounce pass
  // all-gathered, then laid out and dilated on every rank), a range whose last pass widens by
  // the dilation's reach, and glossy-bounce matrices spilled by rank 0.
  const std::string box = "bake 'builtin:cornell?grid=8' --domain texels --samples 16 ";
  const std::string cases[] = {
      box + "--mode shadowed --mode interreflected --bounces 2 --resolution 40 --padding 3",
      box + "--mode interreflected --bounces 1 --resolution 48 --range 700:1500",
      "bake builtin:sphere-plane --domain texels --resolution 24 --samples 8 --mode "
      "interreflected --bounces 2 --transfer matrix --bands 3 --material "
      "'phong?exponent=8&ks=0.4,0.3,0.3'"};
  int ranks = 2;
  for (const std::string& cmd : cases) {
    ASSERT_EQ(prt(cmd + " -q -o one.glb").rc, 0) << cmd;
    const bool matrix = cmd.find("matrix") != std::string::npos;
    const Result r = prt(cmd + " --chunk 97 -o mpi.glb",
                         std::string(matrix ? "PRT_MPI_SPILL_ABOVE=1 " : "") + mpirun(ranks));
    ASSERT_EQ(r.rc, 0) << cmd << ": " << r.err;
    EXPECT_NE(r.err.find(std::to_string(ranks) + " MPI ranks"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("texels sampled"), std::string::npos) << r.err;
    EXPECT_EQ(withoutTimings(dir() / "mpi.glb"), withoutTimings(dir() / "one.glb"))
        << cmd << " on " << ranks << " ranks";
    ++ranks;
  }
}

class JobArray : public CliTest {
 protected:
  fs::path dir() const { return dir_; }
};

TEST_F(JobArray, MoreShardsThanRowsLeaveTheEmptyOnesOutAndStillMerge) {
  // The issue: --shard I/N with N larger than the row count baked everything ("0 vertices
  // 0..18446744073709551615"). Four vertices in six shards: shards 0 and 3 hold none; they say
  // so, write nothing and exit 0, and the other four pieces merge into the whole bake.
  write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  const std::string bake = "bake quad.obj --mode shadowed --bands 3 --samples 16";
  ASSERT_EQ(prt(bake + " -q -o one.glb").rc, 0);
  std::string pieces;
  for (int i = 0; i < 6; ++i) {
    const std::string out = "s" + std::to_string(i) + ".glb";
    const Result r = prt(bake + " --shard " + std::to_string(i) + "/6 --json s" +
                         std::to_string(i) + ".json -o " + out);
    ASSERT_EQ(r.rc, 0) << r.err;
    const bool empty = i == 0 || i == 3;
    EXPECT_EQ(fs::exists(dir() / out), !empty) << i;
    EXPECT_EQ(r.err.find("18446744073709551615"), std::string::npos) << r.err;
    if (empty) {
      EXPECT_NE(r.err.find("shard " + std::to_string(i) +
                           " of 6 holds none of the 4 vertices (more shards than vertices): "
                           "nothing to bake, " + out + " not written"),
                std::string::npos)
          << r.err;
      EXPECT_NE(slurp(dir() / ("s" + std::to_string(i) + ".json")).find("\"empty\": true"),
                std::string::npos);
    } else {
      pieces += " " + out;
    }
  }
  ASSERT_EQ(prt("merge" + pieces + " -q -o merged.glb").rc, 0);
  expectSameTransfers(dir() / "merged.glb", dir() / "one.glb");

  // Pass shards alike: pass 0 of an interreflected bake in six shards.
  const std::string ir = "bake quad.obj --mode interreflected --bounces 1 --bands 3 --samples 16 "
                         "--pass 0 -q";
  const Result empty = prt(ir + " --shard 3/6 -o p3.prtpass");
  EXPECT_EQ(empty.rc, 0) << empty.err;
  EXPECT_FALSE(fs::exists(dir() / "p3.prtpass"));
}

TEST_F(JobArray, ShardsMergeBitExactly) {
  const std::string bake = "bake builtin:cornell --mode shadowed --samples 32 -q";
  ASSERT_EQ(prt(bake + " -o one.glb").rc, 0);
  for (int i = 0; i < 3; ++i)
    ASSERT_EQ(
        prt(bake + " --shard " + std::to_string(i) + "/3 -o s" + std::to_string(i) + ".glb").rc, 0);
  // Slurm's array variables (an array 4-6 here) name the shard as --shard auto reads them.
  const Result slurm =
      prt(bake + " --shard auto -o auto.glb",
          "SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_MIN=4 SLURM_ARRAY_TASK_COUNT=3 ");
  ASSERT_EQ(slurm.rc, 0) << slurm.err;
  expectSameTransfers(dir() / "auto.glb", dir() / "s1.glb");
  ASSERT_EQ(prt("merge s2.glb s0.glb s1.glb -q -o merged.glb").rc, 0);
  expectSameTransfers(dir() / "merged.glb", dir() / "one.glb");
}

TEST_F(JobArray, BouncesShardPassByPassAndMergeBitExactly) {
  for (const std::string& bake :
       {std::string("bake builtin:cornell --mode interreflected --bounces 2 --samples 32 -q"),
        std::string("bake builtin:sphere-plane --mode interreflected --bounces 2 --transfer "
                    "matrix --bands 3 --samples 16 --material 'phong?exponent=8&ks=0.4' -q"),
        // Inter-reflected Haar, one bounce: the SH direct pass, the bounce, the Haar rows.
        std::string("bake builtin:cornell --mode interreflected --bounces 1 --basis haar "
                    "--resolution 8 --terms 16 --bands 2 -q")}) {
    ASSERT_EQ(prt(bake + " -o one.glb").rc, 0);
    // Pass 0 in 2 shards, pass 1 in 3 reading the merged pass 0, the last in 2.
    for (int i = 0; i < 2; ++i)
      ASSERT_EQ(prt(bake + " --pass 0 --shard " + std::to_string(i) + "/2 -o p0-" +
                    std::to_string(i) + ".prtpass")
                    .rc,
                0);
    ASSERT_EQ(prt("merge p0-1.prtpass p0-0.prtpass -q -o p0.prtpass").rc, 0);
    for (int i = 0; i < 3; ++i)
      ASSERT_EQ(prt(bake + " --pass 1 --previous p0.prtpass --shard " + std::to_string(i) +
                    "/3 -o p1-" + std::to_string(i) + ".prtpass")
                    .rc,
                0);
    // A pass that reads an incomplete previous pass is refused, naming what is missing.
    const Result partial = prt(bake + " --pass 2 --previous p1-0.prtpass -o x.glb");
    EXPECT_NE(partial.rc, 0);
    EXPECT_NE(partial.err.find("merge all its pieces first"), std::string::npos) << partial.err;
    ASSERT_EQ(prt("merge p1-0.prtpass p1-1.prtpass p1-2.prtpass -q -o p1.prtpass").rc, 0);
    for (int i = 0; i < 2; ++i)
      ASSERT_EQ(prt(bake + " --pass 2 --previous p1.prtpass --shard " + std::to_string(i) +
                    "/2 -o last" + std::to_string(i) + ".glb")
                    .rc,
                0);
    ASSERT_EQ(prt("merge last0.glb last1.glb -q -o merged.glb").rc, 0);
    expectSameTransfers(dir() / "merged.glb", dir() / "one.glb");
  }
}

TEST_F(JobArray, PerTexelBouncesShardPassByPassAndMergeBitExactly) {
  // The texel domain through the same pass files: each pass reads the merged one before laid out
  // as the lightmap; the last pass's shards widen by the dilation's reach and merge exactly.
  const std::string bake =
      "bake 'builtin:cornell?grid=8' --domain texels --resolution 40 --padding 2 --mode "
      "interreflected --bounces 1 --samples 16 -q";
  ASSERT_EQ(prt(bake + " -o one.glb").rc, 0);
  for (int i = 0; i < 3; ++i)
    ASSERT_EQ(prt(bake + " --pass 0 --shard " + std::to_string(i) + "/3 -o p0-" +
                  std::to_string(i) + ".prtpass")
                  .rc,
              0);
  ASSERT_EQ(prt("merge p0-2.prtpass p0-0.prtpass p0-1.prtpass -q -o p0.prtpass").rc, 0);
  for (int i = 0; i < 2; ++i) {
    const Result r = prt(bake + " --pass 1 --previous p0.prtpass --shard " + std::to_string(i) +
                         "/2 -o last" + std::to_string(i) + ".glb");
    ASSERT_EQ(r.rc, 0) << r.err;
  }
  ASSERT_EQ(prt("merge last1.glb last0.glb -q -o merged.glb").rc, 0);
  expectSameTransfers(dir() / "merged.glb", dir() / "one.glb");
  // A pass file of another lightmap is another bake.
  const Result other =
      prt("bake 'builtin:cornell?grid=8' --domain texels --resolution 40 --padding 3 --mode "
          "interreflected --bounces 1 --samples 16 -q --pass 1 --previous p0.prtpass -o x.glb");
  EXPECT_NE(other.rc, 0);
  EXPECT_NE(other.err.find("is a pass of another bake"), std::string::npos) << other.err;
}

TEST_F(JobArray, ShardingABounceBakeWithoutPassIsRefusedWithTheRecipe) {
  const Result r =
      prt("bake builtin:cornell --mode interreflected --bounces 1 --shard 0/2 -o out/x.glb");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("add --pass 0"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir() / "out"));
}

TEST_F(JobArray, CopiesALauncherStartedWithoutMpiWireUpAreRefused) {
  // srun -n 2 without --mpi: two copies that would each bake everything into the same file.
  const std::string env = "env -u OMPI_COMM_WORLD_SIZE -u PMIX_RANK -u PMI_RANK -u PMI_SIZE ";
  const Result r = prt("bake builtin:cornell --mode shadowed --samples 4 -q -o out/x.glb",
                       env + "SLURM_STEP_NUM_TASKS=2 ");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.err.find("each would do"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir() / "out"));
  // One task, or a job array's shards (separate by design), still bake.
  EXPECT_EQ(0, prt("bake builtin:cornell --mode shadowed --samples 4 -q -o out/one.glb",
                   env + "SLURM_STEP_NUM_TASKS=1 ")
                   .rc);
  EXPECT_EQ(0, prt("bake builtin:cornell --mode shadowed --samples 4 -q --shard 0/2 -o out/s0.glb",
                   env + "SLURM_STEP_NUM_TASKS=2 ")
                   .rc);
}

}  // namespace
}  // namespace prt::testing
