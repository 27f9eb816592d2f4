#pragma once
// One bake as every front end asks for it — `prt bake`, `prtkit.bake` and the MPI driver build
// the same BakeRequest from their options, check it with one set of messages, and hand it to
// one bake(request, …, executor): the modes, the shape (layout, bands, domain with its
// lightmap), the recipe (samples, bounces, seed, sampling, material) and the rows. The domain is
// one field of it, never a branch in a front end.

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "prt/core/options.hpp"
#include "prt/core/progress.hpp"
#include "prt/geometry/lightmap_uvs.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/geometry/texel_samples.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt {

class PassExecutor;

/// The defaults of a Haar bake: a 32² cube (6,144 texels) keeping 64 terms per row.
inline constexpr int kDefaultHaarResolution = 32;
inline constexpr int kDefaultHaarTerms = 64;
/// The samples a bake takes when none are given: 1024 directions per row (SH), one ray per cube
/// texel (Haar) — the one policy every front end follows.
long long defaultSamples(TransferBasis basis);

/// The lightmap of a per-texel bake (TransferDomain::Texels).
struct LightmapRequest {
  int resolution = 512;                ///< the lightmap's side in texels
  int padding = 2;                     ///< rings of gutter dilated around the charts
  UvSetOption uv = UvSetOption::Auto;  ///< which UV set it lies over
  bool seamFix = false;                ///< the least-squares seam fix after the bake
  bool denoise = false;                ///< the à-trous filter after the bake (before the seam fix)
};

/// The grid of a probe bake (TransferDomain::Probes): probes at the centres of count[a] cells
/// along each axis of the bounds (makeProbeGrid).
struct ProbeGridRequest {
  std::array<int, 3> count{0, 0, 0};  ///< all 0: automatic (kAutoProbeCells on the longest side)
  std::optional<std::pair<Vec3f, Vec3f>> bounds;  ///< low and high corners; none: the scene's
};

struct BakeRequest {
  std::vector<TransferMode> modes;  ///< one transfer per mode, in this order
  TransferLayout layout = TransferLayout::Vector;
  int bands = 3;  ///< SH; Haar: the bands of an inter-reflected row's bounce
  /// SH (bands), or Haar wavelets over a cube map (haar: its resolution and the terms kept per
  /// row; samples are then rays per cube texel).
  TransferBasis basis = TransferBasis::SphericalHarmonics;
  TransferShape::HaarSize haar{kDefaultHaarResolution, kDefaultHaarTerms};
  long long samples = 1024;  ///< wide, so an absurd count gets the request's message
  int bounces = 1;           ///< inter-reflected modes only
  std::uint64_t seed = 0;
  Sampling sampling = Sampling::CosineSobol;
  /// Adaptive sampling (BakeRecipe::targetError): 0 off; E > 0 casts up to `samples` per row
  /// until the standard error of its radiance under the unit sky reaches E.
  double targetError = 0;
  /// The surface; none: the mesh file's own glossy surface (materialFromGloss), else lambert.
  std::optional<Material> material;
  /// A uniform albedo replacing the mesh's (and the material's kd).
  std::optional<Rgb> albedo;
  TransferDomain domain = TransferDomain::Vertices;
  LightmapRequest lightmap;  ///< per texel
  ProbeGridRequest probes;   ///< per probe
  RowRange rows;             ///< of the domain; count 0: to the last row
};

/// The one check of a request before anything is loaded: modes given and distinct, bands (or
/// the Haar cube and terms: vector, per vertex or texel; inter-reflected, its bounce's 1..5
/// bands), samples and bounces in range, the lightmap's resolution and padding, the seam fix
/// only per texel and of a whole lightmap. Throws prt::Error with one line naming the option as
/// `spelling` writes it.
void checkBakeRequest(const BakeRequest& request, OptionSpelling spelling);

/// The material the request bakes with on `mesh`: the one given, else the mesh file's own glossy
/// surface (MTL Ks/Ns, glTF metallic-roughness), else lambert; the albedo given replaces its kd.
Material bakeMaterial(const BakeRequest& request, const Mesh& mesh);

/// What the bake of a request changes in its mesh before the work, so that every consumer of
/// the result relights with what the transfer was baked with: a given albedo (or kd) replaces
/// the mesh's albedo and base-colour texture; per texel, the lightmap UV set chosen becomes
/// Mesh::lightmapUvs. Returns lines for the front end to tell (which UV set and why not another).
/// With UvSetOption::Auto and no set that can hold the lightmap, `unwrapped` is false and the
/// mesh keeps its UVs: the front end unwraps it (prt unwrap's atlas) and calls this again.
struct BakeMeshPreparation {
  std::vector<std::string> notes;
  bool lightmapUvsFound = true;
  std::vector<std::string> uvSetsRefused;  ///< why each set was passed over
  std::string uvSetName;                   ///< the set the lightmap lies over
};
BakeMeshPreparation prepareBakeMesh(Mesh& mesh, const BakeRequest& request);

/// The settings of one mode's transfer of the request on `mesh` (its material, domain, lightmap
/// or probe grid, and rows; bounces 0 unless inter-reflected, as the file records).
BakeSettings bakeSettings(const BakeRequest& request, const Mesh& mesh, TransferMode mode);
/// The probe grid a request asks for on `mesh` (its bounds when the request names none).
ProbeGrid probeGridOf(const BakeRequest& request, const Mesh& mesh);

/// One mode's transfer as bake(request, …) returns it.
struct BakeResult {
  BakeSettings settings;
  Transfer transfer;
  BakeStats stats;
  std::size_t texelsSampled = 0;  ///< per texel: covered texels sampled
  std::size_t texelsInside = 0;   ///< of which inside geometry (refilled from neighbours)
};

/// Never hand on a bake no reader can use: throws prt::Error naming the mesh and the row of the
/// first non-finite coefficient of `transfer` (an absurd material albedo amplified by the
/// bounces, coordinates beyond float range).
void refuseNonFinite(const Mesh& mesh, TransferMode mode, const Transfer& transfer);

/// What a front end hears of a bake: before each mode, its progress, after each mode.
struct BakeObserver {
  std::function<void(const BakeSettings&)> starting;
  std::function<ProgressFn(const BakeSettings&)> progress;
  std::function<void(const BakeResult&)> finished;
};

/// Bakes every mode of `request` on `mesh` (prepared by prepareBakeMesh; `occluder` built from
/// it) on `executor` (the seam fix, when asked, is the front end's, which reports it). Throws
/// prt::Error naming the row of a non-finite coefficient. On an executor that does not hold
/// the result (an MPI rank other than 0) the transfers are empty.
std::vector<BakeResult> bake(const BakeRequest& request, const Mesh& mesh, const Occluder& occluder,
                             PassExecutor& executor, const BakeObserver& observer = {});

}  // namespace prt
