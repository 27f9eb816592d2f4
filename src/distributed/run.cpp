#include "prt/distributed/run.hpp"

#include <mpi.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>

#include "prt/core/error.hpp"
#include "prt/core/hash.hpp"
#include "prt/core/file.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/units.hpp"
#include "prt/transport/bake.hpp"
#include "prt/transport/passes.hpp"

namespace prt::distributed {

namespace {

using Clock = std::chrono::steady_clock;

/// Rank 0 claims `folder` for `id` (writing folder/checkpoint.txt) or checks that it holds
/// the same run; every rank throws alike when not (collective).
void claimCheckpoint(Session& session, const std::string& folder, const std::string& id) {
  std::exception_ptr failure;
  if (session.root()) {
    try {
      std::filesystem::create_directories(folder);
      const std::string mark = folder + "/checkpoint.txt";
      if (std::filesystem::exists(mark)) {
        const std::vector<unsigned char> b = readFileBytes(mark);
        const std::string have(b.begin(), b.end());
        if (have != id + "\n")
          throw Error(folder, "holds the checkpoint of another run (" +
                                  have.substr(0, have.find('\n')) +
                                  "); use another --checkpoint folder or remove it");
      } else {
        writeFileAtomically(mark, id + "\n");
      }
    } catch (...) {
      failure = std::current_exception();
    }
  }
  session.agree(failure);
}

std::size_t physicalMemory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return static_cast<std::size_t>(-1);
  return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page);
}

/// `bytes` of zeros in a file-backed shared mapping of a scratch file in `folder`, unlinked at
/// once (nothing is left behind, whatever happens): pages the kernel writes back to the file
/// and drops under memory pressure, instead of memory. The pointer lives as long as the keeper.
std::shared_ptr<void> scratchMapping(const std::string& folder, std::size_t bytes,
                                     unsigned char** data) {
  std::string name = (folder.empty() ? std::string(".") : folder) + "/.prt-spill-XXXXXX";
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw Error(folder, "cannot create a scratch file for the transfer");
  ::unlink(name.c_str());
  if (::ftruncate(fd, static_cast<off_t>(bytes)) != 0) {
    ::close(fd);
    throw Error(folder, "cannot make a scratch file of " + bytesText(bytes) + " for the transfer");
  }
  void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) throw Error(folder, "cannot map a scratch file for the transfer");
  *data = static_cast<unsigned char*>(p);
  return std::shared_ptr<void>(p, [bytes](void* q) { ::munmap(q, bytes); });
}

int totalThreads() {
  int mine = maxThreads(), total = 0;
  MPI_Allreduce(&mine, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  return total;
}

}  // namespace

std::size_t defaultChunkRows(bool matrix, int bands) {
  if (!matrix) return 256;
  return std::max<std::size_t>(8, 1024 / static_cast<std::size_t>(bands * bands));
}

RankExecutor::RankExecutor(Session& session, const RunOptions& options)
    : session_(session), options_(options), threads_(totalThreads()) {}

BakePassOptions RankExecutor::passOptions() const {
  BakePassOptions o;
  o.checkMemory = false;  // begin() checks what this rank holds
  return o;
}

void RankExecutor::begin(const BakePasses& passes) {
  // Memory per rank: the whole-domain passes every rank holds, and of the last pass rank 0
  // the whole transfer (twice for summed vectors: the sum and the pass) unless it spills a
  // matrix transfer to a mapped file, the others their share.
  const BakeSettings& settings = passes.settings();
  const BakeFootprint fp = bakeFootprint(passes.mesh(), settings);
  const std::size_t have = physicalMemory();
  const std::size_t limit = options_.spillAbove ? options_.spillAbove : have / 2;
  const std::size_t output = passes.resultBytes();
  const bool root = session_.root();
  spill_ = root && passes.resultIsLastPass() && !options_.spillFolder.empty() &&
           fp.workingBytes + output > limit;
  const std::size_t need =
      fp.workingBytes +
      (root ? (spill_ ? 0 : output) : fp.transferBytes / static_cast<std::size_t>(session_.size()));
  if (need > have / 10 * 9)
    throw Error(std::string(toString(settings.layout)) + " transfer at " +
                std::to_string(settings.bands) + " bands needs " + bytesText(need) + " on rank " +
                std::to_string(session_.rank()) + ", whose machine has " + bytesText(have) +
                " (fewer bands, a range, or a smaller mesh)");
  report_ = RunReport();
  report_.ranks = session_.size();
  report_.threads = threads_;
  report_.spilled = spill_;
  // A folder per mode under the checkpoint folder, claimed (collectively) in agree().
  checkpoint_.clear();
  claimPending_.clear();
  if (!options_.checkpoint.empty()) {
    checkpoint_ = options_.checkpoint + "/" + toString(settings.mode);
    claimPending_ = "prt bake; " + bakeIdentity(passes.mesh(), settings) + "; rows per chunk";
    for (int k = 0; k < passes.count(); ++k)
      claimPending_ += " " + std::to_string(chunkRows(passes.pass(k).shape));
    checkpointIdentity_ = claimPending_;
  }
}

void RankExecutor::agree(std::exception_ptr failure) {
  session_.agree(failure);
  if (!claimPending_.empty()) {
    claimCheckpoint(session_, checkpoint_, claimPending_);
    claimPending_.clear();
  }
}

PassExecutor::Rows RankExecutor::run(const BakePasses& passes, int k, const PassSource& input,
                                     const ProgressFn& progress) {
  const BakePassInfo& p = passes.pass(k);
  const bool last = k == passes.count() - 1, root = session_.root();
  const RowRange pr = p.shape.rows;
  // The rows: every rank holds a pass the next one reads; the last, rank 0 only.
  const bool spilled = last && spill_;
  Rows out;
  Transfer values = (!last || root) && !spilled ? Transfer::zeros(p.shape) : Transfer();
  unsigned char* bytes = (!last || root) && !spilled
                             ? reinterpret_cast<unsigned char*>(values.mutableValues())
                             : nullptr;
  std::shared_ptr<void> mapping;
  if (spilled) mapping = scratchMapping(options_.spillFolder, p.shape.denseBytes(), &bytes);
  if (root && p.variance) out.variance.assign(pr.count, 0.0);
  RowJob job;
  job.name = "pass " + std::to_string(k) + " '" + p.name + "'";
  job.rows = pr.count;
  job.firstRow = pr.first;
  job.rowNoun = toString(p.shape.domain);
  job.chunkRows = chunkRows(p.shape);
  job.rowBytes = p.shape.stride() * sizeof(float);
  job.sideBytes = p.variance ? sizeof(double) : 0;
  job.allGather = !last;
  job.compute = [&](std::size_t lo, std::size_t hi, unsigned char* r, unsigned char* side) {
    return passes.compute(k, RowRange{pr.first + lo, hi - lo}, input, reinterpret_cast<float*>(r),
                          reinterpret_cast<double*>(side));
  };
  if (!checkpoint_.empty()) {
    job.checkpoint = checkpoint_ + "/pass-" + std::to_string(k);
    Fnv1a id;
    const std::string what = checkpointIdentity_ + "; " + job.name;
    id.add(what.data(), what.size());
    job.identity = id.value();
  }
  const JobStats js =
      runJob(session_, job, bytes,
             out.variance.empty() ? nullptr : reinterpret_cast<unsigned char*>(out.variance.data()),
             root ? progress : ProgressFn());
  out.rays = js.rays;
  out.seconds = js.seconds;
  report_.names.push_back(job.name);
  report_.jobs.push_back(js);
  report_.passBytes.push_back(p.shape.denseBytes());
  report_.bytesReceived = session_.bytesReceived();
  if (spilled)
    values = Transfer::dense(p.shape, FloatArray::view(mapping, reinterpret_cast<float*>(bytes),
                                                       pr.count * p.shape.stride()));
  out.values = std::move(values);
  return out;
}

int RankExecutor::threads() const {
  return threads_;
}

std::size_t RankExecutor::chunkRows(const TransferShape& s) const {
  return options_.chunkRows ? options_.chunkRows : defaultChunkRows(s.isMatrix(), s.bands);
}

Transfer bake(Session& session, const Mesh& mesh, const Occluder& occluder,
              const BakeSettings& settings, const RunOptions& options, BakeStats* stats,
              RunReport* report, const ProgressFn& progress) {
  RankExecutor ranks(session, options);
  Transfer t = prt::bake(mesh, occluder, settings, ranks, stats, progress);
  if (report) *report = ranks.report();
  return t;
}

render::ReferenceResult renderReference(Session& session, const Mesh& mesh,
                                        const Occluder& occluder, const envmap::Environment& env,
                                        const render::ReferenceSettings& settings,
                                        const RunOptions& options, const ProgressFn& progress) {
  using render::BandLimitedEstimate;
  const auto t0 = Clock::now();
  std::unique_ptr<render::ReferenceRows> job;
  std::exception_ptr failure;
  try {
    job = std::make_unique<render::ReferenceRows>(mesh, occluder, env, settings);
  } catch (...) {
    failure = std::current_exception();
  }
  session.agree(failure);
  render::ReferenceResult out;
  out.vertices = job->vertices();
  const std::size_t count = out.vertices.size(), lanes = job->lanes();
  // One row: radiance, standard error, the band-limited estimates, the rays.
  const std::size_t rowBytes =
      2 * sizeof(Rgb) + lanes * sizeof(BandLimitedEstimate) + sizeof(std::uint64_t);
  std::vector<unsigned char> table(count * rowBytes);
  RowJob rj;
  rj.name = "the reference";
  rj.rows = count;
  rj.rowNoun = "vertex entries";
  rj.chunkRows = options.chunkRows ? options.chunkRows : 64;
  rj.rowBytes = rowBytes;
  rj.allGather = true;
  rj.compute = [&](std::size_t lo, std::size_t hi, unsigned char* rows, unsigned char*) {
    const std::size_t m = hi - lo;
    std::vector<Rgb> radiance(m), se(m);
    std::vector<BandLimitedEstimate> band(m * lanes);
    std::vector<std::uint64_t> rays(m);
    job->compute(lo, m, radiance.data(), se.data(), band.data(), rays.data());
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < m; ++i) {
      unsigned char* r = rows + i * rowBytes;
      std::memcpy(r, &radiance[i], sizeof(Rgb));
      std::memcpy(r + sizeof(Rgb), &se[i], sizeof(Rgb));
      if (lanes)
        std::memcpy(r + 2 * sizeof(Rgb), &band[i * lanes], lanes * sizeof(BandLimitedEstimate));
      std::memcpy(r + rowBytes - sizeof(std::uint64_t), &rays[i], sizeof(std::uint64_t));
      total += rays[i];
    }
    return total;
  };
  // (No checkpoint: a reference run is one pass of minutes, not a bake of hours.)
  runJob(session, rj, table.data(), nullptr, progress);
  out.radiance.resize(count);
  out.stdError.resize(count);
  out.bandLimited.resize(count * lanes);
  for (std::size_t i = 0; i < count; ++i) {
    const unsigned char* r = table.data() + i * rowBytes;
    std::memcpy(&out.radiance[i], r, sizeof(Rgb));
    std::memcpy(&out.stdError[i], r + sizeof(Rgb), sizeof(Rgb));
    if (lanes)
      std::memcpy(&out.bandLimited[i * lanes], r + 2 * sizeof(Rgb),
                  lanes * sizeof(BandLimitedEstimate));
    std::uint64_t rays;
    std::memcpy(&rays, r + rowBytes - sizeof(std::uint64_t), sizeof rays);
    out.rays += rays;
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

}  // namespace prt::distributed
