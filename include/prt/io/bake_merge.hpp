#pragma once
// Merging split bakes (prt bake --range, then prt merge): bakes of disjoint, adjacent vertex
// ranges of the same mesh with the same transfers and recipes join into one bake of the union
// range, bit for bit what a bake of the union would hold (a vertex's transfer depends only on
// the inputs, the seed and its global index).

#include <vector>

#include "prt/io/bake_file.hpp"

namespace prt {

/// Concatenates `pieces` (in any order) into one bake of the union range. Statistics combine as
/// combineBakeStats says. Throws prt::Error("merge: the piece starting at vertex F ...") naming
/// the first mismatch, gap or overlap; compressed transfer is refused (merge, then compress).
BakeFile mergeBakes(std::vector<BakeFile> pieces);

}  // namespace prt
