#pragma once
// A relit probe grid as engines load it (issue 32; docs/probes.md, "Exports"):
// `prt export PROBES.glb --format probe-grid --engine E --light ENV -o grid.json`. A probe bake
// relit under one light (relight/relight_probes.hpp: L'_p = M_p L) is the SH of the radiance
// arriving at each probe — what an engine's irradiance probes hold — written once, for engines
// that do not run PRT. One JSON file:
//
//   asset        {generator, format "prtkit probe grid", version 1}
//   source, light, rotateDegrees, exposureStops     where the values came from
//   engine       the convention of `probes` (io/engine_light.hpp states each):
//                  prtkit    our radiance SH, every band the bake holds (Condon–Shortley basis,
//                            glTF's frame)
//                  threejs   three.js SphericalHarmonics3 radiance (no Condon–Shortley phase),
//                            9 × RGB: a LightProbe's `sh` per probe
//                  unity     Unity's SphericalHarmonicsL2 as ShadeSH9 reads it (E/π, basis
//                            constants folded in), 9 × RGB, in Unity's world (x negated)
//                  gltf-ibl  EXT_lights_image_based's irradianceCoefficients, 9 × RGB
//   grid         {origin, spacing, count [nx, ny, nz], order "x + nx (y + ny z)"}: probe (x, y, z)
//                at origin + (x sx, y sy, z sz), in the engine's world
//   lightProbeGrid  three.js's LightProbeGrid (r187: LightProbeGridWebGL, LightProbeGrid) over
//                the same probes: `position` its centre, `width`/`height`/`depth` = n·s (a cell
//                per probe, the probes at the cells' centres, as ours), `resolution` = count
//                (r184–r186 put the probes on the box's corners: there the size is (n − 1)·s);
//                with --engine threejs also `atlas`, the grid's texture as LightProbeGridNode
//                samples it (lightProbeGridAtlas below), base64 of little-endian float32 RGBA
//   coefficients {count: per probe, layout "probe-major, coefficient, then r g b"}
//   probes       probes × coefficients × 3 numbers, flat
//
// A reader needs nothing else: `probes[(p·K + k)·3 + c]` is coefficient k, channel c of probe p.
// `-o grid.glb` writes the same as a glTF extension (writeProbeGridGltf), and `-o grid.exr` as
// an OpenEXR volume (encodeProbeGridExr): nx × (ny · nz) float texels, probe (x, y, z) at column
// x, row z·ny + y (the z slices stacked down the image), a layer per coefficient k with channels
// shK.R, shK.G, shK.B, and the JSON's description (without `probes`) as the header's string
// attribute `prtkit`.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/io/engine_light.hpp"
#include "prt/transfer/probe_grid.hpp"

namespace prt::io {

/// The conventions a probe grid is written in: an engine's (engine_light.hpp, cmgen excepted: it
/// is a tool's text, not a probe's), or ours (no value).
struct ProbeGridConvention {
  std::optional<EngineLight> engine;  ///< none: prtkit's own radiance SH
};
/// "prtkit", "threejs", "unity", "gltf-ibl"; anything else throws naming the choices.
ProbeGridConvention parseProbeGridConvention(std::string_view name);
const char* probeGridConventionName(const ProbeGridConvention& c);

struct ProbeGridExport {
  ProbeGrid grid;
  int bands = 0;
  std::span<const Rgb> radiance;  ///< probes × bands², our radiance SH (relight::ProbeLighting)
  std::string source, light;
  std::array<double, 3> rotateDegrees{0, 0, 0};
  double exposureStops = 0;
};

/// Padding slices at each end of every sub-volume of three.js's LightProbeGrid atlas.
inline constexpr int kLightProbeGridPadding = 1;

/// three.js LightProbeGrid's texture (examples/jsm/lighting/LightProbeGridWebGL.js and
/// LightProbeGrid.js, r184 to r187 alike): one RGBA 3D texture of nx × ny × 7 (nz + 2)
/// texels, seven sub-volumes stacked along z, sub-volume t at slices t (nz + 2) .. with probe
/// layer z at slice t (nz + 2) + 1 + z and the first and last layers repeated in the padding
/// slices around them (so that its linear filter never blends two sub-volumes). The nine RGB
/// coefficients c0..c8 of a probe (three.js's SphericalHarmonics3: `threeJs`, probes × 9) are
/// packed as t0 = (c0.rgb, c1.r), t1 = (c1.gb, c2.rg), t2 = (c2.b, c3.rgb), t3 = (c4.rgb, c5.r),
/// t4 = (c5.gb, c6.rg), t5 = (c6.b, c7.rgb), t6 = (c8.rgb, 0). Returned as a Data3DTexture's
/// floats: texel (x, y, slice) at ((slice · ny + y) · nx + x) · 4.
std::vector<float> lightProbeGridAtlas(const ProbeGrid& grid, std::span<const Rgb> threeJs);

/// The glTF extension the grid is written as in a .glb (docs/extensions/PRTKIT_probe_grid).
inline constexpr const char* kProbeGridExtension = "PRTKIT_probe_grid";

/// The JSON text (see the top). Throws prt::Error when the radiance does not match the grid.
std::string formatProbeGrid(const ProbeGridExport& grid, const ProbeGridConvention& convention);

/// The same as a glTF 2.0 binary (.glb) holding the extension PRTKIT_probe_grid at its root:
/// the JSON's members (its `asset` apart) with `probes` the index of a FLOAT VEC3 accessor of
/// probes × K elements and, for three.js, `lightProbeGrid.atlas.accessor` a FLOAT VEC4 accessor
/// of the atlas' texels in place of its base64 `data`. Written atomically to `path`.
void writeProbeGridGltf(const std::string& path, const ProbeGridExport& grid,
                        const ProbeGridConvention& convention);

/// The EXR volume (see the top): its bytes. Throws prt::Error naming `name` when the radiance
/// does not match the grid or ny · nz passes the 65,535 rows an EXR image holds here.
std::string encodeProbeGridExr(const ProbeGridExport& grid, const ProbeGridConvention& convention,
                               const std::string& name);

}  // namespace prt::io
