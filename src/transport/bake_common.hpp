#pragma once
// Pieces shared by the vector (diffuse) and matrix (glossy) bakes; private to src/transport.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <memory>
#include <optional>
#include <span>

#include "prt/core/limits.hpp"
#include "prt/core/progress.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/transport/bake.hpp"

namespace prt::bakedetail {

using Clock = std::chrono::steady_clock;

inline double seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

/// Albedo used for the bounces: uniform or per vertex, interpolated at hits.
struct BounceAlbedo {
  bool perVertex = false;
  bool grey = true;
  Rgb uniform{1.0f};
  /// The diffuse colour at each vertex (albedoAtVertices: the base-colour texture folded in at
  /// the vertices, as every per-vertex consumer sees it), shared by the copies in the setups.
  std::shared_ptr<const std::vector<Rgb>> store;
  const std::vector<Rgb>* values = nullptr;

  Rgb at(const std::array<std::uint32_t, 3>& tri, float u, float v) const {
    if (!perVertex) return uniform;
    const auto& a = *values;
    return a[tri[0]] * (1.0f - u - v) + a[tri[1]] * u + a[tri[2]] * v;
  }
};

/// Running sum and sum of squares of one scalar estimator, for its i.i.d. standard error.
struct Moments {
  double s1 = 0, s2 = 0;
  void add(double x) {
    s1 += x;
    s2 += x * x;
  }
  /// Estimated variance of the mean of n samples (unbiased sample variance / n).
  double varianceOfMean(int n) const {
    if (n < 2) return 0;
    const double mean = s1 / n;
    const double var = std::max(0.0, (s2 - n * mean * mean) / (n - 1));
    return var / n;
  }
};

/// The mean and the largest of the per-vertex standard errors √Var over a baked range.
struct StandardErrors {
  double mean = 0, max = 0;
};
inline StandardErrors standardErrors(const std::vector<double>& variances) {
  StandardErrors e;
  for (double var : variances) {
    const double se = std::sqrt(var);
    e.mean += se;
    e.max = std::max(e.max, se);
  }
  e.mean = variances.empty() ? 0.0 : e.mean / double(variances.size());
  return e;
}

/// Throws prt::Error naming the first problem with the mesh or the settings.
void validateBake(const Mesh& mesh, const BakeSettings& s);
using prt::domainRows;  // (prt/transport/bake.hpp)
/// The rows a bake covers: settings.rows with count 0 meaning "to the last row".
RowRange bakeRows(const Mesh& mesh, const BakeSettings& s);
/// The bounce albedo: the material's diffuse colour, else the mesh's, else white.
BounceAlbedo resolveAlbedo(const Mesh& mesh, const BakeSettings& s);

using prt::physicalMemoryBytes;  // (prt/core/limits.hpp, with the 90% policy)
/// Throws prt::Error stating the figure when the bake would not fit in this machine's memory.
void checkFootprint(const Mesh& mesh, const BakeSettings& s, const BakeFootprint& f);

/// What a bake is, decided once before its passes are made (planBake, the one call the pass list
/// makes here): the settings checked, its rows, its footprint, and the recipes of the passes that
/// feed a matrix bake's bounces.
struct BakePlan {
  RowRange rows;               ///< the bake's range (count resolved)
  std::size_t domainRows = 0;  ///< rows of the whole domain
  BakeFootprint footprint;
  /// Matrix, K bounces, diffuse bounce surfaces: the vector transfer of K − 1 bounces the
  /// matrices gather (diffuseBounceSource).
  std::optional<BakeSettings> diffuseSource;
  /// Matrix, K bounces, glossy bounce surfaces: the orders 0..K (glossyBounceOrders) and each
  /// order's channels.
  std::vector<BakeSettings> glossyOrders;
  std::vector<int> glossyChannels;
  /// Haar, K bounces: the SH vector transfer with K bounces whose bounce passes each row holds
  /// after its pairs (haarBounceSource).
  std::optional<BakeSettings> haarBounce;
};
/// Checks the mesh and the settings (validateBake) and, when `checkMemory`, the footprint
/// against this machine's memory (checkFootprint), then plans the bake.
/// The SH bake an inter-reflected Haar bake takes its bounce from: vector, its bounce bands,
/// kHaarBounceSamplesPerTexelRay directions per ray a texel, the same bounces, seed and material,
/// over the whole domain.
BakeSettings haarBounceSource(const BakeSettings& haarBake);
BakePlan planBake(const Mesh& mesh, const BakeSettings& s, bool checkMemory);

// The passes' kernels (passes.cpp builds the pass list on them).

/// Where a row of the transfer is integrated: a point of the surface, its unit normal, and the
/// row's global index, which alone seeds its samples (a mesh vertex, or a texel's sample point).
struct RowPoint {
  Vec3f position, normal;
  std::size_t id = 0;
};

/// A texel-domain pass as a lightmap image for the next pass to read: width × height texels of
/// `stride` floats (dilated past the charts), over the mesh's lightmap `uvs`.
struct TexelImage {
  const float* values = nullptr;
  int width = 0, height = 0;
  std::size_t stride = 0;
  std::span<const Vec2f> uvs;
  /// The four texels a hit reads (bilinearTaps at its interpolated lightmap UV): the one lookup
  /// every bounce over a lightmap makes, vector or matrix.
  TexelTaps tapsAt(const std::array<std::uint32_t, 3>& tri, float u, float v) const {
    const float b0 = 1.0f - u - v;
    const Vec2f a = uvs[tri[0]], b = uvs[tri[1]], c = uvs[tri[2]];
    return bilinearTaps({b0 * a.x + u * b.x + v * c.x, b0 * a.y + u * b.y + v * c.y}, width,
                        height);
  }
  const float* row(std::size_t texel) const { return values + texel * stride; }
};

/// The bounce recipes a matrix bake is made of, the one rule for every driver (passes.cpp per
/// vertex, bake_texels.cpp per texel): with diffuse bounce surfaces, the vector transfer of one
/// bounce less the matrices gather; with glossy ones, the matrices of orders 0..K, each from the
/// one before, order j's seed derived down the chain from the bake's (order K is the bake's).
/// The passes a later one reads have their rows cleared (they cover the whole domain); order K
/// is the bake itself.
BakeSettings diffuseBounceSource(const BakeSettings& matrixBake);
std::vector<BakeSettings> glossyBounceOrders(const BakeSettings& matrixBake);

/// How a matrix bake's passes are reported, from each pass's rays and seconds (in pass order)
/// and the variance of M_00 per row of its range: the direct seconds are the matrices' own (the
/// first order's, with glossy bounces), a diffuse bake's vector passes count as its one bounce;
/// the standard error is that of M_00, the transferred radiance under the constant light.
enum class MatrixPassKind { Direct, DiffuseBounces, GlossyBounces };
BakeStats matrixStats(MatrixPassKind kind, const std::vector<std::uint64_t>& rays,
                      const std::vector<double>& seconds, const std::vector<double>& variance,
                      double secondsTotal);

/// A vector bake's shared tables (bake.cpp).
struct VectorSetup;
std::shared_ptr<const VectorSetup> makeVectorSetup(const Mesh& mesh, const BakeSettings& s);
bool vectorAlbedoGrey(const VectorSetup& setup);
/// Rows of vector pass `pass` (0: direct, B² floats per row; k ≥ 1: bounce k reading `prev`,
/// the whole mesh's Tᵏ⁻¹, B² × outChannels floats per row).
std::uint64_t computeVectorRows(const Mesh& mesh, const Occluder& occluder,
                                const VectorSetup& setup, int pass, RowRange rows,
                                const Transfer* prev, int outChannels, float* out, double* variance,
                                Progress* progress);
/// The same at texel sample points (bake_texels.cpp): rows 0..points.size()−1, pass k ≥ 1
/// reading the previous pass's lightmap `prev` bilinearly at each hit's lightmap UV.
std::uint64_t computeTexelRows(const Mesh& mesh, const Occluder& occluder, const VectorSetup& setup,
                               int pass, std::span<const RowPoint> points, const TexelImage* prev,
                               int outChannels, float* out, double* variance, Progress* progress);
/// The statistics of a vector bake from its passes' rays, seconds and summed variances.
BakeStats vectorStats(const std::vector<std::uint64_t>& rays, const std::vector<double>& seconds,
                      const std::vector<double>& variance);

/// One matrix pass's tables (bake_matrix.cpp).
struct MatrixSetup;
/// `bounce`: it reads a bounced transfer; `glossy`: that transfer is the matrices of one order
/// less, seen through the material's lobe (else the diffuse vector transfer).
std::shared_ptr<const MatrixSetup> makeMatrixSetup(const Mesh& mesh, const BakeSettings& s,
                                                   bool bounce, bool glossy, int channels);
std::uint64_t computeMatrixRows(const Mesh& mesh, const Occluder& occluder,
                                const MatrixSetup& setup, RowRange rows, const Transfer* bounced,
                                float* out, double* variance, Progress* progress);
/// The same at texel sample points (bake_texels.cpp): rows 0..points.size()−1, a bounce reading
/// `bounced` — the previous order's lightmap (the diffuse vector sum, or the glossy matrices of
/// one order less), dilated — bilinearly at each hit's lightmap UV.
std::uint64_t computeMatrixTexelRows(const Mesh& mesh, const Occluder& occluder,
                                     const MatrixSetup& setup, std::span<const RowPoint> points,
                                     const TexelImage* bounced, float* out, double* variance,
                                     Progress* progress);
/// The same at probes (points with no surface: over the whole sphere), rows
/// 0..points.size()−1, a bounce reading `bounced`, the mesh's diffuse vector transfer of one
/// bounce less (its vertices' rows), interpolated over each hit triangle.
std::uint64_t computeMatrixProbeRows(const Mesh& mesh, const Occluder& occluder,
                                     const MatrixSetup& setup, std::span<const RowPoint> points,
                                     const Transfer* bounced, float* out, double* variance,
                                     Progress* progress);
/// The seed of the glossy bounce order `order` baked under a bake of seed `seed`.
std::uint64_t matrixBounceOrderSeed(std::uint64_t seed, int order);
/// The unshadowed matrix H(n) = ∫_{n·ω>0} Y Yᵀ dω at each of `normals` (unit): B² × B² floats,
/// row-major, one after another — what a matrix bake's control variate makes exact.
std::vector<float> unshadowedMatrixRows(int bands, std::span<const Vec3f> normals);

}  // namespace prt::bakedetail
