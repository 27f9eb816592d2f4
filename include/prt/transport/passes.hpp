#pragma once
// A bake cut into passes: the unit every scheduler drives — the in-process bake (bake.hpp), the
// MPI ranks (prt/distributed/) and job-array shards (`prt bake --pass K --shard I/N`).
//
// A bake is a sequence of passes 0..P−1, each a table of rows over a row range (the whole mesh
// for the passes a later pass reads, the bake's range for the last one), each row a function of
// the mesh, the settings, the row's global index and the *whole* output of the passes before:
//
//   vector, unshadowed | shadowed      P = 1: the direct pass T⁰ over the range
//   vector, K bounces                  P = K+1: T⁰, T¹ … Tᴷ; pass k reads Tᵏ⁻¹ (Previous); the
//                                      transfer is T⁰ + T¹ + … + Tᴷ (resultIsSum)
//   matrix, unshadowed | shadowed      P = 1: the matrices over the range
//   matrix, K bounces, diffuse         P = K+1: the vector passes T⁰ … Tᴷ⁻¹ over the whole mesh,
//                                      then the matrices, which read their sum (Sum)
//   matrix, K bounces, glossy          P = K+1: the matrices of orders 0 … K, each reading the
//                                      one before (Previous); the transfer is the last
//
// compute(k, rows) fills any rows of pass k — a thread pool's share, an MPI chunk, a shard —
// and the same row always comes out bit for bit the same (per-row seeds from the global index,
// a fixed order of summation inside a row), so any split of any pass, run anywhere, reassembles
// into exactly the single-process bake. The bookkeeping that joins passes (accumulate, stats) is
// here too, so no scheduler re-derives it.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

/// What a pass reads besides the mesh.
enum class PassInput {
  None,      ///< nothing (the direct pass, the shadowed matrices)
  Previous,  ///< the whole output of the pass before
  Sum,       ///< the sum of all the passes before, over the whole mesh (BakePasses::accumulate)
};

struct BakePassInfo {
  std::string name;     ///< "direct", "bounce 2", "matrices", "matrices of order 1"
  TransferShape shape;  ///< its rows: layout, bands, channels, and which rows it covers
  PassInput input = PassInput::None;
  bool variance = false;  ///< its per-row variances count in the bake's error estimate
};

class BakePasses {
 public:
  /// Validates the mesh and the settings (the errors bake() throws) and prepares every pass
  /// (sample tables, kernels). `mesh` and `occluder` must outlive it.
  BakePasses(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings);
  /// The same; `checkMemory` false leaves the memory check (bakeFootprint against this
  /// machine's memory) to a driver that holds less than one process does (an MPI rank).
  BakePasses(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
             bool checkMemory);
  ~BakePasses();
  BakePasses(const BakePasses&) = delete;
  BakePasses& operator=(const BakePasses&) = delete;

  int count() const;
  const BakePassInfo& pass(int k) const;
  /// The transfer the bake returns (its rows: the bake's range).
  const TransferShape& resultShape() const;
  /// True when the transfer is the sum of every pass (vectors), false when it is the last pass.
  bool resultIsSum() const;
  /// True when some pass reads the sum of those before it over the whole mesh (so a driver
  /// keeps that sum over the whole mesh, not only the bake's range).
  bool needsFullSum() const;
  /// Channels of the running sum (1, or 3 once an RGB pass is added).
  int sumChannels() const;
  /// The progress of pass k as a share of the whole bake's `whole` (empty when `whole` is): the
  /// passes in proportion to their work, a matrix row counting as B² vector rows.
  ProgressFn passProgress(int k, const ProgressFn& whole) const;
  const BakeSettings& settings() const;
  const Mesh& mesh() const;

  /// Rows `rows` (inside pass(k).shape.rows) of pass k into out (rows.count × stride floats)
  /// and, when `variance` is given, each row's estimator variance (rows.count doubles). `input`:
  /// what pass(k).input names, over the whole mesh (ignored for PassInput::None). Parallel over
  /// the rows; advances `progress` per row (throws prt::Cancelled). Returns the rays cast.
  std::uint64_t compute(int k, RowRange rows, const Transfer& input, float* out, double* variance,
                        Progress* progress = nullptr) const;

  /// sum[r] += pass[r] for the rows both cover, in the one order every driver uses: the first
  /// pass added sets the sum (a scalar pass broadcast to every channel of an RGB sum), later
  /// ones add. `sum` has sumChannels() channels over sumRows; `first` marks pass 0.
  void accumulate(int k, RowRange passRows, const float* values, RowRange sumRows,
                  float* sum) const;

  /// The statistics bake() reports, from each pass's rays and seconds and the variance per row
  /// of the bake's range summed, in pass order, over the passes that count.
  BakeStats stats(const std::vector<std::uint64_t>& rays, const std::vector<double>& seconds,
                  const std::vector<double>& variance, double secondsTotal, int threads) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One line that tells one bake from another: the mesh (vertex and triangle count, a
/// fingerprint of its positions, normals, triangles and albedo) and every setting that changes a
/// row. Pieces of a split bake (checkpointed chunks, job-array pass files) carry it, and only
/// pieces with the same identity are joined.
std::string bakeIdentity(const Mesh& mesh, const BakeSettings& settings);

/// Runs every pass in this process over all its rows (what bake() does): two full-mesh buffers
/// of the previous and current pass, the sum over the range (or the whole mesh when a pass
/// reads it). Returns the transfer of resultShape().
Transfer runBakePasses(const BakePasses& passes, BakeStats* stats, const ProgressFn& progress);

}  // namespace prt
