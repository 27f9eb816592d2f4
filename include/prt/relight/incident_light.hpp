#pragma once
// The light arriving at each row of a matrix (glossy) transfer: the SH of the incident radiance
// L'_p = M_p L (Sloan, Kautz & Snyder 2002, §6; transfer/shape.hpp gives M_p's layout), under a
// light rotated on its coefficients (sh::Rotation) as relight() rotates it. What an engine's
// irradiance lightmap is made from (io/engine_lightmaps.hpp, prt export --format lightmap-sh):
// a diffuse (vector) transfer has already integrated the light against the normal, so it holds
// one number per colour where the engine wants the light's directional content.
//
// Row p, coefficient i (of `bands` bands, i = l(l+1) + m), colour c:
//
//   L'_p,i,c = Σ_j (M_p)_ij,c L_j,c     j over the light's and the transfer's common bands
//
// (a scalar transfer uses its one channel for r, g and b). The light's missing bands count as
// zero; its bands beyond the transfer's meet no column and are cut (relight.hpp's rule).

#include <vector>

#include "prt/core/vec.hpp"
#include "prt/relight/relight.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

/// L'_p for every row of `matrices` (dense or CPCA, any domain), `bands`² RGB coefficients per
/// row, row-major (rows × bands²). `bands` must be 1..matrices.bands(). Parallel over the rows,
/// independent of the thread count. `info` (if given) says how the light's bands were met.
/// Throws prt::Error for a vector transfer or `bands` out of range.
std::vector<Rgb> incidentLight(const Transfer& matrices, const sh::RgbSh& light, int bands,
                               const Mat3d& rotation = Mat3d::identity(),
                               RelightInfo* info = nullptr);

}  // namespace prt::relight
