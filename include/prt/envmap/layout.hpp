#pragma once
// Environment-map layouts and their geometry: texel directions and exact texel solid angles.
//
// World frame: right-handed, +Y up.
//
// Lat-long (equirectangular, 2:1). Pixel (x, y) of a W×H image has its centre at
// u = (x + 0.5)/W, v = (y + 0.5)/H; polar angle from +Y θ = π v (top row looks up), azimuth
// φ = 2π (u − 1/2), direction (sin θ cos φ, cos θ, sin θ sin φ). So the centre column looks along
// +X, u = 1/4 looks along −Z, u = 3/4 along +Z and the left/right edges along −X: the mapping of
// Blender's equirectangular world texture (converted from Blender's Z-up by the glTF rule
// Y_up = Z_blender, Z_up = −Y_blender) and of three.js's equirectUv, so an HDRI looks the same
// here as in those viewers. Texel solid angle, exactly: Δφ (cos θ_top − cos θ_bottom),
// Δφ = 2π/W.
//
// Cube faces follow the OpenGL cube-map convention (OpenGL 4.6 spec §8.13, table 8.19), order
// +X −X +Y −Y +Z −Z, file names posx negx posy negy posz negz. Texel (x, y) of an N×N face (row
// 0 at the top of the file) has s = 2(x + 0.5)/N − 1, t = 2(y + 0.5)/N − 1 and looks along
//     +X: ( 1, −t, −s)   −X: (−1, −t,  s)   +Y: ( s,  1,  t)
//     −Y: ( s, −1, −t)   +Z: ( s, −t,  1)   −Z: (−s, −t, −1)    (then normalised).
// Texel solid angle, exactly: with A(a, b) = atan2(a b, sqrt(a² + b² + 1)) the solid angle of the
// face rectangle [0, a] × [0, b] at unit distance, a texel [a0, a1] × [b0, b1] subtends
// A(a1, b1) − A(a0, b1) − A(a1, b0) + A(a0, b0).
//
// Crosses are cut into the six faces above:
//     vertical cross (3:4)      horizontal cross (4:3)
//        . +Y .                    . +Y .  .
//       −X +Z +X                  −X +Z +X −Z
//        . −Y .                    . −Y .  .
//        . −Z .   (−Z rotated 180° so its edges meet −Y's)
//
// Angular light probe (1:1), Debevec's angular map ("Light Probe Image Gallery"): image
// coordinates (a, b) ∈ [−1, 1]², b up, r = sqrt(a² + b²) ≤ 1; the direction makes the angle π r
// with the forward axis −Z: d = (sin(πr) a/r, sin(πr) b/r, −cos(πr)). Texels outside the disc
// carry no solid angle. The area element is dω = π sin(πr)/r dA, and a texel's exact solid angle
// is computed by Green's theorem as the flux of the radial field (1 − cos(π min(r, 1)))/r² (x, y)
// through its four edges, each edge integrated by Gauss–Legendre split at the r = 1 crossing
// (smooth pieces, so the quadrature is exact to rounding); the texels' sum telescopes to 4π.

#include <array>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"

namespace prt::envmap {

enum class Layout { LatLong, Probe, VCross, HCross, Faces };

/// "latlong" | "probe" | "vcross" | "hcross" | "faces"; throws prt::Error otherwise.
Layout parseLayout(const std::string& name);
const char* layoutName(Layout layout);
/// The layout whose aspect ratio matches exactly (2:1, 1:1, 3:4, 4:3); throws prt::Error naming
/// `file` when none does.
Layout detectLayout(int width, int height, const std::string& file);

enum CubeFace { PosX = 0, NegX, PosY, NegY, PosZ, NegZ };
inline constexpr std::array<const char*, 6> kFaceNames = {"posx", "negx", "posy",
                                                          "negy", "posz", "negz"};

/// Unnormalised direction of face point (s, t) ∈ [−1, 1]² (OpenGL convention above).
Vec3d cubeFaceDirection(int face, double s, double t);
/// The face and (s, t) ∈ [−1, 1]² that direction `d` (any length > 0) hits.
int cubeFaceCoords(const Vec3f& d, float& s, float& t);
/// Exact solid angles of the N×N texels of one face (all six faces share them), row-major.
std::vector<double> cubeTexelSolidAngles(int n);

/// Direction of lat-long pixel centre (x + 0.5, y + 0.5) in a W×H image.
Vec3d latLongDirection(int width, int height, double x, double y);
/// Continuous pixel coordinates (pixel centres at +0.5) of direction d in a W×H lat-long image.
void latLongPixel(const Vec3f& d, int width, int height, float& px, float& py);

/// Direction of probe image point (a, b) ∈ disc (b up); `inside` false when r > 1.
Vec3d probeDirection(double a, double b, bool* inside = nullptr);
/// Exact solid angles of the W×H probe texels (0 outside the disc), row-major.
std::vector<double> probeTexelSolidAngles(int width, int height);

}  // namespace prt::envmap
