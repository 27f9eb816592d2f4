#pragma once
// prt denoise and --denoise of prt bake: the edge-avoiding à-trous filter
// (transport/denoise_texels.hpp) of every transfer of a complete per-texel bake, with the
// estimated noise before and after on stderr.

#include <string>

#include "prt/core/json.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/transport/denoise_texels.hpp"

namespace prt::cli {

/// Filters every transfer of `file` in place; throws prt::Error naming `name` for a per-vertex,
/// probe, partial or compressed bake. Returns what the filter did per transfer (the report's
/// "denoise").
Json denoiseBake(BakeFile& file, const std::string& name, const DenoiseSettings& settings);

}  // namespace prt::cli
