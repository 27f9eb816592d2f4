#pragma once
// Diffuse exit radiance through an engine's irradiance encoding (issue 34; prt render
// --encoding): what a surface looks like when an engine shades it from the compact SH of
// sh/irradiance_encoding.hpp stored per vertex or per texel, instead of from PRT's full
// transfer.
//
//   f_p = kd_p ⊙ Ê_p(n_p) / π
//
// with L'_p = M_p L the light arriving at row p (incident_light.hpp, its bands 0..2: no encoding
// keeps more), Ê_p = evaluate(encodeIrradiance(L'_p, E), ·) its encoded irradiance as an engine
// reconstructs it (sh/encode_irradiance.hpp), n_p the row's unit normal (the vertex normal, or
// the texel's sample normal: render/texel_points.hpp) and kd_p the material's kd when it sets
// one, else the row's albedo (transfer/albedo.hpp) — relight()'s diffuse term of a matrix,
// kd (A_l/π) Y(n_p)·L'_p, with the exact irradiance replaced by the encoded one. So with l2 and a
// transfer of at most 3 bands the two are the same function (l2 is the irradiance of bands 0..2
// exactly); past 3 bands l2 leaves out band 4's irradiance (A₃ = 0, A₄/π = −1/24).
//
// Diffuse only: an encoding holds irradiance, which a view-dependent lobe cannot be shaded from.
// A glossy material is refused rather than silently drawn without its lobe.

#include <vector>

#include "prt/core/vec.hpp"
#include "prt/relight/relight.hpp"
#include "prt/sh/irradiance_encoding.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

/// f_p for every row of `matrices` (dense or CPCA, any domain) under `light` rotated by
/// `rotation`, through `encoding`. `surface.normals` holds one unit normal per row; its albedo
/// one per row, one, or none (white), replaced by the material's kd when it sets one. Parallel
/// over the rows, independent of the thread count. Throws prt::Error for a vector transfer, a
/// glossy material, or sizes that do not match.
std::vector<Rgb> encodedDiffuse(const Transfer& matrices, const sh::RgbSh& light,
                                sh::IrradianceEncoding encoding, const Material& material,
                                const Surface& surface, const Mat3d& rotation = Mat3d::identity(),
                                RelightInfo* info = nullptr);

}  // namespace prt::relight
