#pragma once
// Primary rays, in one place for every renderer (the PRT image renderer here, a Monte Carlo
// reference beside it): for each pixel, `spp` jittered sub-pixel positions, a ray through each,
// the closest hit (Occluder::intersect), and the average of what the shader returns for a hit
// or the background for a miss (a box filter over the pixel).
//
// Sub-pixel positions are an Owen-scrambled Sobol' (0,2)-sequence per pixel (core/sampling.hpp):
// every power-of-two prefix is stratified in both axes (one sample per elementary interval), the
// scramble seed is a hash of (seed, pixel), so an image depends on its inputs and seed only —
// never on the thread count — and neighbouring pixels do not share a pattern.

#include <cstdint>
#include <functional>

#include "prt/core/progress.hpp"
#include "prt/image/image.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/camera.hpp"

namespace prt::render {

/// Radiance leaving the hit surface toward the camera (−ray.dir).
using ShadeFn = std::function<Rgb(const Ray& ray, const Hit& hit)>;
/// Radiance arriving from the environment along direction `dir` (unit), seen through the camera.
using BackgroundFn = std::function<Rgb(const Vec3f& dir)>;

struct FrameSettings {
  int width = 640;
  int height = 480;
  int spp = 4;             ///< samples per pixel (≥ 1)
  std::uint32_t seed = 0;  ///< decorrelates the jitter between renders
};

/// Throws prt::Error("image size WxH ...") for sizes ≤ 0 or absurd (> 16384 per side), or spp ≤ 0.
void checkFrameSettings(const FrameSettings& settings);

/// The k-th sub-pixel offset in [0, 1)² of pixel (x, y).
Vec2f subpixelOffset(const FrameSettings& settings, int x, int y, int k);

/// Renders the frame (rows in parallel). An empty `background` means black. Progress per row;
/// throws prt::Cancelled when the callback asks to stop.
image::Image tracePrimary(const Camera& camera, const FrameSettings& settings,
                          const Occluder& occluder, const ShadeFn& shade,
                          const BackgroundFn& background, const ProgressFn& progress = {});

/// Heuristic: true when the eye is inside a closed mesh, i.e. most of a few probe rays from the
/// eye hit triangles from behind (against their counter-clockwise front). False when nothing or
/// mostly front faces are hit.
bool eyeInsideMesh(const Mesh& mesh, const Occluder& occluder, const Vec3f& eye);

}  // namespace prt::render
