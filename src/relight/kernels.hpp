#pragma once
// The relighting kernels, one per layout × representation, behind relight()'s one dispatch
// (relight.cpp); private to src/relight. Each checks what only it can (its arrays against the
// shape); the dispatch has checked the light, the surface and the output against the transfer.

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <span>

#include "prt/relight/cluster_projection.hpp"
#include "prt/relight/relight.hpp"
#include "prt/transfer/albedo.hpp"

namespace prt::relight::detail {

/// Dense vectors: out[r] = albedo(r) ⊙ T(r)·L (vector_kernels.cpp).
void relightDenseVectors(const Transfer& t, const PreparedLight& light, const Albedo& albedo,
                         std::span<Rgb> out);
/// Dense matrices: the glossy shading of relight.hpp (matrix_kernels.cpp).
void relightDenseMatrices(const Transfer& t, const PreparedLight& light,
                          const PreparedMaterial& material, const Surface& surface,
                          const Vec3f& eye, const Albedo& albedo, std::span<Rgb> out);
/// CPCA vectors from this frame's projections (cpca_vector_kernels.cpp).
void relightCpcaVectors(const Transfer& t, const ClusterLight& projected, const Albedo& albedo,
                        std::span<Rgb> out);
/// CPCA matrices (cpca_matrix_kernels.cpp).
void relightCpcaMatrices(const Transfer& t, const PreparedLight& light,
                         const PreparedMaterial& material, const Surface& surface, const Vec3f& eye,
                         const Albedo& albedo, std::span<Rgb> out);

struct AlignedFree {
  void operator()(float* p) const { std::free(p); }
};
/// A float array whose start is 32-byte aligned (for aligned 256-bit loads).
using AlignedFloats = std::unique_ptr<float[], AlignedFree>;

/// n zero floats, 32-byte aligned, rounded up to whole 32-byte blocks (also zero).
AlignedFloats alignedZeros(std::size_t n);

}  // namespace prt::relight::detail
