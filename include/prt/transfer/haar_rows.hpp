#pragma once
// A row of Haar transfer as prtkit stores it (transfer/shape.hpp's Haar basis).
//
// What a row holds: one of the two halves of diffuse transfer over the cube's texels, whichever
// is the smaller — the occluded part D_j = U_j − T_j (kind Occluded) for a row that sees more
// than half of its cosine-weighted sky, else the visible part T_j itself (kind Visible). A
// mostly open vertex then stores its shadow and a mostly closed one its window on the sky: both
// are the small, sparse half, and a row never relights as the small difference of two large
// sums (the unshadowed light less the occluded one) where the two sums hold the light
// differently (docs/haar.md measures what that cost).
//
// Pruned: the `terms` wavelet coefficients with the largest |c|·s, s the side of the
// coefficient's support in texels (Ng, Ramamoorthi & Hanrahan 2003 §5 keep the largest |c|).
// Weighting by the support favours coarse terms a little, as the paper's area weighting of the
// light does: measured on the sphere over a plane under builtin:sky (docs/haar.md), it lowers the
// relit error at 25 terms from 8.1% to 5.8% (|c|·s² overshoots).
//
// Held as 1 + 2·terms floats: the kind (0 occluded, 1 visible), then `terms` pairs (index, value)
// in ascending index. The index is held as a float, exactly (6 N² ≤ 393,216 < 2²⁴), so the row is
// plain floats that every split, merge and pass of the bake moves unchanged. A row with fewer
// non-zero coefficients than its budget ends in pairs (0, 0), which add nothing.
//
// Quantised (Ng et al. quantise theirs too): the kept values lie on a 16-bit grid of the row's
// largest |value| s, v = s·q/32767 with q an integer in [−32767, 32767], so that a bake file holds
// them exactly in 4 bytes a term and 5 a row (s and the kind, then per term a 16-bit index —
// 32-bit for cubes past 6·104² coefficients — and q; docs/formats-bake.md): a row in memory is
// what its file holds, bit for bit. The grid's step is s/32767; a term that rounds to 0 is
// dropped.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace prt::haar {

/// Which half of the transfer a row holds (its first float).
enum class HaarRowKind : int {
  Occluded = 0,  ///< D = U − T: relit as the unshadowed light less D̃·L̃
  Visible = 1,   ///< T: relit as T̃·L̃
};
/// A row holds the visible part once more than this share of its cosine-weighted sky is
/// occluded (Σ_j D_j, since Σ_j U_j = 1).
inline constexpr double kVisibleRowAbove = 0.5;

/// Floats of a row: the kind and `terms` pairs.
constexpr std::size_t haarRowFloats(int terms) {
  return 1 + 2 * static_cast<std::size_t>(terms < 0 ? 0 : terms);
}

/// The quantisation grid's steps each side of 0.
inline constexpr int kHaarValueSteps = 32767;
/// q for v on the grid of scale s (s > 0), and back: v = s·q/32767, computed once, one way.
int quantizeHaarValue(float value, float scale);
float dequantizeHaarValue(float scale, int q);
/// Bytes of one row in a bake file: the scale and the kind, and per term its index (2 bytes
/// while 6 N² ≤ 65,536, else 4) and its 16-bit value.
std::size_t storedHaarRowBytes(int resolution, int terms);

/// Writes the row of `kind` into out[0 .. haarRowFloats(terms)): the `terms` largest
/// |coeffs[k]|·supportSide(k) of the 6 N² wavelet coefficients (ties to the lower index; zeros
/// never kept), quantised, in ascending index. `keys` is scratch.
void pruneRow(const float* coeffs, int resolution, std::size_t terms, HaarRowKind kind,
              float* out, std::vector<std::pair<float, std::uint32_t>>& keys);

/// Throws prt::Error("WHAT: row R: ...") unless the row's kind is 0 or 1, every pair has an
/// integral index below 6 N² and a finite value, the indices of its non-zero values ascend, and
/// padding (value 0) has index 0.
void checkRow(const float* row, int resolution, std::size_t terms, std::size_t rowIndex,
              const std::string& what);

}  // namespace prt::haar
