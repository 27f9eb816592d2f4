#pragma once
// The options that say what a verb relights or checks — which transfer of a bake (--mode,
// --transfer) and with which material (--material) — worded once for render, validate,
// reference, compress, export, view, web and the demo, with one rule each.

#include <CLI/CLI.hpp>
#include <string>

#include "prt/io/bake_file.hpp"
#include "prt/transfer/material.hpp"

namespace prt::cli {

/// Which transfer of a bake: a mode and a layout ("" = the default, prt::pickTransfer's order).
struct TransferChoice {
  std::string mode;
  std::string layout;
};
/// Adds --mode and --transfer to `cmd`; `what` ends their help ("to relight", "to compress").
void addTransferChoice(CLI::App* cmd, TransferChoice& choice, const std::string& what);
/// The transfer the choice names (prt::pickTransfer; prt::Error naming `file` if absent).
const BakedTransfer& pickTransfer(const BakeFile& bake, const TransferChoice& choice,
                                  const std::string& file);

/// What a material spec may say, for --material's help: the three lobes, kd, what ggx is.
const std::string& materialGrammar();
/// Adds --material to `cmd`; `what` ends its help (what the material is for in this verb).
void addMaterialOption(CLI::App* cmd, std::string& spec, const std::string& what);
/// The bake's material when `spec` is empty; else `spec` parsed (prt::Error on a bad one),
/// keeping the bake's kd unless `spec` names its own. When the spec changes the lobe or ks that
/// an inter-reflected matrix bake's bounces were baked with (glossyBounces), warns, naming
/// `file`: the light the surfaces send each other keeps the baked material, the surface at each
/// vertex takes the new one. `consequence` ends that warning (what it means for this verb).
Material materialOption(const std::string& spec, const BakedTransfer& baked,
                        const std::string& file, const std::string& consequence);
/// Warns when a glossy material meets a vector transfer (diffuse only): `consequence` says what
/// the verb does instead.
void warnLobeOnVectors(const Material& m, const BakedTransfer& baked, const std::string& file,
                       const std::string& consequence);

/// Warns, naming `file`, when the glossy lobe of `m` loses more than kLobeEnergyLossWarning of
/// its energy beyond `bands` (what no `bands`-band transfer can hold), with the fraction and
/// what would hold it.
void warnLobeEnergyLoss(const Material& m, int bands, const std::string& file);

/// `validate` and `reference` integrate the environment itself: an SH light file (.json, the
/// course's light.txt) cannot stand in for it; refused in one line naming the file and `verb`.
void refuseShLight(const std::string& light, const std::string& verb);

}  // namespace prt::cli
