#pragma once
// A bake cut into passes, and the one loop that runs them: the unit every executor drives — this
// process's threads (bake.hpp), MPI ranks (prt/distributed/) and job-array shards (`prt bake
// --pass K --shard I/N`) — for every domain (vertices, lightmap texels).
//
// A bake is a sequence of passes 0..P−1, each a table of rows over a row range of its domain
// (the whole domain for the passes a later pass reads, the bake's range for the last one), each
// row a function of the mesh, the settings, the row's global index and the *whole* output of
// the passes before:
//
//   vector, unshadowed | shadowed      P = 1: the direct pass T⁰ over the range
//   vector, K bounces                  P = K+1: T⁰, T¹ … Tᴷ; pass k reads Tᵏ⁻¹ (Previous); the
//                                      transfer is T⁰ + T¹ + … + Tᴷ (resultIsSum)
//   matrix, unshadowed | shadowed      P = 1: the matrices over the range
//   matrix, K bounces, diffuse         P = K+1: the vector passes T⁰ … Tᴷ⁻¹ over the whole
//                                      domain, then the matrices, which read their sum (Sum)
//   matrix, K bounces, glossy          P = K+1: the matrices of orders 0 … K, each reading the
//                                      one before (Previous); the transfer is the last
//   Haar, unshadowed | shadowed        P = 1: the pruned wavelet rows over the range
//   Haar, K bounces                    P = K+2: the bounce in SH — its direct pass T⁰ and the
//                                      bounces T¹ … Tᴷ over the whole domain, each reading the
//                                      one before, T⁰ not summed — then the Haar rows, which
//                                      read the sum T¹ + … + Tᴷ and hold it after their pairs
//
// The domain is one axis of the list, never a branch in its drivers. Per vertex a row is
// integrated at the vertex and a bounce reads the pass before interpolated across the hit
// triangle. Per texel (bake_texels.hpp) a row is integrated at the texel's sample point (texels
// no triangle covers hold zeros), a pass is laid out as the lightmap and dilated past its charts
// before the next reads it bilinearly through the hit's lightmap UV (prepare), and the result is
// dilated into the gutter the same way (finish), so the last pass covers the range widened by
// the dilation's reach.
//
// compute(k, rows) fills any rows of pass k — a thread pool's share, an MPI chunk, a shard —
// and the same row always comes out bit for bit the same (per-row seeds from the global index,
// a fixed order of summation inside a row), so any split of any pass, run anywhere, reassembles
// into exactly the single-process bake. The bookkeeping that joins passes (the running sum, the
// error estimate, the statistics) is runPass's alone, so no executor re-derives it.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "prt/core/progress.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

/// What a pass reads besides the mesh.
enum class PassInput {
  None,      ///< nothing (the direct pass, the shadowed matrices)
  Previous,  ///< the whole output of the pass before
  Sum,       ///< the sum of all the passes before, over the whole domain (BakePasses::accumulate)
};

struct BakePassInfo {
  std::string name;     ///< "direct", "bounce 2", "matrices", "matrices of order 1"
  TransferShape shape;  ///< its rows: domain, layout, bands, channels, and which rows it covers
  PassInput input = PassInput::None;
  bool variance = false;  ///< its per-row variances count in the bake's error estimate
  /// It is added to the running sum (when the bake keeps one): every pass but an inter-reflected
  /// Haar bake's SH direct pass, which only its first bounce reads.
  bool summed = true;
};

/// What pass k reads, prepared once from the whole-domain transfer its PassInput names: that
/// transfer itself per vertex; per texel, that transfer laid out as the lightmap and dilated
/// (BakePasses::prepare). Empty for a pass that reads nothing.
class PassSource {
 public:
  PassSource() = default;

 private:
  friend class BakePasses;
  const Transfer* transfer_ = nullptr;
  std::shared_ptr<const std::vector<float>> image_;
  std::size_t stride_ = 0;
};

/// Options of a pass list beside its settings.
struct BakePassOptions {
  /// False leaves the memory check (bakeFootprint against this machine's memory) to a driver
  /// that holds less than one process does (an MPI rank).
  bool checkMemory = true;
  /// Per texel: the UV set the lightmap lies over, one per vertex (empty: mesh.lightmapUvs).
  std::span<const Vec2f> lightmapUvs;
};

class BakePasses {
 public:
  /// Validates the mesh and the settings (the errors bake() throws) and prepares every pass
  /// (sample tables, kernels; per texel the sample points and which lie inside geometry).
  /// `mesh`, `occluder` and options.lightmapUvs must outlive it.
  BakePasses(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
             const BakePassOptions& options = {});
  ~BakePasses();
  BakePasses(const BakePasses&) = delete;
  BakePasses& operator=(const BakePasses&) = delete;

  int count() const;
  const BakePassInfo& pass(int k) const;
  /// The transfer the bake returns (its rows: the bake's range).
  const TransferShape& resultShape() const;
  /// True when the transfer is the sum of every pass (vectors), false when it is the last pass.
  bool resultIsSum() const;
  /// Channels of the running sum (1, or 3 once an RGB pass is added).
  int sumChannels() const;
  /// Bytes the process that holds the result keeps for it: the transfer, twice when the result
  /// is the sum of the passes (the sum beside the last pass).
  std::size_t resultBytes() const;
  /// True when the result is the last pass's rows themselves, so that a driver may keep them in
  /// a file-backed mapping (an MPI rank 0 short of memory) and hand them on as they are.
  bool resultIsLastPass() const;
  /// True when the bake keeps a running sum of its passes: its result, or what its last pass
  /// reads (PassInput::Sum).
  bool sums() const;
  /// The progress of pass k as a share of the whole bake's `whole` (empty when `whole` is): the
  /// passes in proportion to their work, a matrix row counting as B² vector rows.
  ProgressFn passProgress(int k, const ProgressFn& whole) const;
  const BakeSettings& settings() const;
  const Mesh& mesh() const;
  /// Rows of the whole domain (vertices, or the lightmap's texels).
  std::size_t domainRows() const;
  /// Per texel: where each covered texel is sampled, and the covered texels whose sample point
  /// lies inside geometry (refilled from their neighbours). Empty per vertex.
  const TexelSamples& texelSamples() const;
  const std::vector<std::uint32_t>& texelsInsideGeometry() const;

  /// What pass k reads, from `input`: the whole domain's rows of what pass(k).input names (the
  /// pass before, or the running sum). `input` must outlive the source.
  PassSource prepare(int k, const Transfer& input) const;

  /// Rows `rows` (inside pass(k).shape.rows) of pass k into out (rows.count × stride floats)
  /// and, when `variance` is given, each row's estimator variance (rows.count doubles; 0 for a
  /// texel no triangle covers). Parallel over the rows; advances `progress` per row (throws
  /// prt::Cancelled). Returns the rays cast.
  std::uint64_t compute(int k, RowRange rows, const PassSource& input, float* out, double* variance,
                        Progress* progress = nullptr) const;

  /// sum[r] += pass[r] for the rows both cover, in the one order every driver uses: the first
  /// pass added sets the sum (a scalar pass broadcast to every channel of an RGB sum), later
  /// ones add. `sum` has sumChannels() channels over sumRows.
  void accumulate(int k, RowRange passRows, const float* values, RowRange sumRows,
                  float* sum) const;

  /// The transfer of resultShape() from the last pass (or the sum) over the rows of the last
  /// pass: per texel laid out as the lightmap, dilated `padding` rings (texels beyond hold
  /// zeros) and cut to the bake's range; `filled` (when given) gets, per texel of the whole
  /// lightmap, whether a covered texel or the dilation set it. Per vertex, the rows as they are.
  Transfer finish(const Transfer& last, std::vector<std::uint8_t>* filled = nullptr) const;

  /// The statistics bake() reports, from each pass's rays and seconds and the variance per row
  /// of `varianceRows` (summed in pass order over the passes that count): the error estimates
  /// over the rows of the bake's range that were sampled.
  BakeStats stats(const std::vector<std::uint64_t>& rays, const std::vector<double>& seconds,
                  RowRange varianceRows, const std::vector<double>& variance, double secondsTotal,
                  int threads) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One line that tells one bake from another: the mesh (vertex and triangle count, a
/// fingerprint of its positions, normals, triangles and albedo; per texel its lightmap UVs
/// too), the domain and every setting that changes a row. Pieces of a split bake (checkpointed
/// chunks, job-array pass files) carry it, and only pieces with the same identity are joined.
std::string bakeIdentity(const Mesh& mesh, const BakeSettings& settings);

/// A bake between its passes: what the passes finished so far leave for the next one, held by
/// this process. The rows of a pass an executor computed only part of (a job-array shard; the
/// last pass on an MPI rank other than 0) narrow `previous`, `sum` and `variance` to them.
struct PassState {
  int done = 0;                  ///< passes finished
  Transfer previous;             ///< the last finished pass's rows (empty before pass 0)
  Transfer sum;                  ///< the running sum (a vector transfer), when the bake keeps one
  RowRange varianceRows;         ///< the rows `variance` covers
  std::vector<double> variance;  ///< per row, summed over the passes that count
  std::vector<std::uint64_t> rays;  ///< per finished pass, over all the rows it covers
  std::vector<double> seconds;      ///< per finished pass
};

/// Where a pass's rows are computed: this process's threads, the ranks of an MPI job, or one
/// shard of a job array. The executor decides nothing about the bake: runPass asks it for rows.
class PassExecutor {
 public:
  virtual ~PassExecutor() = default;
  struct Rows {
    /// The rows of the pass this process holds afterwards (empty Transfer: none).
    Transfer values;
    /// Their estimator variances, one per row of `values` (empty unless the pass counts them).
    std::vector<double> variance;
    std::uint64_t rays = 0;  ///< cast by every process for this pass
    double seconds = 0;
  };
  /// The options its pass lists are made with (an MPI rank checks its own memory in begin).
  virtual BakePassOptions passOptions() const { return {}; }
  /// Called once a bake's passes are made, before pass 0 (memory per rank, a checkpoint).
  virtual void begin(const BakePasses& passes) {}
  /// Where a failure in making the passes or in begin meets the other processes: rethrown
  /// here; MPI ranks agree on it first, so that every rank throws alike.
  virtual void agree(std::exception_ptr failure);
  /// Computes pass k of `passes` reading `input`; `progress` for its share of the bake.
  virtual Rows run(const BakePasses& passes, int k, const PassSource& input,
                   const ProgressFn& progress) = 0;
  /// Threads the bake ran on, all processes together.
  virtual int threads() const;
};

/// The in-process executor: every row of every pass on this process's threads.
class ThreadExecutor : public PassExecutor {
 public:
  Rows run(const BakePasses& passes, int k, const PassSource& input,
           const ProgressFn& progress) override;
};

/// The state before pass 0: the running sum (when the bake keeps one) and the variances over
/// the whole domain, zero (each pass narrows them to the rows it covers).
PassState startPasses(const BakePasses& passes);
/// Runs pass state.done on `executor` and joins it to the state: the one step every driver
/// takes, which alone knows whether the bake sums its passes.
void runPass(const BakePasses& passes, PassExecutor& executor, PassState& state,
             const ProgressFn& progress = {});
/// The transfer of a state whose passes are all done (BakePasses::finish of the last pass, or
/// of the sum), and its statistics; `secondsTotal` the bake's wall time.
Transfer finishPasses(const BakePasses& passes, const PassState& state, double secondsTotal,
                      int threads, BakeStats* stats, std::vector<std::uint8_t>* filled = nullptr);
/// Every pass on `executor` (the loop bake() runs): startPasses, runPass for each, finishPasses.
Transfer runBakePasses(const BakePasses& passes, PassExecutor& executor, BakeStats* stats,
                       const ProgressFn& progress);

/// What a bake returns besides its transfer, per texel: where it sampled and what it refilled.
struct TexelBakeInfo {
  TexelSamples samples;
  std::vector<std::uint32_t> inside;  ///< covered texels inside geometry, ascending
  std::vector<std::uint8_t> filled;   ///< per texel: covered, or reached by the dilation
};

/// bake() on `executor`: makes the passes (executor.passOptions(), agreed on), begins and runs
/// them. Empty on a process that does not hold the result.
Transfer bake(const Mesh& mesh, const Occluder& occluder, const BakeSettings& settings,
              PassExecutor& executor, BakeStats* stats = nullptr, const ProgressFn& progress = {},
              TexelBakeInfo* texels = nullptr);

}  // namespace prt
