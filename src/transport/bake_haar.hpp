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

/// An inter-reflected Haar bake's bounce, in SH (the sum of its SH bounce passes): the row of
/// global index i (a vertex, or a texel of the dilated lightmap) at values + i · stride, copied
/// after each Haar row's pairs. Empty (values null) for a bake without bounces.
struct HaarBounceSource {
  const float* values = nullptr;
  std::size_t stride = 0;
};

/// Rows `rows` of the mesh's vertices (`stride` floats each: the row, then its bounce).
std::uint64_t computeHaarRows(const Mesh& mesh, const Occluder& occluder, const HaarSetup& setup,
                              RowRange rows, HaarBounceSource bounce, std::size_t stride,
                              float* out, double* variance, Progress* progress);
/// The same at texel sample points, rows 0..points.size()−1.
std::uint64_t computeHaarTexelRows(const Occluder& occluder, const HaarSetup& setup,
                                   std::span<const RowPoint> points, HaarBounceSource bounce,
                                   std::size_t stride, float* out, double* variance,
                                   Progress* progress);

}  // namespace prt::bakedetail
