#pragma once
// --seam-fix of prt bake and prt merge: the least-squares seam fix
// (transport/lightmap_seam_fix.hpp) of every transfer of a complete per-texel bake, with the
// seam metric before and after on stderr.

#include <string>

#include "prt/io/bake_file.hpp"

namespace prt::cli {

/// Fixes the seams of every transfer of `file` in place; throws prt::Error naming `name` for a
/// per-vertex, partial or compressed bake.
void fixBakeSeams(BakeFile& file, const std::string& name);

}  // namespace prt::cli
