#pragma once
// A Haar light turned by a viewer that holds the environment's cube rather than the environment
// (the browser page and prtkit-three: web/src/haar_light.js is this file in JavaScript, and
// tests/web holds the two to each other). Made once per environment: its texel means over a cube
// kFineCubeFactor times finer than the transfer's, M = 4N a side, and its SH at kUnshadowedBands.
// At each turn R of the light: the N cube's means splatted from the fine one, then the K largest
// terms and the unshadowed part as projectLight makes them (haar/project_light.hpp).
//
// Turning. The fine cube's texels are splatted, as cubeMeans splats a tabulated environment's:
// each fine texel's power L·Ω, in kSplatPoints² equal parts at points spread over it, goes to the
// coarse texel the turn R sends each point to (R d), and each coarse texel's sum is divided by its
// exact solid angle. Power is kept exactly, a sun's included wherever it lands; unturned, every
// point stays in its own coarse texel and the means are exactly the fine cube's averaged. Turned,
// a coarse texel takes the 64 points its area covers give or take a few (a constant
// environment's means scatter by up to 12%), which relighting averages away: on the sphere over a
// plane under builtin:sky the relit radiance is projectLight's to 0.05% (4² points: 0.4%;
// measured: tests/haar/test_turned_cube.cpp). Gathering bilinear lookups of the fine cube instead
// (no scatter, power not kept) was 6% off.

#include <cstddef>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/envmap/environment.hpp"
#include "prt/haar/haar_light.hpp"
#include "prt/haar/project_light.hpp"
#include "prt/sh/sh.hpp"

namespace prt::haar {

/// The fine cube's side over the transfer's.
inline constexpr int kFineCubeFactor = 4;
/// Points per side each fine texel is splatted by.
inline constexpr int kSplatPoints = 2;
/// The largest transfer cube a turned light is made for: its fine cube holds 6 (4N)² texels
/// (1.5 MB as RGBE at N = 64, what the page carries per environment).
inline constexpr int kMaxTurnedResolution = 64;

/// What a viewer keeps of an environment to turn Haar lights from it.
struct EnvironmentCube {
  int resolution = 0;      ///< M, the fine cube's side
  std::vector<Rgb> means;  ///< its 6 M² texel means (cube_haar.hpp's order), unturned
  sh::RgbSh sh;            ///< the environment's SH at kUnshadowedBands, unturned
};

/// The cube of `env` for lights over an N = `lightResolution` cube (M = kFineCubeFactor · N).
/// Throws prt::Error unless N is a valid resolution ≤ kMaxTurnedResolution.
EnvironmentCube environmentCube(const envmap::Environment& env, int lightResolution);

/// The means of the N = `resolution` cube of the environment turned by `rotation`, splatted
/// (the header). Throws prt::Error unless M is a multiple of N and the cube is whole.
std::vector<Rgb> turnCubeMeans(const EnvironmentCube& cube, int resolution, const Mat3d& rotation);

/// The light a Haar bake over an N cube is relit with, turned by `rotation`: approximate() of
/// the turned means and unshadowedPart() of the cube's SH.
HaarLight turnedLight(const EnvironmentCube& cube, int resolution, std::size_t terms,
                      const Mat3d& rotation = Mat3d::identity(),
                      Selection selection = Selection::AreaWeighted);

}  // namespace prt::haar
