#include "mpi_verb.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "cli.hpp"
#include "prt/core/error.hpp"

namespace prt::cli {

void refuseUnjoinedCopies(const std::string& verb) {
  const auto count = [](const char* name) {
    const char* v = std::getenv(name);
    return v ? std::atol(v) : 0L;
  };
  bool mpi = false;
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    mpi = mpi || std::getenv(v) != nullptr;
#if PRT_HAVE_MPI
  if (!mpi && count("SLURM_STEP_NUM_TASKS") > 1)
    throw Error(verb + " was started as " + std::to_string(count("SLURM_STEP_NUM_TASKS")) +
                " srun tasks without MPI wire-up (no PMI in the environment): each would do the "
                "whole work; use srun --mpi=pmix (or pmi2), or --shard for job arrays");
#else
  if ((mpi && count("OMPI_COMM_WORLD_SIZE") != 1) || count("SLURM_STEP_NUM_TASKS") > 1)
    throw Error(
        "this prt was built without MPI, so the copies a launcher started cannot share "
        "the work (each would do all of it): rebuild with Open MPI installed "
        "(scripts/setup.sh), or use --shard for job arrays");
#endif
}

MpiVerb::MpiVerb(const std::string& verb, bool refuseCopies) {
  if (refuseCopies) refuseUnjoinedCopies(verb);
#if PRT_HAVE_MPI
  if (!distributed::launchedByMpi()) return;
  session_ = std::make_unique<distributed::Session>(verb, [verb](const std::string& line) {
    std::cerr << verb << ": error: " << line << std::endl;
  });
  if (!session_->root()) globals().quiet = globals().silent = true;
#else
  (void)verb;
#endif
}

MpiVerb::~MpiVerb() = default;

bool MpiVerb::active() const {
#if PRT_HAVE_MPI
  return session_ != nullptr;
#else
  return false;
#endif
}
bool MpiVerb::root() const {
  return rank() == 0;
}
int MpiVerb::rank() const {
#if PRT_HAVE_MPI
  if (session_) return session_->rank();
#endif
  return 0;
}
int MpiVerb::size() const {
#if PRT_HAVE_MPI
  if (session_) return session_->size();
#endif
  return 1;
}

void MpiVerb::run(const std::function<void()>& body) {
#if PRT_HAVE_MPI
  if (session_) {
    try {
      body();
    } catch (const distributed::AgreedFailure&) {
      throw QuietFailure();
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      if (session_->root()) throw;
      // Before the ranks first agreed, a failure is most likely every rank's (the same inputs):
      // rank 0 reports it. After, it is this rank's own.
      if (!session_->agreedOnce()) throw QuietFailure();
      throw Error("rank " + std::to_string(session_->rank()) + ": " + e.what());
    }
    return;
  }
#endif
  body();
}

void MpiVerb::collective(const std::function<void()>& fn) {
#if PRT_HAVE_MPI
  if (session_) {
    std::exception_ptr failure;
    try {
      fn();
    } catch (...) {
      failure = std::current_exception();
    }
    session_->agree(failure);
    return;
  }
#endif
  fn();
}

std::unique_ptr<PassExecutor> MpiVerb::bakeExecutor(const RankOptions& options) const {
#if PRT_HAVE_MPI
  if (session_) {
    distributed::RunOptions o;
    o.chunkRows = options.chunkRows;
    o.checkpoint = options.checkpoint;
    o.spillFolder = options.spillFolder;
    o.spillAbove = options.spillAbove;
    return std::make_unique<distributed::RankExecutor>(*session_, o);
  }
#else
  (void)options;
#endif
  return std::make_unique<ThreadExecutor>();
}

std::vector<std::string> MpiVerb::bakeExchange(const PassExecutor& executor) const {
  std::vector<std::string> lines;
#if PRT_HAVE_MPI
  const auto* ranks = dynamic_cast<const distributed::RankExecutor*>(&executor);
  if (!ranks || !root()) return lines;
  const distributed::RunReport& rep = ranks->report();
  if (rep.spilled)
    lines.push_back("rank 0 kept the transfer in a mapped scratch file beside the output, not "
                    "in memory");
  for (std::size_t j = 0; j < rep.jobs.size(); ++j) {
    const distributed::JobStats& js = rep.jobs[j];
    // What moved: each rank receives the rows it did not compute, (N − 1) × the pass's bytes
    // over all ranks for an all-gather (rank 0 alone, its share, for the last pass); rank 0
    // also receives each row's variance (8 B) for the error estimate.
    lines.push_back(fmt::format(
        "{}: {} chunks ({} on rank 0{}), {:.3f} s, exchange {:.3f} s; rows received {} B "
        "({:.2f} x the pass's {} B), variances {} B",
        rep.names[j], js.chunks, js.chunksHere,
        js.chunksResumed ? fmt::format(", {} from the checkpoint", js.chunksResumed)
                         : std::string(),
        js.seconds, js.exchangeSeconds, js.rowBytesAll,
        double(js.rowBytesAll) / double(std::max<std::uint64_t>(rep.passBytes[j], 1)),
        rep.passBytes[j], js.sideBytesAll));
  }
#else
  (void)executor;
#endif
  return lines;
}

render::ReferenceResult MpiVerb::reference(const Mesh& mesh, const Occluder& occluder,
                                           const envmap::Environment& env,
                                           const render::ReferenceSettings& settings,
                                           const ProgressFn& progress) {
#if PRT_HAVE_MPI
  if (session_)
    return distributed::renderReference(*session_, mesh, occluder, env, settings, {},
                                        session_->root() ? progress : ProgressFn{});
#endif
  return render::renderReference(mesh, occluder, env, settings, progress);
}

}  // namespace prt::cli
