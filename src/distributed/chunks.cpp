#include "prt/distributed/chunks.hpp"

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include "mpi_util.hpp"
#include "prt/core/error.hpp"
#include "prt/core/file.hpp"
#include "prt/core/hash.hpp"

namespace prt::distributed {

namespace {

using Clock = std::chrono::steady_clock;
using detail::politeWait;

constexpr int kTagRequest = 1901, kTagReply = 1902, kTagRows = 1903, kTagSide = 1904;
constexpr std::int32_t kResumed = -2;  // owner of a chunk loaded from the checkpoint

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// The fault-test hook: "R:C" — rank R exits when it is handed its C-th chunk of the run
/// (counted from 0 on that rank: which chunks a rank gets varies, how many it has had does not).
/// So that R surely gets that many however the machine schedules the ranks, rank 0 computes
/// nothing itself until it has handed R its fatal chunk.
struct ExitHook {
  int rank = -1;
  long long chunk = -1;
  long long handed = 0;                      ///< on rank R: chunks it was handed
  std::atomic<long long> handedToDoomed{0};  ///< on rank 0: chunks it handed to rank R
  ExitHook() {
    if (const char* v = std::getenv("PRT_TEST_EXIT_AT_CHUNK"))
      if (std::sscanf(v, "%d:%lld", &rank, &chunk) != 2) rank = -1;
  }
};

// A checkpointed chunk: "PRTCHNK2", then lo, hi, rowBytes, sideBytes, rays, the job's identity
// (RowJob::identity: the bake's settings, mesh and pass) and the FNV-1a checksum of the payload
// (uint64 each, little-endian as the machines are), then the rows and the side bytes. A chunk of
// another run (another seed, copied in) or one whose bytes changed is refused by name, never
// used ("PRTCHNK1" chunks, without either, too).
constexpr char kMagic[8] = {'P', 'R', 'T', 'C', 'H', 'N', 'K', '2'};
constexpr std::size_t kFields = 7;
constexpr std::size_t kHeader = 8 + kFields * 8;

std::string chunkPath(const std::string& folder, std::size_t c) {
  char name[32];
  std::snprintf(name, sizeof name, "chunk-%06zu.bin", c);
  return folder + "/" + name;
}

std::uint64_t payloadChecksum(const unsigned char* payload, std::size_t bytes) {
  Fnv1a h;
  h.add(payload, bytes);
  return h.value();
}

void writeChunk(const std::string& path, std::size_t lo, std::size_t hi, const RowJob& job,
                const unsigned char* rows, const unsigned char* side, std::uint64_t rays) {
  std::string bytes(kHeader, '\0');
  std::memcpy(bytes.data(), kMagic, 8);
  bytes.append(reinterpret_cast<const char*>(rows), (hi - lo) * job.rowBytes);
  if (job.sideBytes) bytes.append(reinterpret_cast<const char*>(side), (hi - lo) * job.sideBytes);
  const std::uint64_t h[kFields] = {
      lo, hi, job.rowBytes, job.sideBytes, rays, job.identity,
      payloadChecksum(reinterpret_cast<const unsigned char*>(bytes.data()) + kHeader,
                      bytes.size() - kHeader)};
  std::memcpy(bytes.data() + 8, h, sizeof h);
  writeFileAtomically(path, bytes);
}

/// Loads a checkpointed chunk into its rows (and side, when given); returns its rays.
std::uint64_t readChunk(const std::string& path, std::size_t lo, std::size_t hi, const RowJob& job,
                        unsigned char* rows, unsigned char* side) {
  const std::vector<unsigned char> b = readFileBytes(path);
  std::uint64_t h[kFields] = {};
  const std::size_t need = kHeader + (hi - lo) * (job.rowBytes + job.sideBytes);
  if (b.size() >= kHeader) std::memcpy(h, b.data() + 8, sizeof h);
  if (b.size() != need || std::memcmp(b.data(), kMagic, 8) != 0 || h[0] != lo || h[1] != hi ||
      h[2] != job.rowBytes || h[3] != job.sideBytes)
    throw Error(path, "is not a chunk of this job (rows " + std::to_string(lo) + ".." +
                          std::to_string(hi) + "): remove the checkpoint folder or use another");
  if (h[5] != job.identity)
    throw Error(path, "is a chunk of another run (its settings, seed or mesh differ from this "
                      "bake's): remove the checkpoint folder or use another");
  if (h[6] != payloadChecksum(b.data() + kHeader, b.size() - kHeader))
    throw Error(path, "is damaged (its checksum does not match its rows): remove it and run "
                      "again to bake its rows anew");
  if (rows) std::memcpy(rows, b.data() + kHeader, (hi - lo) * job.rowBytes);
  if (side && job.sideBytes)
    std::memcpy(side, b.data() + kHeader + (hi - lo) * job.rowBytes, (hi - lo) * job.sideBytes);
  return h[4];
}

/// An MPI datatype of the byte blocks [lo·unit, hi·unit) of the given chunks, at their place in
/// a full table (packed = false) or one after another (packed = true).
MPI_Datatype blocksType(const std::vector<std::size_t>& chunks, const RowJob& job, std::size_t unit,
                        bool packed) {
  std::vector<int> lengths;
  std::vector<MPI_Aint> displs;
  MPI_Aint at = 0;
  for (std::size_t c : chunks) {
    const std::size_t lo = c * job.chunkRows, hi = std::min(job.rows, lo + job.chunkRows);
    lengths.push_back(static_cast<int>((hi - lo) * unit));
    displs.push_back(packed ? at : static_cast<MPI_Aint>(lo * unit));
    at += static_cast<MPI_Aint>((hi - lo) * unit);
  }
  MPI_Datatype t;
  MPI_Type_create_hindexed(static_cast<int>(chunks.size()), lengths.data(), displs.data(), MPI_BYTE,
                           &t);
  MPI_Type_commit(&t);
  return t;
}

}  // namespace

JobStats runJob(Session& session, const RowJob& job, unsigned char* rowsOut, unsigned char* sideOut,
                const ProgressFn& progress) {
  static ExitHook hook;
  const auto start = Clock::now();
  const int rank = session.rank(), size = session.size();
  const bool root = session.root();
  PRT_CHECK(job.chunkRows > 0, "chunks hold rows");
  const std::size_t nchunks = (job.rows + job.chunkRows - 1) / job.chunkRows;
  const std::uint64_t base = session.reserveChunks(nchunks);
  JobStats st;
  st.chunks = nchunks;
  const auto rangeOf = [&](std::size_t c) {
    const std::size_t lo = c * job.chunkRows;
    return std::pair<std::size_t, std::size_t>(lo, std::min(job.rows, lo + job.chunkRows));
  };
  const auto describe = [&](std::size_t c) {
    const auto [lo, hi] = rangeOf(c);
    return "chunk " + std::to_string(base + c) + " of " + job.name + " (" + job.rowNoun + " " +
           std::to_string(job.firstRow + lo) + ".." + std::to_string(job.firstRow + hi - 1) + ")";
  };

  // The checkpoint: rank 0 lists the chunks already there and tells the others.
  std::vector<char> present(nchunks, 0);
  if (!job.checkpoint.empty()) {
    if (root) {
      std::filesystem::create_directories(job.checkpoint);
      for (std::size_t c = 0; c < nchunks; ++c)
        present[c] = std::filesystem::is_regular_file(chunkPath(job.checkpoint, c)) ? 1 : 0;
    }
    MPI_Bcast(present.data(), static_cast<int>(nchunks), MPI_CHAR, 0, MPI_COMM_WORLD);
  }

  // Chunks: rank 0 hands them out in order; each rank computes into the full table (all-gather,
  // or rank 0) or into its own packed buffer (the others, for a gather).
  std::vector<std::int32_t> owner(nchunks, -1);
  std::mutex mutex;
  std::size_t next = 0;
  std::atomic<std::size_t> finished{0};
  bool failed = false;  // rank 0's own work failed: hand out nothing more, then rethrow
  const auto acquire = [&](int who) -> long long {
    std::lock_guard<std::mutex> lock(mutex);
    if (failed) return -1;
    while (next < nchunks && present[next]) owner[next++] = kResumed;
    if (next == nchunks) return -1;
    owner[next] = who;
    return static_cast<long long>(next++);
  };

  std::thread coordinator;
  if (root && size > 1) {
    coordinator = std::thread([&] {
      int working = size - 1;
      while (working > 0) {
        long long msg[2];
        MPI_Request req;
        MPI_Status status;
        MPI_Irecv(msg, 2, MPI_LONG_LONG, MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &req);
        politeWait(&req, &status, [&] { session.watch(); });
        const int r = status.MPI_SOURCE;
        if (msg[1] >= 0) finished.fetch_add(1);  // it finished a chunk before asking
        const long long c = acquire(r);
        if (c >= 0 && r == hook.rank) hook.handedToDoomed.fetch_add(1);
        session.setActivity(r, c >= 0 ? "computing " + describe(static_cast<std::size_t>(c))
                                      : "waiting for the end of " + job.name);
        MPI_Send(&c, 1, MPI_LONG_LONG, r, kTagReply, MPI_COMM_WORLD);
        if (c < 0) --working;
      }
    });
  }

  const bool direct = job.allGather || root;
  std::vector<unsigned char> packed, sidePacked;
  std::vector<std::size_t> mine;
  std::uint64_t rays = 0;
  long long last = -1;
  std::exception_ptr failure;
  try {
    for (;;) {
      long long c;
      if (root) {
        if (hook.rank > 0 && hook.rank < size)  // the fault test: let rank R reach its chunk
          while (hook.handedToDoomed.load() <= hook.chunk)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        c = acquire(0);
        if (c >= 0) session.setActivity(0, "computing " + describe(static_cast<std::size_t>(c)));
      } else {
        long long msg[2] = {static_cast<long long>(base), last};
        MPI_Send(msg, 2, MPI_LONG_LONG, 0, kTagRequest, MPI_COMM_WORLD);
        MPI_Request req;
        MPI_Irecv(&c, 1, MPI_LONG_LONG, 0, kTagReply, MPI_COMM_WORLD, &req);
        politeWait(&req, nullptr);
      }
      if (c < 0) break;
      const std::size_t chunk = static_cast<std::size_t>(c);
      if (hook.rank == rank && hook.handed++ == hook.chunk) std::_Exit(3);
      const auto [lo, hi] = rangeOf(chunk);
      unsigned char* rowsAt;
      unsigned char* sideAt;
      if (direct) {
        rowsAt = rowsOut + lo * job.rowBytes;
        sideAt = root && job.sideBytes ? sideOut + lo * job.sideBytes : nullptr;
      } else {
        packed.resize(packed.size() + (hi - lo) * job.rowBytes);
        rowsAt = packed.data() + packed.size() - (hi - lo) * job.rowBytes;
        sideAt = nullptr;
      }
      if (!sideAt && job.sideBytes) {
        sidePacked.resize(sidePacked.size() + (hi - lo) * job.sideBytes);
        sideAt = sidePacked.data() + sidePacked.size() - (hi - lo) * job.sideBytes;
      }
      const std::uint64_t r = job.compute(lo, hi, rowsAt, sideAt);
      rays += r;
      if (!job.checkpoint.empty())
        writeChunk(chunkPath(job.checkpoint, chunk), lo, hi, job, rowsAt, sideAt, r);
      mine.push_back(chunk);
      last = c;
      if (root) {
        finished.fetch_add(1);
        if (progress &&
            !progress(double(finished.load()) / double(std::max<std::size_t>(nchunks, 1))))
          throw Cancelled();
      }
    }
  } catch (...) {
    // Rank 0's coordinator still answers the others (with "no more chunks") before this rank
    // reports the failure; a failure elsewhere ends that rank, and the runtime the job.
    failure = std::current_exception();
    std::lock_guard<std::mutex> lock(mutex);
    failed = true;
  }
  if (coordinator.joinable()) coordinator.join();
  if (failure) std::rethrow_exception(failure);
  if (root) session.setActivity(0, "exchanging the rows of " + job.name);
  st.chunksHere = mine.size();

  // Who computed what, then the rows: all-gather (one broadcast per rank of its chunks, straight
  // into place) or gather to rank 0.
  const auto t0 = Clock::now();
  session.barrier();
  MPI_Bcast(owner.data(), static_cast<int>(nchunks), MPI_INT32_T, 0, MPI_COMM_WORLD);
  std::vector<std::vector<std::size_t>> byRank(static_cast<std::size_t>(size));
  std::vector<std::size_t> resumed;
  for (std::size_t c = 0; c < nchunks; ++c) {
    if (owner[c] == kResumed)
      resumed.push_back(c);
    else
      byRank[static_cast<std::size_t>(owner[c])].push_back(c);
  }
  st.chunksResumed = resumed.size();
  std::uint64_t resumedRays = 0;
  for (std::size_t c : resumed) {
    const auto [lo, hi] = rangeOf(c);
    if (job.allGather || root) {
      const std::uint64_t r =
          readChunk(chunkPath(job.checkpoint, c), lo, hi, job, rowsOut + lo * job.rowBytes,
                    root && job.sideBytes ? sideOut + lo * job.sideBytes : nullptr);
      if (root) resumedRays += r;
    }
  }
  const auto bytesOf = [&](const std::vector<std::size_t>& chunks, std::size_t unit) {
    std::uint64_t b = 0;
    for (std::size_t c : chunks) b += (rangeOf(c).second - rangeOf(c).first) * unit;
    return b;
  };
  std::uint64_t received = 0, sideReceived = 0;
  if (size > 1) {
    if (job.allGather) {
      for (int r = 0; r < size; ++r) {
        const auto& chunks = byRank[static_cast<std::size_t>(r)];
        if (chunks.empty()) continue;
        MPI_Datatype t = blocksType(chunks, job, job.rowBytes, false);
        MPI_Request req;
        MPI_Ibcast(rowsOut, 1, t, r, MPI_COMM_WORLD, &req);
        politeWait(&req, nullptr);
        MPI_Type_free(&t);
        if (r != rank) received += bytesOf(chunks, job.rowBytes);
      }
    }
    // Gathers to rank 0: the rows of a gather job, the side bytes of every job.
    const auto gather = [&](std::size_t unit, unsigned char* full, const unsigned char* mineData,
                            int tag) {
      if (unit == 0) return;
      if (root) {
        std::vector<MPI_Request> reqs;
        std::vector<MPI_Datatype> types;
        for (int r = 1; r < size; ++r) {
          const auto& chunks = byRank[static_cast<std::size_t>(r)];
          if (chunks.empty()) continue;
          types.push_back(blocksType(chunks, job, unit, false));
          reqs.emplace_back();
          MPI_Irecv(full, 1, types.back(), r, tag, MPI_COMM_WORLD, &reqs.back());
          (tag == kTagSide ? sideReceived : received) += bytesOf(chunks, unit);
        }
        detail::politeWaitAll(static_cast<int>(reqs.size()), reqs.data());
        for (MPI_Datatype& t : types) MPI_Type_free(&t);
      } else if (!mine.empty()) {
        MPI_Datatype t = blocksType(
            mine, job, unit, !(job.allGather && unit == job.rowBytes && mineData == rowsOut));
        MPI_Request req;
        MPI_Isend(mineData, 1, t, 0, tag, MPI_COMM_WORLD, &req);
        politeWait(&req, nullptr);
        MPI_Type_free(&t);
      }
    };
    if (!job.allGather) gather(job.rowBytes, rowsOut, packed.data(), kTagRows);
    gather(job.sideBytes, sideOut, sidePacked.data(), kTagSide);
  }
  st.exchangeSeconds = since(t0);
  unsigned long long mineRays = rays, total = 0;
  MPI_Reduce(&mineRays, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  st.rays = root ? total + resumedRays : rays;
  st.bytesReceived = received + sideReceived;
  unsigned long long mineBytes = received, allBytes = 0;
  MPI_Reduce(&mineBytes, &allBytes, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  st.rowBytesAll = allBytes;
  st.sideBytesAll = sideReceived;
  session.addBytesReceived(received + sideReceived);
  st.seconds = since(start);
  if (root && progress) progress(1.0);
  return st;
}

}  // namespace prt::distributed
