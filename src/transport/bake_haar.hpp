#pragma once
// The Haar bake's kernel (bake_haar.cpp); private to src/transport.

#include <cstdint>
#include <memory>
#include <span>

#include "bake_common.hpp"
#include "prt/haar/cube_texels.hpp"

namespace prt::bakedetail {

/// What every row of a Haar bake shares: the settings and the cube's texels.
struct HaarSetup {
  BakeSettings settings;
  haar::CubeTexels texels;
};
std::shared_ptr<const HaarSetup> makeHaarSetup(const BakeSettings& s);

/// Rows `rows` of the mesh's vertices (2 · terms floats each).
std::uint64_t computeHaarRows(const Mesh& mesh, const Occluder& occluder, const HaarSetup& setup,
                              RowRange rows, float* out, double* variance, Progress* progress);
/// The same at texel sample points, rows 0..points.size()−1.
std::uint64_t computeHaarTexelRows(const Occluder& occluder, const HaarSetup& setup,
                                   std::span<const RowPoint> points, float* out, double* variance,
                                   Progress* progress);

}  // namespace prt::bakedetail
