#pragma once
// Validation of a bake against the Monte Carlo reference (reference.hpp): per band count b, the
// PRT radiance R_b(p) = ρ(p) ⊙ T_b(p)·L_b (the first b² coefficients of one bake and of the
// light: Transfer::cut) against the reference R_ref(p), over a set of vertices.
//
// With N validated vertices p, channels c ∈ {r, g, b}, d = R_b − R_ref, and
// ε = 10⁻² · m², m the mean over vertices and channels of R_ref (scale-free, so dark vertices do
// not dominate; cf. Rousselle et al. 2011's relMSE):
//   rel RMSE         sqrt( 1/(3N) Σ_p Σ_c d_pc² / (R_ref,pc² + ε) )   (render::relativeRmse)
//   energy-weighted  sqrt( Σ_p Σ_c d_pc² / Σ_p Σ_c R_ref,pc² )        (‖d‖ / ‖R_ref‖, no ε)
//   mean / max       mean and maximum over p of
//                    e(p) = sqrt( Σ_c d_pc² / Σ_c (R_ref,pc² + ε) )
//   truncation floor the rel RMSE of exact band-limited relighting — what PRT with a noise-free
//                    b-band transfer gives — against the reference: the same metric with
//                    e_b − e for the difference, e_b − e estimated per vertex from the
//                    reference's own samples (reference.hpp: the light cut to b bands along
//                    every path, and for matrix transfer the cosine and lobe kernels and the
//                    transferred light cut too), x̂² − se² per channel so its noise does not
//                    inflate it. Over an even stride of at most `floorVertices` of the
//                    validated vertices.
//   ref std err      the reference's noise in the same metric:
//                    sqrt( 1/(3N) Σ_p Σ_c se_pc² / (R_ref,pc² + ε) )
// so that, for a noise-free bake, E[rel RMSE²] = floor² + (ref std err)² (docs/validation.md
// derives it): `unexplainedSq` = rel RMSE² − floor² − ref std err² (over the floor's vertices)
// is then 0 within `unexplainedSqStdErr`, its standard error over vertices; what stands above
// it is the bake's own error (its noise, its interpolation at bounce hits) or a bug.
//   negative         the share of validated vertices (for glossy transfer, of those facing the
//                    eye: the others are not seen from it) whose PRT radiance is negative in
//                    some channel (below −10⁻³ m, so that rounding does not count): SH
//                    ringing, which a window on the light (ValidateSettings::window) tames.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "prt/core/random_order.hpp"
#include "prt/image/image.hpp"
#include "prt/render/reference.hpp"
#include "prt/sh/convolve.hpp"
#include "prt/sh/irradiance_encoding.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transport/bake.hpp"

namespace prt::render {

struct ValidateSettings {
  /// Samples, seed, rotation, heuristic (mode and bounces: the bake's; the rows and, per texel,
  /// their points: validate()'s own, chooseRows — `reference.points` is left empty).
  ReferenceSettings reference;
  std::vector<int> bandsList;   ///< band counts to tabulate; empty: 1..B
  std::size_t maxVertices = 0;  ///< 0: every vertex; else a deterministic random subset
  /// Vertices over which the truncation floor is taken (an even stride of the validated ones);
  /// it costs one band-limited reference run over them for all band counts (about the
  /// reference's own cost per vertex for vector transfer, twice it for matrices).
  std::size_t floorVertices = 1024;
  /// A window on the light against ringing, applied at each band count b to the b-band light
  /// (as `prt light --bands b --window W` would) for PRT and the floor alike.
  sh::Window window = sh::Window::None;
  /// Irradiance encodings to measure (issue 34; a diffuse matrix bake only): at each validated
  /// row, the diffuse shading an engine gets from encoding E of the light arriving there
  /// (relight::encodedDiffuse) at the full band count, against the reference and against the
  /// bake's own relighting (ValidationReport::encodings).
  std::vector<sh::IrradianceEncoding> encodings;
  /// The bake file the transfer came from, named when its relighting overflows.
  std::string bakeName;
  /// Runs the reference (the main run and the floor's band-limited run): renderReference over
  /// the mesh, occluder and environment validate() is given when empty; a scheduler that
  /// spreads it over ranks sets its own (it must return renderReference's result).
  std::function<ReferenceResult(const ReferenceSettings&, const ProgressFn&)> runReference;
  /// The reference already computed (a reference file, io/reference_file.hpp) with `reference`'s
  /// settings and this bake's mode, bounces and material: used as it is, over its own vertices
  /// (maxVertices is then ignored); only the floor's band-limited run is made. The caller checks
  /// that it belongs to this mesh and environment.
  const ReferenceResult* precomputed = nullptr;
};

/// Above this share of negative-radiance vertices a row calls for a window on the light.
inline constexpr double kNegativeShareWarning = 0.05;

struct BandRow {
  int bands = 0;
  double relRmse = 0, energyRel = 0, meanRel = 0, maxRel = 0, floor = 0, refStdErr = 0;
  /// The floor with the light alone cut (exact kernels): for matrix transfer, what a floor
  /// that ignores the truncation of the transferred light would say; = floor for vectors.
  double lightFloor = 0;
  /// rel RMSE² − floor² − ref std err² over the floor's vertices, and its standard error.
  double unexplainedSq = 0, unexplainedSqStdErr = 0;
  /// sqrt(floor² + ref std err²) / rel RMSE over the floor's vertices: near 1 when truncation
  /// and the reference's noise account for the error; well below 1, the bake's own error (its
  /// noise, or a bug) shows.
  double explained = 1;
  /// Share of the validated (glossy: eye-facing) vertices with a negative channel.
  double negativeShare = 0;
  /// Glossy materials: the fraction of the lobe's energy beyond `bands` (GlossyLobe::energyBeyond),
  /// what no b-band transfer can hold however exact; 0 for diffuse surfaces.
  double lobeEnergyBeyond = 0;
};

/// What an irradiance encoding costs at the validated rows (ValidateSettings::encodings).
struct EncodingRow {
  sh::IrradianceEncoding encoding = sh::IrradianceEncoding::L2;
  int numbers = 0;          ///< stored per row, RGB (sh::storedNumbers)
  double relRmse = 0;       ///< the table's metric against the reference
  double energyRel = 0;     ///< ‖E − R_ref‖ / ‖R_ref‖
  double vsBake = 0;        ///< ‖E − R_b‖ / ‖R_b‖: against the bake's own relighting (all bands)
  double negativeShare = 0; ///< validated rows with a negative channel
};

/// What the floor is, in one phrase (the report's floorMethod; the CLI's label).
inline constexpr const char* kFloorMethod = "exact band-limited relighting";

struct ValidationReport {
  TransferMode mode = TransferMode::Shadowed;
  int bounces = 0;
  int transferBands = 0, lightBands = 0, bands = 0;  ///< bands = min(transfer, light)
  std::vector<std::string> warnings;
  ReferenceResult reference;       ///< over the validated vertices
  std::vector<BandRow> rows;       ///< one per band count, ascending
  std::vector<EncodingRow> encodings;  ///< one per ValidateSettings::encodings, in its order
  std::vector<float> vertexError;  ///< e(p) at the last row's band count, per validated vertex
  std::string floorMethod;         ///< kFloorMethod
  std::size_t floorVertices = 0;   ///< vertices the floor was taken over
  std::uint64_t floorRays = 0;     ///< rays of the band-limited run
  double floorSeconds = 0;
  std::string window = "none";       ///< the window on the light
  std::size_t negativeVertices = 0;  ///< the vertices negativeShare counts among
  /// The reference is 0 at every validated vertex (a black environment): relative errors are
  /// undefined, and the rows hold NaN for them (formatTable prints "n/a", reportJson null).
  bool referenceIsZero = false;
};

/// The seeded random order of [0, n) that subsets are drawn in (core/random_order.hpp).
RandomOrder subsetOrder(std::size_t n, std::uint64_t seed);
/// A deterministic random subset of `count` of [0, n) (all when count is 0 or ≥ n), sorted: the
/// first `count` elements of subsetOrder(n, seed), in O(count) memory.
std::vector<std::uint32_t> vertexSubset(std::size_t n, std::size_t count, std::uint64_t seed);

/// The rows a reference estimates and where they lie.
struct RowChoice {
  std::vector<std::uint32_t> rows;          ///< ascending
  std::shared_ptr<const RowPoints> points;  ///< per texel: the rows' points alone; per vertex null
};
/// The rows a reference estimates, the one rule for prt reference and validation. Of a
/// per-vertex transfer, vertexSubset of the mesh's vertices. Of a per-texel one, `count` of its
/// valid texels (never the gutter, never a texel inside geometry; 0 or more than there are:
/// every one): the covered texels are taken in subsetOrder of them and the valid ones kept until
/// `count` are. Each valid texel is as likely as any other — a uniformly random subset of the
/// valid ones — yet only the texels drawn are sampled and probed for being inside geometry, so
/// the cost is that of `count` texels (and one bit per texel to find the covered ones), not of
/// the lightmap; where no texel lies inside geometry it is vertexSubset of the covered texels.
RowChoice chooseRows(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                     std::size_t count, std::uint64_t seed);

/// Validates `transfer` (every vertex of `mesh`, baked with `bake` settings) lit by `light` (the
/// projection of `env`) against the reference. Band counts beyond min(transfer, light) are
/// dropped with a warning. Reads the transfer's validated rows alone (a mapped bake file,
/// io/bake_file.hpp: mapBake, is read there only), and throws prt::Error naming
/// settings.bakeName if one of them is not finite. Throws prt::Error on mismatched sizes or bad
/// settings.
ValidationReport validate(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                          const BakeRecipe& bake, const envmap::Environment& env,
                          const sh::RgbSh& light, const ValidateSettings& settings,
                          const ProgressFn& progress = {});

/// The per-vertex error e(p) of `report` (its last row's band count) as false colours for every
/// vertex of `mesh`, black 0 .. white `*scale` (the 99th percentile of e, written to `scale`).
/// When the report covers a vertex subset, every other vertex shows the error of the nearest
/// validated vertex facing within 60° of it (a Voronoi fill), so the image reads as a field.
std::vector<Rgb> vertexErrorColours(const Mesh& mesh, const ValidationReport& report,
                                    float* scale = nullptr);

/// The error image of `report` over `transfer`'s rows, black 0 .. white `*scale` (the 99th
/// percentile, written to `scale`): per vertex the mesh drawn through `width` × `height` pixels
/// of prt render's default camera with vertexErrorColours; per texel the lightmap itself, each
/// validated texel's error, black elsewhere (`width`, `height` unused).
image::Image errorImage(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
                        const ValidationReport& report, int width, int height, float* scale,
                        const ProgressFn& progress = {});

/// The table as text: a header and one line per band count.
std::string formatTable(const ValidationReport& report);
/// The report as JSON (settings, rows, timing).
std::string reportJson(const ValidationReport& report, int indent = 2);

}  // namespace prt::render
