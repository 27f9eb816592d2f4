#pragma once
// Environment → SH: L_i = ∫ L(ω) Y_i(ω) dω ≈ Σ_texels L_k Y_i(ω_k) ΔΩ_k with ΔΩ_k the texel's
// exact solid angle (layout.hpp), so a constant environment projects to exactly √(4π)·c in L_00.
// Analytic environments: the smooth part is projected from its lat-long sampling, discs exactly
// (analytic.hpp).
//
// Evaluation uses the compile-time unrolled SH polynomials (sh/sh_fixed.hpp) and float
// accumulators over fixed chunks of 1024 texels, combined in double in chunk order: the result
// is independent of the thread count.

#include "prt/core/progress.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/sh/sh.hpp"

namespace prt::envmap {

/// Projects the environment onto `bands` bands (1..32). Progress is reported per chunk.
sh::RgbSh projectEnvironment(const Environment& env, int bands, const ProgressFn& progress = {});

/// The GAMES202 course framework's own cube-map projection (homework 2, prt.cpp), for
/// `--compat games202`: `faces` in the course's reading order negx, posx, posy, negy, posz, negz,
/// each paired in turn with these (U, V, C) frames:
///   ((0,0,1),(0,−1,0),(−1,0,0)), ((0,0,1),(0,−1,0),(1,0,0)), ((1,0,0),(0,0,−1),(0,−1,0)),
///   ((1,0,0),(0,0,1),(0,1,0)),   ((−1,0,0),(0,−1,0),(0,0,−1)), ((1,0,0),(0,−1,0),(0,0,1));
/// texel (x, y), y from the top row, looks along normalize(u U + v V + C) with
/// u = 2(x + 0.5)/w − 1, v = 2(y + 0.5)/h − 1, weighted by its exact solid angle. Note that this
/// pairs posy with −Y and posz with −Z: the course's quirk, kept on purpose.
sh::RgbSh projectGames202Faces(const std::array<image::Image, 6>& facesInCourseOrder, int bands,
                               const ProgressFn& progress = {});
/// The course's file reading order.
inline constexpr std::array<const char*, 6> kGames202FaceOrder = {"negx", "posx", "posy",
                                                                  "negy", "posz", "negz"};

}  // namespace prt::envmap
