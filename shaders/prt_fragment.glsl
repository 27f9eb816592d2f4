// The exit radiance a mesh pass's fragment writes (mesh.frag, three.frag): the vertex stages'
// interpolated radiance, or with PRT_LIGHTMAP (per-texel transfer, lightmap.vert) relit here,
// per pixel, at the interpolated lightmap UV, times the interpolated albedo (prt_lightmap.glsl)
// — what prt render does at a ray's hit. With PRT_BASE_COLOUR the mesh's base-colour texture
// (an sRGB texture: decoded before bilinear filtering; repeat wrapping, no mipmaps:
// geometry/base_colour.hpp) multiplies the diffuse part at the pixel's texture UV and the lobe
// is added after (render/base_colour.hpp's rule), unless uBaseColourOn is off (a material that
// sets kd replaces the texture: render::pixelTexture).
#ifdef PRT_BASE_COLOUR
uniform sampler2D uBaseColour;
uniform bool uBaseColourOn;
in vec2 vBaseUv;
vec3 prtBaseColour() { return uBaseColourOn ? texture(uBaseColour, vBaseUv).rgb : vec3(1.0); }
#else
vec3 prtBaseColour() { return vec3(1.0); }
#endif
#ifdef PRT_LIGHTMAP
centroid in vec2 vLightmapUv;
in vec3 vAlbedo;
#include "prt_lightmap.glsl"
vec3 prtRadiance() {
  vec3 lobe;
  vec3 diffuse = prtLightmapRadiance(vLightmapUv, lobe);
#ifndef PRT_LIGHTMAP_GLOSSY
  diffuse *= vAlbedo;  // glossy rows hold their albedo
#endif
  return prtBaseColour() * diffuse + lobe;
}
#else
in vec3 vRadiance;
#ifdef PRT_BASE_COLOUR
in vec3 vGlossy;
vec3 prtRadiance() { return prtBaseColour() * vRadiance + vGlossy; }
#else
vec3 prtRadiance() { return vRadiance; }
#endif
#endif
