#pragma once
// Projection onto SH: f_i = ∫ f(ω) Y_i(ω) dω.
//  * of a callable, by a product quadrature that is exact for band-limited functions:
//    Gauss–Legendre in cos θ (n nodes, exact for polynomials of degree 2n-1 in z) times 2n
//    equally spaced φ (exact for trigonometric polynomials of degree < 2n);
//  * of weighted samples: f_i = Σ_k w_k f(ω_k) Y_i(ω_k) (w_k = solid angle or 1/pdf/N).

#include <functional>
#include <span>
#include <vector>

#include "prt/sh/sh.hpp"

namespace prt::sh {

/// Nodes and weights of a product quadrature on the sphere; weights sum to 4π.
struct SphereQuadrature {
  std::vector<Vec3d> dirs;
  std::vector<double> weights;
};

/// Gauss–Legendre (n nodes in z) × uniform φ (2n nodes): integrates exactly every spherical
/// polynomial of degree ≤ 2n-1, i.e. products Y_i Y_j of bands < n.
SphereQuadrature gaussLegendreSphere(int n);

/// Projects a scalar function. `quadratureN` = 0 picks n = bands + 8 nodes in cos θ.
ShCoeffs projectFunction(int bands, const std::function<double(const Vec3d&)>& f,
                         int quadratureN = 0);
/// Projects an RGB function.
RgbSh projectFunctionRgb(int bands, const std::function<Rgbd(const Vec3d&)>& f,
                         int quadratureN = 0);

/// Projects weighted samples (dirs unit, weights in steradians or 1/(pdf·N)). Accumulates in
/// double in a fixed order, so the result is deterministic.
RgbSh projectSamples(int bands, std::span<const Vec3f> dirs, std::span<const Rgb> values,
                     std::span<const float> weights);

}  // namespace prt::sh
