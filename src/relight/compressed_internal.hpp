#pragma once
// Shared by the compressed-relighting sources (compressed.cpp, compressed_diffuse.cpp,
// compressed_glossy.cpp); not installed.

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <memory>

#include "prt/relight/compressed.hpp"

namespace prt::relight {

/// Throws prt::Error unless the light's bands, the transfer's arrays, the output and the albedo
/// (one per vertex, one, or none) fit together.
void checkCompressedShapes(const CompressedTransfer& t, const PreparedLight& light,
                           std::size_t outSize, std::size_t albedoSize);

/// Whether this CPU runs AVX2 and FMA (the compressed kernels' SIMD paths), checked once.
bool cpuHasAvx2Fma();

struct AlignedFree {
  void operator()(float* p) const { std::free(p); }
};
/// A float array whose start is 32-byte aligned (for aligned 256-bit loads).
using AlignedFloats = std::unique_ptr<float[], AlignedFree>;

/// n zero floats, 32-byte aligned, rounded up to whole 32-byte blocks (also zero).
AlignedFloats alignedZeros(std::size_t n);

}  // namespace prt::relight
