#pragma once
// How a lightmap's gutter takes the rows of a basis (geometry/texel_sampling.hpp's dilation), the
// one rule for the bake (transport/texel_domain) and for the points the rows are relit at
// (render/texel_points.hpp): SH rows are linear and take their neighbours' mean; a Haar row is a
// record — its kind and sparse (index, value) pairs (transfer/haar_rows.hpp) — which a mean would
// scramble, so a gutter texel copies one neighbour's row whole, and is relit at that
// neighbour's point.

#include "prt/geometry/texel_sampling.hpp"
#include "prt/transfer/shape.hpp"

namespace prt {

inline TexelDilation rowDilation(TransferBasis basis) {
  return basis == TransferBasis::Haar ? TexelDilation::CopyFirst : TexelDilation::Mean;
}

}  // namespace prt
