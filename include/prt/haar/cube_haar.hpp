#pragma once
// The all-frequency basis: orthonormal 2D Haar wavelets over the six faces of a cube map (Ng,
// Ramamoorthi & Hanrahan, "All-Frequency Shadows Using Non-linear Wavelet Lighting
// Approximation", SIGGRAPH 2003, §4), the basis prtkit offers beside spherical harmonics.
//
// The cube. Six N×N faces (N = the resolution, a power of two) in the order and orientation of
// envmap/layout.hpp (OpenGL: +X −X +Y −Y +Z −Z; texel (x, y) of face f looks along
// cubeFaceDirection(f, s, t), s = 2(x + ½)/N − 1, t = 2(y + ½)/N − 1). Texel index
// j = f·N² + y·N + x. A function f(ω) on the sphere is represented by one number per texel.
//
// What the numbers are. Lighting is stored as the texel's mean radiance, L_j = (1/Ω_j)∫_j L dω;
// diffuse transfer as the texel's integral, T_j = (1/π)∫_j V(ω) max(n·ω, 0) dω, so that exit
// radiance is ρ Σ_j L_j T_j — exact for light constant over each texel, which is what the cube
// map holds (Ng et al. eq. 2, with the solid angle folded into T as they fold it).
//
// The wavelets. Each face is transformed on its own by the non-standard 2D Haar decomposition
// (Stollnitz, DeRose & Salesin, "Wavelets for Computer Graphics", 1995, §2.2.2): at each level
// every 2×2 block (a b / c d) becomes
//     (a + b + c + d)/2  (scaling)   (a − b + c − d)/2  (horizontal detail)
//     (a + b − c − d)/2  (vertical)   (a − b − c + d)/2  (diagonal)
// the scalings going on to the next level, laid out in the usual pyramid: level h (the h×h
// block of scalings it is made from, h = N/2 … 1) puts its details at (h + i, j), (i, h + j) and
// (h + i, h + j), and the face's one scaling coefficient ends at (0, 0). Every step is a product
// of 4×4 orthonormal blocks, so the whole transform W is orthonormal: Σ_j L_j T_j = Σ_k L̃_k T̃_k
// for L̃ = W L, T̃ = W T (Parseval) — relighting is a dot product of wavelet coefficients, and a
// product of two sparse vectors when both are approximated by their largest terms. Coefficient
// k keeps the index of its pyramid position: face·N² + y·N + x.

#include <cstddef>
#include <cstdint>
#include <string>

#include "prt/core/vec.hpp"
#include "prt/haar/resolution.hpp"

namespace prt::haar {

/// Throws prt::Error("WHAT: ...") unless `resolution` is a power of two in range
/// (resolution.hpp).
void checkResolution(int resolution, const std::string& what);

/// The orthonormal transform of a cube's 6 N² texel values (index as above), in place.
void forward(float* cube, int resolution);
void forward(double* cube, int resolution);
/// Its inverse (the transpose), in place.
void inverse(float* cube, int resolution);

/// The face, column and row of texel `index`.
struct CubeTexel {
  int face = 0, x = 0, y = 0;
};
CubeTexel cubeTexel(std::uint32_t index, int resolution);
/// The texel a unit (or any non-zero) direction falls in.
std::uint32_t texelOf(const Vec3f& direction, int resolution);

}  // namespace prt::haar
