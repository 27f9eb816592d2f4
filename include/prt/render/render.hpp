#pragma once
// The offline PRT image renderer: per-vertex exit radiance (relight::relight) interpolated
// across each triangle with the hit's barycentrics, R(p) = (1−u−v) R_0 + u R_1 + v R_2 —
// exactly what a GPU's Gouraud shading of the relit mesh shows — over the environment (or its
// SH reconstruction, or a colour) seen through the camera, with stratified anti-aliasing
// (primary.hpp). Tone mapping and file writing belong to the image module (image_io.hpp).

#include <span>
#include <string>

#include "prt/envmap/environment.hpp"
#include "prt/render/primary.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/material.hpp"

namespace prt::render {

/// What is seen where camera rays miss the scene.
enum class Background { Env, Sh, None, Colour };
/// "env" | "sh" | "none" | a colour "r,g,b" (linear) or "#rrggbb" (sRGB); throws prt::Error.
Background parseBackground(const std::string& spec, Rgb* colour);

/// The environment as seen along `dir` after rotating it by R (a feature at d appears at R d):
/// L'(ω) = L(Rᵀ ω).
BackgroundFn environmentBackground(const envmap::Environment& env, const Mat3d& rotation);
/// The SH reconstruction of `light` rotated by R, clamped at zero (ringing can go negative).
BackgroundFn shBackground(const sh::RgbSh& light, const Mat3d& rotation);
BackgroundFn colourBackground(const Rgb& colour);
/// The background of `kind` under `rotation`: the environment image (`env`; with none, a light
/// file's, `light`'s SH reconstruction instead), the SH reconstruction of `light`, the colour,
/// or none (an empty function). Throws prt::Error when what the kind draws is not given
/// (`light` missing for Sh). One rule for prt render and Python's render.
BackgroundFn background(Background kind, const Rgb& colour, const envmap::Environment* env,
                        const sh::RgbSh* light, const Mat3d& rotation);

/// Throws Error(label, "the relit radiance at vertex N is not finite ...") for the first value
/// that is not: finite transfer times a finite light can still overflow float (CPCA weights of
/// 3e38), and inf − inf is NaN, which no tone map can show as anything but black. Call it on
/// relit radiance before rendering it.
/// `row` names what the values are of ("vertex"; "texel" for per-texel transfer).
void checkFiniteRadiance(std::span<const Rgb> radiance, const std::string& label,
                         const std::string& row = "vertex");

/// Shades a hit by barycentric interpolation of per-vertex radiance.
ShadeFn vertexRadianceShader(const Mesh& mesh, std::span<const Rgb> radiance);

/// Shades a hit from a lightmap of relit radiance (per-texel transfer relit row by row: W·H
/// values, texel (x, y) at y·W + x) — the hit's lightmap UV interpolated with its barycentrics,
/// the lightmap fetched bilinearly there (texel centres at ((x + ½)/W, (y + ½)/H), clamped at
/// the edges, as a GPU samples a texture) — times the albedo interpolated the same way
/// (`albedo`: one per vertex, or empty for white). Since relighting is linear in the transfer,
/// fetching relit radiance equals relighting the fetched coefficients: exactly the fragment
/// shader's per-pixel dot product. Throws prt::Error unless the mesh has lightmap UVs and the
/// sizes match.
ShadeFn texelRadianceShader(const Mesh& mesh, std::span<const Rgb> radiance, int width, int height,
                            std::span<const Rgb> albedo);
/// The albedo texelRadianceShader multiplies, the one rule for every per-texel image: the mesh's,
/// unless the material sets kd (then relighting applied it already: empty). The base-colour
/// texture follows the same rule, for every image (pixelTexture, base_colour.hpp).
inline std::span<const Rgb> texelAlbedo(const Mesh& mesh, const Material& material) {
  return material.diffuse ? std::span<const Rgb>() : std::span<const Rgb>(mesh.albedo);
}

/// Renders the relit mesh. `radiance` holds one value per mesh vertex (throws otherwise).
image::Image renderRelit(const Mesh& mesh, const Occluder& occluder, std::span<const Rgb> radiance,
                         const Camera& camera, const FrameSettings& settings,
                         const BackgroundFn& background, const ProgressFn& progress = {});

/// Tiles equally sized frames into a grid `columns` wide (0: about square), row by row, with a
/// `gap`-pixel border of `gapColour` between and around them.
image::Image contactSheet(std::span<const image::Image> frames, int columns = 0, int gap = 2,
                          const Rgb& gapColour = Rgb(0.0f));

}  // namespace prt::render
