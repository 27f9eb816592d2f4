#pragma once
// Validation of a Haar bake (transfer/shape.hpp's Haar basis) against the Monte Carlo reference
// (reference.hpp, which knows no basis): per light budget K, the rows relit under the
// environment's K largest wavelet terms (haar/project_light.hpp; relight/relight_haar.hpp)
// against the reference's radiance at the same vertices, in the SH table's metrics
// (validate.hpp: rel RMSE with ε = 10⁻² m², energy-weighted, mean and max of e(p)).
//
// The rows always end with the whole cube (K = 6 N²): the light exact on the cube's texels, so
// what that row shows is the bake's own error — its noise, the rows' pruning to their terms,
// and the cube's texels being lit by their mean — and the rows above it add the light's
// non-linear approximation to it (Ng, Ramamoorthi & Hanrahan 2003, §4.2).

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "prt/envmap/environment.hpp"
#include "prt/render/reference.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::render {

struct HaarValidateSettings {
  /// Samples, seed, rotation, heuristic (mode: the bake's; material: its diffuse part).
  ReferenceSettings reference;
  /// Light budgets to tabulate (each clamped to 6 N²); the whole cube is added last.
  std::vector<std::size_t> lightTerms{200};
  std::size_t maxVertices = 0;  ///< rows: 0 every one; else chooseRows' (validate.hpp)
  std::string bakeName;         ///< named when a row is not finite
  /// As ValidateSettings: a scheduler's reference, or one already computed (its vertices).
  std::function<ReferenceResult(const ReferenceSettings&, const ProgressFn&)> runReference;
  const ReferenceResult* precomputed = nullptr;
};

struct HaarRow {
  std::size_t lightTerms = 0;  ///< K
  double energyKept = 1;       ///< of the light's wavelet energy (HaarLight::energyKept)
  double relRmse = 0, energyRel = 0, meanRel = 0, maxRel = 0;
  double negativeShare = 0;  ///< validated vertices relit below −10⁻³ m in some channel
};

struct HaarValidationReport {
  TransferMode mode = TransferMode::Shadowed;
  TransferDomain domain = TransferDomain::Vertices;  ///< what a row is
  int resolution = 0;     ///< the cube's N
  int transferTerms = 0;  ///< kept per row
  ReferenceResult reference;
  double refStdErr = 0;  ///< the reference's noise in the rel-RMSE metric
  std::vector<HaarRow> rows;
  std::vector<std::string> warnings;
};

/// Validates the Haar `transfer` (complete, per vertex of `mesh` or per texel of its lightmap,
/// baked with `bake`) under `env` against the reference, at the rows the SH validation draws
/// (chooseRows). Throws prt::Error for another basis or domain, or non-finite rows.
HaarValidationReport validateHaar(const Mesh& mesh, const Occluder& occluder,
                                  const Transfer& transfer, const BakeRecipe& bake,
                                  const envmap::Environment& env,
                                  const HaarValidateSettings& settings,
                                  const ProgressFn& progress = {});

/// The table prt validate prints for it.
std::string formatHaarTable(const HaarValidationReport& report);

}  // namespace prt::render
