#pragma once
// The probe grid: the third domain of a transfer (issue 32) — points in space, not on a surface,
// where a bake stores how the distant light arrives (Sloan, Kautz & Snyder 2002, §7 "neighbourhood
// transfer"; shipped as relightable probes in Far Cry 3 and Bannerlord). One row per probe, a
// B² × B² matrix over the whole sphere of directions:
//
//   (M_p)_ij = ∫_{S²} Y_i(ω) V(p,ω) Y_j(ω) dω  (+ the light the scene's surfaces send to p),
//
// so the SH of the radiance arriving at p is L'_p = M_p L (a probe in open space has M = I).
//
// Layout: probe (x, y, z) at origin + (x·sx, y·sy, z·sz), row x + nx·(y + ny·z) (x fastest, as
// three.js's LightProbeGrid and a 3D texture store it). The probes sit at the centres of the
// cells of the bounds they were made for (makeProbeGrid), never on the bounds' faces, which are
// often a scene's walls.

#include <array>
#include <cstddef>
#include <string>

#include "prt/core/vec.hpp"

namespace prt {

/// Probes per axis, at most (and kMaxProbes in all): a 512³ grid would be 134 M rows.
inline constexpr int kMaxProbeSide = 512;
inline constexpr std::size_t kMaxProbes = std::size_t(1) << 24;
/// Cells along the longest side of an automatic grid (makeProbeGrid with no counts).
inline constexpr int kAutoProbeCells = 16;

struct ProbeGrid {
  Vec3f origin{0.0f};   ///< probe (0, 0, 0)
  Vec3f spacing{1.0f};  ///< between neighbours along x, y, z (> 0)
  std::array<int, 3> count{0, 0, 0};

  std::size_t probes() const {
    return std::size_t(count[0]) * std::size_t(count[1]) * std::size_t(count[2]);
  }
  /// The probe of row r (x + nx·(y + ny·z)).
  std::array<int, 3> cell(std::size_t r) const {
    const std::size_t nx = std::size_t(count[0]), ny = std::size_t(count[1]);
    return {int(r % nx), int((r / nx) % ny), int(r / (nx * ny))};
  }
  std::size_t row(int x, int y, int z) const {
    return std::size_t(x) + std::size_t(count[0]) * (std::size_t(y) + std::size_t(count[1]) * z);
  }
  Vec3f position(std::size_t r) const {
    const auto c = cell(r);
    return origin + spacing * Vec3f(float(c[0]), float(c[1]), float(c[2]));
  }
  /// "8 x 4 x 8 probes, 0.25 apart" (one spacing when all three agree).
  std::string describe() const;
  bool operator==(const ProbeGrid&) const = default;
};

/// The grid over the box [lo, hi]: counts[a] cells along axis a, a probe at each cell's centre;
/// a count of 0 (all three 0: an automatic grid) gives cells of the longest side / kAutoProbeCells
/// along that axis (one cell across a flat side). Throws prt::Error naming `what` on bounds that
/// are not finite or inverted, or counts outside 0..kMaxProbeSide or over kMaxProbes in all.
ProbeGrid makeProbeGrid(const Vec3f& lo, const Vec3f& hi, std::array<int, 3> counts,
                        const std::string& what);

/// Throws prt::Error("WHAT: ...") unless the grid is one a bake could have made: counts in
/// 1..kMaxProbeSide and kMaxProbes in all, origin finite, spacings finite and > 0.
void checkProbeGrid(const ProbeGrid& grid, const std::string& what);

}  // namespace prt
