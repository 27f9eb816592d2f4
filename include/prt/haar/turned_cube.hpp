#pragma once
// A Haar light turned by a viewer that holds the environment's cube rather than the environment
// (the browser page and prtkit-three: web/src/haar_light.js is this file in JavaScript, and
// tests/web holds the two to each other). Made once per environment: its texel means over a cube
// kFineCubeFactor times finer than the transfer's, M = 4N a side, and its SH at kUnshadowedBands.
// At each turn R of the light: the N cube's means gathered from the fine one, then the K largest
// terms and the unshadowed part as projectLight makes them (haar/project_light.hpp).
//
// Gathering. Texel j of the N cube is the solid-angle-weighted mean of its (M/N)² sub-texels
// (the fine cube's texels it covers), each taking the fine cube's value at its centre's turned
// direction Rᵀd: looked up bilinearly within the face that direction falls on (the four nearest
// texel centres, clamped at the face's edges). Unturned, every lookup lands on a fine texel's
// own centre and the means are exactly the fine cube's averaged — cubeMeans at N wherever cubeMeans
// at M nests in it (a splatted environment, a sun's disc). Turned, a bilinear tent sampled on a
// grid of the fine texels' own spacing sums to one, so a sun no wider than a fine texel keeps its
// power to first order wherever it lands (docs/haar.md measures the light against projectLight).

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

/// The means of the N = `resolution` cube of the environment turned by `rotation`, gathered
/// (the header). Throws prt::Error unless M is a multiple of N and the cube is whole.
std::vector<Rgb> turnCubeMeans(const EnvironmentCube& cube, int resolution, const Mat3d& rotation);

/// The light a Haar bake over an N cube is relit with, turned by `rotation`: approximate() of
/// the gathered means and unshadowedPart() of the cube's SH.
HaarLight turnedLight(const EnvironmentCube& cube, int resolution, std::size_t terms,
                      const Mat3d& rotation = Mat3d::identity(),
                      Selection selection = Selection::AreaWeighted);

}  // namespace prt::haar
