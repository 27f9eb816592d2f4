#pragma once
// The verbs that run across MPI ranks when started by mpirun/srun (bake, reference, validate;
// docs/distributed.md) share this: a session when launched by MPI (none otherwise, and none in a
// prt built without MPI), rank 0 alone speaking, failures agreed on and reported once.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/reference.hpp"
#include "prt/transport/passes.hpp"

#if PRT_HAVE_MPI
#include "prt/distributed/run.hpp"
#endif

namespace prt::cli {

/// Throws prt::Error when this process is one of several copies that cannot join into one job:
/// started by srun with several tasks but no MPI wire-up (no PMI in the environment), or by an
/// MPI launcher when this prt was built without MPI — each copy would do the whole work and
/// write the same output.
void refuseUnjoinedCopies(const std::string& verb);

/// How a bake's passes are split over MPI ranks (docs/distributed.md; unused in one process).
struct RankOptions {
  std::size_t chunkRows = 0;  ///< rows per chunk; 0: the default of each pass
  std::string checkpoint;     ///< folder keeping finished chunks ("" for none)
  std::string spillFolder;    ///< where rank 0 may map a matrix transfer too large for memory
  std::size_t spillAbove = 0;  ///< 0: half of this machine's memory
};

class MpiVerb {
 public:
  /// Starts an MPI session when launched by an MPI launcher; the other ranks go quiet. With
  /// `refuseCopies`, first refuses copies a launcher started that cannot join
  /// (refuseUnjoinedCopies); job-array tasks are separate by design.
  explicit MpiVerb(const std::string& verb, bool refuseCopies = true);
  ~MpiVerb();
  bool active() const;
  bool root() const;  ///< true without MPI
  int rank() const;
  int size() const;

  /// Runs `body`; under MPI a failure on any rank is reported once (by rank 0) for all, a
  /// failure on one rank alone names it ("rank 2: ..."). A failure every rank agreed on
  /// (collective) returns normally on the ranks other than rank 0, which leave with status 0
  /// so that the runtime does not stop rank 0 before it prints the failure: run must be the
  /// last thing a verb does on those ranks.
  void run(const std::function<void()>& body);
  /// Runs `fn` on every rank, then agrees: when any rank failed, every rank stops (collective).
  void collective(const std::function<void()>& fn);
  /// Where a bake's passes run: the ranks under MPI (distributed::RankExecutor), else this
  /// process's threads.
  std::unique_ptr<PassExecutor> bakeExecutor(const RankOptions& options) const;
  /// What the last bake on `executor` moved between the ranks, a line per pass (rank 0 under
  /// MPI; none in one process).
  std::vector<std::string> bakeExchange(const PassExecutor& executor) const;
  /// render::renderReference, across the ranks under MPI (every rank gets the result).
  render::ReferenceResult reference(const Mesh& mesh, const Occluder& occluder,
                                    const envmap::Environment& env,
                                    const render::ReferenceSettings& settings,
                                    const ProgressFn& progress);

 private:
#if PRT_HAVE_MPI
  std::unique_ptr<distributed::Session> session_;
#endif
};

}  // namespace prt::cli
