#pragma once
// Relighting Haar transfer (prt/transfer/shape.hpp's Haar basis; Ng, Ramamoorthi & Hanrahan
// 2003, §6): exit radiance per row from its sparse wavelet terms and the light's,
//     occluded-part row   R(p) = kd(p) ⊙ ( U(n_p)·L − Σ_t D̃_t(p) L̃[k_t(p)] )
//     visible-part row    R(p) = kd(p) ⊙ Σ_t T̃_t(p) L̃[k_t(p)]
// (an inter-reflected row adds its bounce in SH against the whole light's SH, haar::fullSh:
//  kd(p) ⊙ Σ_i B_i(p) L_i, inside the same kd),
// with U(n)·L = Σ_b L_b U_b(n) + Σ_lm (A_l/π) L'_lm Y_lm(n), the light's brightest texels exactly
// and the rest in SH (haar/haar_light.hpp), against the light's K terms laid out densely (6 N²
// RGB values, zeros where no term is kept: 72 KiB at N = 32, resident in cache while every row
// walks its pairs). Organised by row, not by light coefficient as the paper's loop was: each
// row's pairs are contiguous, each output written once, and the cost is one gather per kept
// transfer term whatever K, plus, for an occluded-part row, the SH of its normal and the bright
// texels' cosine integrals. The paper's loop does the product alone in 0.30–0.45 of the time
// (a light term meets only the rows keeping its coefficient), but needs the rows held again,
// transposed, and the product is a third of the whole (bench BM_HaarProductOrder;
// docs/performance.md).

#include <span>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

/// out[r] = the radiance of row r (the formula above) under `light`, whose cube must be the
/// transfer's; `normals` one unit normal per row; `albedo` one per row, one, or none (white;
/// transfer/albedo.hpp). Throws prt::Error on a transfer that is not Haar, another cube
/// resolution, mismatched sizes or a row naming a coefficient outside the cube.
void relightHaar(const Transfer& transfer, const haar::HaarLight& light,
                 std::span<const Vec3f> normals, std::span<const Rgb> albedo, std::span<Rgb> out);
std::vector<Rgb> relightHaar(const Transfer& transfer, const haar::HaarLight& light,
                             std::span<const Vec3f> normals, std::span<const Rgb> albedo);

}  // namespace prt::relight
