#pragma once
// Relit lightmaps for engines that do not run PRT (issue 34; prt export --format lightmap and
// --format lightmap-sh): a per-texel bake relit under one light, written as the textures an
// engine's own lightmap shader samples. docs/lightmaps.md gives every layout with its source.
//
// What is stored is the light *arriving* at each texel, without the surface's albedo — what
// engines call a lightmap, and multiply by the albedo themselves: the exit radiance of a white
// Lambertian surface, f(n) = E(n)/π, with E(n) = ∫ L'(ω) max(n·ω, 0) dω the irradiance of the
// texel's incident light L' at a normal n. Godot (`ambient_light *= albedo`, after the lightmap
// is added to ambient_light) and Unity (`diffColor * gi.diffuse`) both multiply by the albedo.
//
//   lightmap      one RGB float EXR: f(n_p) at each texel (a vector bake's R/albedo = Σ T_i L_i;
//                 a matrix bake's diffuse part d(n_p)·L'_p), and an 8-bit sRGB PNG preview.
//   lightmap-sh   the irradiance of L'_p in one of sh/irradiance_encoding.hpp's encodings, in
//                 the layouts below. In the decodes, A and c are the L1 part of f in world
//                 (glTF) axes, f(n) ≈ A + c·n: A = E₀₀ Y₀₀ / π, c = 0.488603 v(E₁) / π with
//                 v(E₁) = (−E₁₁, −E₁₋₁, E₁₀) (prtkit's basis has the Condon–Shortley phase;
//                 sh::bandOneVector).
//
// Engine layouts of the L1 part (all rows top-down: image row 0 is v = 0 of the lightmap UVs,
// glTF TEXCOORD_1, as Godot's UV2 and Unity's flipped importers read it):
//
//   godot       Godot 4.4+ LightmapGI "directional" (SH L1), packed L1 (godot PR #96114):
//               godot.exr, W × 4H, RGB float, four layers stacked down the image (an imported
//               Texture2DArray with slices/vertical = 4, as LightmapGI saves its atlas:
//               scene/3d/lightmap_gi.cpp): L0 = A; L1n1, L1_0, L1p1 = c_y, c_z, c_x each
//               stored as c/(8A) + ½, clamped to [0, 1] (modules/lightmapper_rd/
//               lm_compute.glsl, MODE_PACK_L1_COEFFS). Decoded (scene_forward_clustered.glsl):
//               f = L0 + 4 L0 ((l1n1 − ½)·2 n_y + (l1_0 − ½)·2 n_z + (l1p1 − ½)·2 n_x).
//   godot-4.3   Godot 4.0–4.3, unpacked: the same four layers holding A / 0.282095 and
//               c_y, c_z, c_x / 0.32573; decoded f = 0.282095 L0 + 0.32573 (L1n1 n_y + L1_0 n_z +
//               L1p1 n_x).
//   bakery      Unity with Bakery's "SH" directional mode: bakery-L0.exr (the lightmap,
//               unity_Lightmap) = A, and bakery-L1x/y/z.exr (_RNM0, _RNM1, _RNM2) = c_k/(4A) + ½
//               clamped to [0, 1], in Unity's axes (x negated: Unity is left-handed and
//               UnityGLTF's import mirrors x). Decoded (Bakery.cginc, BakerySH):
//               f = L0 + Σ_k n_k (2 t_k − 1) · 2 L0.
//
// The packed forms hold |c_k| up to 4A (Godot) or 2A (Bakery): the L1 irradiance of any
// non-negative light stays within |c| ≤ 2A. A channel beyond that (a light that rings below
// zero, or a Monte Carlo matrix's noise) has its c scaled down as a whole until it fits — its
// direction kept, where the engines' packers clamp each component — and one with A ≤ 0 loses
// its L1; such texels are counted (clampedTexels).
//
// prtkit's own layouts for what no engine ships (the decode adds to the L1 part's A + c·n):
//
//   zh3.exr        k (RGB): f += k (3 (a·n)² − 1), k = z √(5/16π) / π with z the zonal
//                  coefficient (zh3, zh3-shared, zh3-optimal; Roughton et al., "ZH3: Quadratic
//                  Zonal Harmonics", I3D 2024). The axis a is the luminance's band-1 direction,
//                  normalize(Σ_c w_c c_c) with Rec. 709 weights (+Z when zero), so the engine
//                  derives it from the L1 layers; zh3-shared and zh3-optimal store it instead,
//                  zh3-axis.exr (RGB = a, glTF axes). zh3-shared's k is s A per channel (one s a
//                  texel: an engine stores s alone). zh3-hallucinated stores nothing more: per
//                  channel r = (√3/2) |c·a| / A and k = A (√5/8)(0.08 r + 0.6 r²) (A > 0, else 0).
//   l2.exr         W × 9H, RGB float: layer i = E_i / π (i = l(l+1) + m, prtkit's basis);
//                  f = Σ_i layer_i Y_i(n) (l2, l2-deringed).
//   l1-geomerics   the L1 layers alone, decoded with Hazel's non-linear form (Geomerics 2014):
//                  f = A (α + (1 − α)(p + 1) q^p), s = min(|c|/2A, 1), p = 1 + 2s,
//                  α = (1 − s)/(1 + s), q = (1 + ĉ·n)/2 (per channel, as sh::evaluate does).
//
// A manifest, lightmap.json, says all of this for the files written, with the light, rotation,
// exposure and lightmap UV set.
//
// `-o NAME.glb` instead keeps the encoding's own numbers, unpacked (no engine's packing, no
// clamping: floats hold them all), as named layers of W × H RGB texels beside the bake's mesh
// (LightmapLayers; io/lightmap_gltf.hpp writes them under the glTF extension PRTKIT_lightmap):
//
//   lightmap      f
//   lightmap-sh   L0, L1x, L1y, L1z (A and the x, y, z components of each channel's c, glTF
//                 axes: f ≈ L0 + L1x n_x + L1y n_y + L1z n_z), then zonal (k: zh3,
//                 zh3-shared, zh3-optimal) and axis (zh3-shared, zh3-optimal); l2 and
//                 l2-deringed: sh0 .. sh8
//                 (E_i / π) in place of the L1 layers.

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "prt/core/vec.hpp"
#include "prt/geometry/mesh.hpp"
#include "prt/sh/irradiance_encoding.hpp"
#include "prt/transfer/shape.hpp"

namespace prt::io {

/// An engine whose lightmap shader the L1 layers are laid out for.
enum class LightmapEngine { Godot, Godot43, Bakery };
/// "godot", "godot-4.3", "bakery".
const char* toString(LightmapEngine e);
/// A comma-separated list of the names above ("godot,bakery"), each once; throws prt::Error
/// naming what it expected otherwise.
std::vector<LightmapEngine> parseLightmapEngines(const std::string& list);

/// What the lightmap is of and how it was lit: written into the manifest as given.
struct LightmapDescription {
  std::string source;                      ///< the bake file
  TransferShape::LightmapSize lightmap{};  ///< its size and padding
  nlohmann::json transfer;                 ///< which transfer was relit ({mode, layout, ...})
  nlohmann::json light;                    ///< {spec, bands, rotateDegrees}
  double exposureStops = 0;                ///< every value is scaled by 2^stops
};

/// The files of an export (flat names, then lightmap.json last) and its manifest.
struct EngineLightmaps {
  std::vector<std::pair<std::string, std::string>> files;  ///< (name, bytes)
  nlohmann::json manifest;
  /// The most texels any engine's packed L1 had to scale down or drop (A ≤ 0): those decode to
  /// less than the encoding holds. Per engine in manifest["clampedTexels"].
  std::size_t clampedTexels = 0;
};

/// --format lightmap: `radiance` (W·H texels, row-major, f(n_p) per texel: the white surface's
/// exit radiance) as lightmap.exr, lightmap.png (8-bit sRGB preview, clamped) and lightmap.json;
/// `mesh` is the bake's (the manifest names its lightmap UV set). Throws prt::Error naming
/// `d.source` on a size mismatch.
EngineLightmaps encodeRadianceLightmap(std::span<const Rgb> radiance, const Mesh& mesh,
                                       const LightmapDescription& d);

/// --format lightmap-sh: `incident` (W·H texels × bands² RGB coefficients, relight::incidentLight)
/// encoded per texel (sh::encodeIrradiance) and laid out for `engines` (at least one), with
/// zh3*.exr or l2.exr where the encoding holds more than L1. Parallel over texels.
EngineLightmaps encodeIrradianceLightmaps(std::span<const Rgb> incident, int bands,
                                          sh::IrradianceEncoding encoding,
                                          std::span<const LightmapEngine> engines, const Mesh& mesh,
                                          const LightmapDescription& d);

/// One layer of an export: W·H RGB texels, row-major, row 0 at v = 0.
struct LightmapLayer {
  std::string name;   ///< "f", "L0", "L1x", ..., "sh8"
  std::string holds;  ///< what it holds, for the manifest
  std::vector<Rgb> texels;
};

/// The unpacked layers of an export and its manifest (lightmap.json's members, without
/// "files": `layers` lists the layers' names, what they hold and how f decodes from them).
struct LightmapLayers {
  std::vector<LightmapLayer> layers;
  nlohmann::json manifest;
};

/// --format lightmap as layers: "f" alone (`radiance` scaled by 2^stops).
LightmapLayers radianceLayers(std::span<const Rgb> radiance, const Mesh& mesh,
                              const LightmapDescription& d);

/// --format lightmap-sh as layers (see the top), from the same per-texel encoding as
/// encodeIrradianceLightmaps. Parallel over texels.
LightmapLayers irradianceLayers(std::span<const Rgb> incident, int bands,
                                sh::IrradianceEncoding encoding, const Mesh& mesh,
                                const LightmapDescription& d);

}  // namespace prt::io
