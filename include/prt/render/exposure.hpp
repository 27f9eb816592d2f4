#pragma once
// The auto exposure of a relit mesh as a camera sees it: image::autoExposure (prt/image/
// exposure.hpp) of the pixels that show the mesh. prt render, view, web and demo all call this,
// so the stills, the viewer and the page open at the same exposure for the same bake, light and
// camera.

#include <span>
#include <string>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/image/color.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/primary.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::render {

/// The width of the image autoExposure looks at (its height follows the aspect): enough pixels
/// for a stable 98th percentile, a few milliseconds of rays.
inline constexpr int kExposureProbeWidth = 256;

/// The radiance at the centre of every pixel of a width × height image whose ray hits the mesh
/// (barycentric interpolation of per-vertex `radiance`, as renderRelit), row by row.
std::vector<Rgb> modelPixels(const Mesh& mesh, const Occluder& occluder,
                             std::span<const Rgb> radiance, const Camera& camera, int width,
                             int height);
/// The same for any shading of the mesh (render.hpp's shaders: per-vertex or per-texel radiance).
std::vector<Rgb> modelPixels(const Occluder& occluder, const ShadeFn& shade, const Camera& camera,
                             int width, int height);
/// What the exposure probe sees of a frame: the auto exposure, and the share of the model's
/// pixels where some channel of the radiance is negative — SH ringing (a light or transfer cut
/// to few bands dipping below zero around a bright, small source), which the tone mappers draw
/// black.
struct FrameSurvey {
  float exposureStops = 0;
  double negativeShare = 0;
};

/// The share of the model's pixels above which prt render, view and web warn (issue 35): a few
/// dark pixels at a terminator are the method; more is an artefact the user can remove.
inline constexpr double kNegativeShareWarned = 0.02;
/// The warning for `share` of the model's pixels negative ("" at or below kNegativeShareWarned),
/// naming the remedies (a window on the light, fewer bands).
std::string negativeRadianceWarning(double share);

/// image::autoExposure of modelPixels at kExposureProbeWidth × (its aspect's height), for an
/// image of `width` × `height` seen through `camera` and tone-mapped with `op`.
float autoExposure(const Mesh& mesh, const Occluder& occluder, std::span<const Rgb> radiance,
                   const Camera& camera, int width, int height, image::ToneMap op);
/// The same for any shading of the mesh.
float autoExposure(const Occluder& occluder, const ShadeFn& shade, const Camera& camera, int width,
                   int height, image::ToneMap op);
/// The auto exposure and the negative share of the same probe pixels.
FrameSurvey surveyFrame(const Occluder& occluder, const ShadeFn& shade, const Camera& camera,
                        int width, int height, image::ToneMap op);

/// surveyFrame of `transfer` relit on the CPU (relight::relight) under `light` rotated by
/// `rotation` with `material`, seen through `camera`: what prt view and prt web open at, from
/// the bake and light they show (an Embree occluder of the mesh is built for the probe rays).
/// `bands` > 0 cuts the transfer first, as the viewers' band control does. Per-texel transfer is
/// drawn as prt render draws it (texelRadianceShader).
FrameSurvey relitSurvey(const Mesh& mesh, const Transfer& transfer, const Material& material,
                        const sh::RgbSh& light, const Mat3d& rotation, const Camera& camera,
                        int width, int height, image::ToneMap op, int bands = 0);

}  // namespace prt::render
