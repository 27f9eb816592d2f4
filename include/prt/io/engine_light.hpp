#pragma once
// SH lights in the conventions engines read: `prt light … --format threejs|gltf-ibl|cmgen|unity`.
//
// Ours (prt/sh/sh.hpp): radiance coefficients L_lm of the real orthonormal basis *with* the
// Condon–Shortley phase (Y1,-1 = −0.4886 y, Y1,1 = −0.4886 x, Y2,-1 = −1.0925 yz,
// Y2,1 = −1.0925 xz), evaluated on world (x, y, z), right-handed, +Y up: glTF's frame. Each
// format below states what it holds and how it is derived; docs/formats-light.md has the table
// and tests/io/test_engine_light.cpp checks each against the engine's own code or tool.
//
//  threejs   A three.js object JSON (`new THREE.ObjectLoader().parse(json)` gives a LightProbe;
//            `probe.sh.fromArray(json.object.sh)` for the bare array). three.js's
//            SphericalHarmonics3 holds radiance coefficients of the basis *without* the
//            Condon–Shortley phase (its getAt: 0.488603 y, 0.488603 z, 0.488603 x,
//            1.092548 xy, 1.092548 yz, 0.315392 (3z²−1), 1.092548 xz, 0.546274 (x²−y²)), in
//            three.js's world, which is glTF's: coefficients 1, 3, 5 and 7 change sign. 3 bands.
//  gltf-ibl  The irradiance of EXT_lights_image_based (`irradianceCoefficients`, 9 × [r, g, b]):
//            E_lm = Â_l L_lm (Ramamoorthi & Hanrahan 2001: Â = π, 2π/3, π/4), basis and axes as
//            ours (Babylon.js, the extension's reference runtime, uses the Condon–Shortley signs
//            and turns the coefficients into radiance by 1/π). Written as a complete glTF 2.0
//            asset (asset.version, extensionsUsed, a scene using the light) whose light also has
//            the prefiltered specular cube map the extension requires: the SH light's own
//            radiance (every band given) prefiltered with GGX per mip (64², 32², 16²: roughness
//            0, ½, 1), six RGBD PNGs a mip embedded as data URIs. 3 bands of irradiance.
//  cmgen     Filament cmgen's `--sh=B --sh-output sh.txt` text ("( r, g, b); // L1-1"): the
//            radiance coefficients cmgen computes from the same image with its windowing off
//            (-w no; its default -w auto scales bands ≥ 1 down by an image-dependent window)
//            and its default mirroring. Basis as ours; cmgen maps a lat-long image onto
//            its cube turned −90° about +Y against ours (the image centre looks along +Z there,
//            along +X here), so the light is rotated by that first. Any band count.
//  unity     Unity's SphericalHarmonicsL2 as its shaders evaluate it (ShadeSH9: sh[c,0] −
//            sh[c,6] + sh[c,3] x + sh[c,1] y + sh[c,2] z + sh[c,4] xy + sh[c,5] yz +
//            3 sh[c,6] z² + sh[c,7] xz + sh[c,8] (x² − y²) is the diffuse radiance, E/π, of a
//            white Lambertian surface): the irradiance over π with each basis function's constant
//            folded in, in Unity's left-handed world, which glTF importers (glTFast, UnityGLTF)
//            reach by negating x. Written as JSON {"sh": [[27 floats, 9 per channel: r, g, b]]}
//            for a script to copy into `sh[channel, i]`. 3 bands.

#include <string>
#include <string_view>

#include "prt/sh/sh.hpp"

namespace prt::io {

enum class EngineLight { ThreeJs, GltfIbl, Cmgen, Unity };

/// "threejs", "gltf-ibl", "cmgen", "unity"; anything else throws naming the choices.
EngineLight parseEngineLight(std::string_view name);
const char* engineLightName(EngineLight format);
/// The file extension each format is written with ("json" or "txt").
const char* engineLightExtension(EngineLight format);

/// Coefficients in the engine's convention, as the flat list its format stores: 3-band formats
/// get 9 × RGB (a light of fewer bands is padded with zeros, more bands are cut: the engine
/// holds no more), cmgen every band. Index k of the result is coefficient k's (r, g, b).
sh::RgbSh toEngineConvention(EngineLight format, const sh::RgbSh& radiance);

/// The text of the file, from our radiance coefficients; `source` names the environment.
std::string formatEngineLight(EngineLight format, const sh::RgbSh& radiance,
                              const std::string& source);

}  // namespace prt::io
