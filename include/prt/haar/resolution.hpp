#pragma once
// The sizes of the Haar basis (cube_haar.hpp), header-only so that a transfer's shape can state
// and check them without linking the basis.

#include <bit>
#include <cstddef>

namespace prt::haar {

/// Cube resolutions the basis accepts: powers of two in [kMinResolution, kMaxResolution].
inline constexpr int kMinResolution = 2;
inline constexpr int kMaxResolution = 256;

constexpr bool validResolution(int n) {
  return n >= kMinResolution && n <= kMaxResolution && (n & (n - 1)) == 0;
}

/// Texels (and wavelet coefficients) of a cube of this resolution: 6 N².
constexpr std::size_t coefficientCount(int resolution) {
  return std::size_t(6) * std::size_t(resolution) * std::size_t(resolution);
}

/// Side, in texels, of the square on its face that wavelet coefficient `index` (face·N² + y·N +
/// x, cube_haar.hpp's pyramid) is supported on: N for the face's scaling coefficient and its
/// coarsest details, down to 2 for the finest.
constexpr int supportSide(std::size_t index, int resolution) {
  const std::size_t n = std::size_t(resolution), r = index % (n * n);
  const std::size_t x = r % n, y = r / n, m = x > y ? x : y;
  if (m == 0) return resolution;
  // The level's block: details of level h sit in [h, 2h), h the highest power of two ≤ m.
  return int(n / std::bit_floor(m));
}

}  // namespace prt::haar
