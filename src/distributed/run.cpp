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

Transfer bake(Session& session, const Mesh& mesh, const Occluder& occluder,
              const BakeSettings& settings, const RunOptions& options, BakeStats* stats,
              RunReport* report, const ProgressFn& progressFn) {
  const auto start = Clock::now();
  std::unique_ptr<BakePasses> plan;
  std::exception_ptr failure;
  const bool root = session.root();
  bool spill = false;
  try {
    plan = std::make_unique<BakePasses>(mesh, occluder, settings, false);
    // Memory per rank: the whole-mesh passes every rank holds, and of the last pass rank 0 the
    // whole transfer (twice for summed vectors: the sum and the pass) unless it spills a
    // matrix transfer to a mapped file, the others their share.
    const BakeFootprint fp = bakeFootprint(mesh, settings);
    const std::size_t have = physicalMemory();
    const std::size_t limit = options.spillAbove ? options.spillAbove : have / 2;
    const std::size_t output = plan->resultIsSum() ? 2 * fp.transferBytes : fp.transferBytes;
    spill = root && !plan->resultIsSum() && !options.spillFolder.empty() &&
            fp.workingBytes + output > limit;
    const std::size_t need =
        fp.workingBytes +
        (root ? (spill ? 0 : output) : fp.transferBytes / static_cast<std::size_t>(session.size()));
    if (need > have / 10 * 9)
      throw Error(std::string(toString(settings.layout)) + " transfer at " +
                  std::to_string(settings.bands) + " bands needs " + bytesText(need) + " on rank " +
                  std::to_string(session.rank()) + ", whose machine has " + bytesText(have) +
                  " (fewer bands, a vertex range, or a smaller mesh)");
  } catch (...) {
    failure = std::current_exception();
  }
  session.agree(failure);
  const BakePasses& passes = *plan;
  const int count = passes.count();
  const std::size_t n = mesh.vertexCount();
  const TransferShape& result = passes.resultShape();
  const RowRange rows = result.rows;
  const auto chunkOf = [&](const TransferShape& s) {
    return options.chunkRows ? options.chunkRows : defaultChunkRows(s.isMatrix(), s.bands);
  };
  if (!options.checkpoint.empty()) {
    std::string id = "prt bake; " + bakeIdentity(mesh, settings) + "; rows per chunk";
    for (int k = 0; k < count; ++k) id += " " + std::to_string(chunkOf(passes.pass(k).shape));
    claimCheckpoint(session, options.checkpoint, id);
  }

  // The running sum: on rank 0 over the bake's rows; on every rank over the whole mesh when a
  // pass reads it.
  const bool summing = passes.resultIsSum() || passes.needsFullSum();
  const bool keepSum = summing && (root || passes.needsFullSum());
  TransferShape sumShape = result;
  sumShape.layout = TransferLayout::Vector;
  sumShape.channels = passes.sumChannels();
  sumShape.rows = passes.needsFullSum() ? RowRange{0, n} : rows;
  Transfer sum = keepSum ? Transfer::zeros(sumShape) : Transfer();
  float* const sumData = keepSum ? sum.mutableValues() : nullptr;

  std::vector<double> variance(root ? rows.count : 0, 0.0);
  std::vector<std::uint64_t> rays;
  std::vector<double> seconds;
  Transfer prev;
  RunReport rep;
  rep.ranks = session.size();
  rep.threads = totalThreads();
  for (int k = 0; k < count; ++k) {
    const BakePassInfo& p = passes.pass(k);
    const bool last = k == count - 1;
    const RowRange pr = p.shape.rows;
    // The rows: every rank holds a pass the next one reads; the last, rank 0 only.
    const bool spilled = last && spill;
    Transfer out = (!last || root) && !spilled ? Transfer::zeros(p.shape) : Transfer();
    unsigned char* outBytes = (!last || root) && !spilled
                                  ? reinterpret_cast<unsigned char*>(out.mutableValues())
                                  : nullptr;
    std::shared_ptr<void> mapping;
    if (spilled) mapping = scratchMapping(options.spillFolder, p.shape.denseBytes(), &outBytes);
    std::vector<double> var(root && p.variance ? pr.count : 0);
    const Transfer& input = p.input == PassInput::Sum ? sum : prev;
    RowJob job;
    job.name = "pass " + std::to_string(k) + " '" + p.name + "'";
    job.rows = pr.count;
    job.firstRow = pr.first;
    job.rowNoun = "vertices";
    job.chunkRows = chunkOf(p.shape);
    job.rowBytes = p.shape.stride() * sizeof(float);
    job.sideBytes = p.variance ? sizeof(double) : 0;
    job.allGather = !last;
    job.compute = [&](std::size_t lo, std::size_t hi, unsigned char* r, unsigned char* side) {
      return passes.compute(k, RowRange{pr.first + lo, hi - lo}, input, reinterpret_cast<float*>(r),
                            reinterpret_cast<double*>(side));
    };
    if (!options.checkpoint.empty())
      job.checkpoint = options.checkpoint + "/pass-" + std::to_string(k);
    const ProgressFn sub = root ? passes.passProgress(k, progressFn) : ProgressFn();
    const JobStats js =
        runJob(session, job, outBytes,
               var.empty() ? nullptr : reinterpret_cast<unsigned char*>(var.data()), sub);
    rays.push_back(js.rays);
    seconds.push_back(js.seconds);
    rep.names.push_back(job.name);
    rep.jobs.push_back(js);
    rep.passBytes.push_back(p.shape.denseBytes());
    if (root && p.variance)
      for (std::size_t v = std::max(rows.first, pr.first); v < std::min(rows.end(), pr.end()); ++v)
        variance[v - rows.first] += var[v - pr.first];
    if (keepSum && !(last && !passes.resultIsSum()) && (root || !last))
      passes.accumulate(k, pr, out.values().data(), sumShape.rows, sumData);
    if (spilled)
      out = Transfer::dense(p.shape, FloatArray::view(mapping, reinterpret_cast<float*>(outBytes),
                                                      p.shape.rows.count * p.shape.stride()));
    prev = std::move(out);
  }
  rep.spilled = spill;
  rep.bytesReceived = session.bytesReceived();
  if (report) *report = rep;
  if (!root) return Transfer();
  if (stats)
    *stats = passes.stats(rays, seconds, variance,
                          std::chrono::duration<double>(Clock::now() - start).count(), rep.threads);
  return passes.resultIsSum() ? sum : prev;
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
