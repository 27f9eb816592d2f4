#pragma once
// A row of Haar transfer as prtkit stores it: the `terms` wavelet coefficients of the row with
// the largest |c|·s, s the side of the coefficient's support in texels (the transfer pruned per
// row to a budget, Ng, Ramamoorthi & Hanrahan 2003 §5, who keep the largest |c|). Weighting by
// the support favours coarse terms a little, as the paper's area weighting of the light does:
// measured on the sphere over a plane under builtin:sky (docs/validation.md), it lowers the
// relit error at 25 terms from 8.1% to 5.8% (|c| s² overshoots: 9.7% at 12 terms against 7.6%).
// They are stored as `terms` pairs of floats (index, value) in ascending index. The index is
// held as a float, exactly (6 N² ≤ 393,216 < 2²⁴), so the row is plain floats that every split,
// merge and file of the bake moves unchanged. A row with fewer non-zero coefficients than its budget ends in
// pairs (0, 0), which add nothing.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace prt::haar {

/// The quantisation grid's steps each side of 0.
inline constexpr int kHaarValueSteps = 32767;
/// q for v on the grid of scale s (s > 0), and back: v = s·q/32767, computed once, one way.
int quantizeHaarValue(float value, float scale);
float dequantizeHaarValue(float scale, int q);
/// Bytes of one row in a bake file: the scale, and per term its index (2 bytes while 6 N² ≤
/// 65,536, else 4) and its 16-bit value.
std::size_t storedHaarRowBytes(int resolution, int terms);

/// Keeps the `terms` largest |coeffs[k]|·supportSide(k) of the 6 N² wavelet coefficients (ties
/// to the lower index; zeros never kept), quantised as above, and writes them to out[0 .. 2·terms) as above. `order` is scratch.
void pruneRow(const float* coeffs, int resolution, std::size_t terms, float* out,
              std::vector<std::uint32_t>& order);

/// Throws prt::Error("WHAT: row R: ...") unless every pair of the row has an integral index
/// below 6 N² and a finite value, the indices of its non-zero values ascend, and padding (value
/// 0) has index 0.
void checkRow(const float* row, int resolution, std::size_t terms, std::size_t rowIndex,
              const std::string& what);

}  // namespace prt::haar
