#pragma once
// Relighting Haar transfer (prt/transfer/shape.hpp's Haar basis; Ng, Ramamoorthi & Hanrahan
// 2003, §6): exit radiance per row, the unshadowed part from the light's SH in closed form less
// the occlusion as the product of two sparse vectors of wavelet coefficients,
//     R(p) = kd(p) ⊙ ( Σ_lm (A_l/π) L_lm Y_lm(n_p) − Σ_t D̃_t(p) L̃[k_t(p)] )
// over the row's `terms` pairs (k_t, D̃_t), against the light's K terms laid out densely (6 N² RGB
// values, zeros where no term is kept: 72 KiB at N = 32, resident in cache while every row walks
// its pairs) and its kUnshadowedBands-band SH. Organised by row, not by light coefficient as the
// paper's loop was: each row's pairs are contiguous, each output written once, and the cost is
// one gather per kept transfer term whatever K, plus the SH of the normal (docs/performance.md).

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
