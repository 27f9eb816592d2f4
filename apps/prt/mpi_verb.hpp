#pragma once
// The verbs that run across MPI ranks when started by mpirun/srun (bake, reference, validate;
// docs/distributed.md) share this: a session when launched by MPI (none otherwise, and none in a
// prt built without MPI), rank 0 alone speaking, failures agreed on and reported once.

#include <functional>
#include <memory>
#include <string>

#include "prt/core/progress.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/reference.hpp"

#if PRT_HAVE_MPI
#include "prt/distributed/run.hpp"
#endif

namespace prt::cli {

/// Throws prt::Error when this process is one of several copies that cannot join into one job:
/// started by srun with several tasks but no MPI wire-up (no PMI in the environment), or by an
/// MPI launcher when this prt was built without MPI — each copy would do the whole work and
/// write the same output.
void refuseUnjoinedCopies(const std::string& verb);

class MpiVerb {
 public:
  /// Starts an MPI session when launched by an MPI launcher; the other ranks go quiet.
  explicit MpiVerb(const std::string& verb);
  ~MpiVerb();
  bool active() const;
  bool root() const;  ///< true without MPI
  int rank() const;
  int size() const;

  /// Runs `body`; under MPI a failure on any rank is reported once (by rank 0) for all, a
  /// failure on one rank alone names it ("rank 2: ...").
  void run(const std::function<void()>& body);
  /// Runs `fn` on every rank, then agrees: when any rank failed, every rank stops (collective).
  void collective(const std::function<void()>& fn);
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
