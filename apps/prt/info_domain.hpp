#pragma once
// prt info: the domain of a bake beyond its mesh (info_domain.cpp).

#include <ostream>

#include "prt/core/json.hpp"
#include "prt/io/bake_file.hpp"

namespace prt::cli {

/// Per texel: the lightmap's size, coverage and seams; per probe: the grid. Nothing per vertex.
void describeBakeDomain(const BakeFile& bake, std::ostream& out, Json& j);

}  // namespace prt::cli
