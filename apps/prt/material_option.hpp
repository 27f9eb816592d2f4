#pragma once
// `--material SPEC` for the verbs that relight or check a bake (render, validate, reference,
// web): one rule for all of them.

#include <string>

#include "prt/transfer/material.hpp"
#include "prt/transport/bake.hpp"

namespace prt::cli {

/// The bake's material when `spec` is empty; else `spec` parsed (prt::Error on a bad one),
/// keeping the bake's kd unless `spec` names its own. When the spec changes the lobe or ks that
/// an inter-reflected matrix bake's bounces were baked with (glossyBounces), warns, naming
/// `file`: the light the surfaces send each other keeps the baked material, the surface at each
/// vertex takes the new one. `consequence` ends that warning (what it means for this verb).
Material materialOption(const std::string& spec, const BakeSettings& baked, const std::string& file,
                        const std::string& consequence);

}  // namespace prt::cli
