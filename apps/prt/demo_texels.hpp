#pragma once
// prt demo's per-texel row (issue 18): the builtin Cornell box as a coarse mesh (2 × 2 quads a
// wall) baked inter-reflected per vertex and per texel (a 128² lightmap over its packed charts),
// and per vertex on the box tessellated to the lightmap's number of rows (the same bytes of
// transfer), each rendered and compared with the Monte Carlo reference of the same box,
// computed at the vertices of a fine tessellation and drawn the same way: the exact relighting
// under the light cut to the bake's bands (render/reference.hpp's band-limited lane: the errors
// are then the storage's, not the band limit's), and the brute force with no SH.

#include <string>

#include "prt/envmap/environment.hpp"
#include "prt/render/primary.hpp"

namespace prt::cli {

struct DemoArgs;

/// One way of storing the box's transfer, drawn.
struct TexelRowEntry {
  std::string label;  ///< "per vertex, coarse mesh (12 rows a wall)"
  std::string image;  ///< relative to the demo folder
  std::size_t rows = 0, bytes = 0;
  double relRmse = 0;      ///< against the band-limited reference image (model pixels)
  double relRmseFull = 0;  ///< against the full reference (the band limit's error included)
};

struct TexelRow {
  std::string environment;
  std::string referenceImage;      ///< the exact relighting at the bands (band-limited light)
  std::string fullReferenceImage;  ///< brute force, no SH
  int referenceVertices = 0, referenceSamples = 0;
  double referenceNoise = 0;  ///< its relative standard error, RMS over the vertices
  TexelRowEntry coarse, texels, dense;
  int resolution = 0, bands = 0;
  double seconds = 0;
};

/// Bakes, renders and measures the row under `env` (its SH at a.bands), writing img/texels_*.png
/// into `folder`.
TexelRow demoTexelRow(const envmap::Environment& env, const std::string& envName, const DemoArgs& a,
                      const render::FrameSettings& frame, const std::string& folder);

}  // namespace prt::cli
