#include "prt/core/sampling.hpp"

namespace prt {

OwenSobol2D::OwenSobol2D(std::uint32_t n) : rev1_(n) {
  // Gray-code order would be cheaper, but the table is built once per bake and must hold the
  // points in natural order (prefixes of length 2^m are then (0,m,2)-nets).
  for (std::uint32_t i = 0; i < n; ++i) rev1_[i] = reverseBits(sobol1(i));
}

}  // namespace prt
