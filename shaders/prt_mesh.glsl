// The vertex inputs every mesh stage shares, at the locations the desktop viewer binds and
// under the names three.js gives a glTF's attributes: position (0), the linear per-vertex albedo
// COLOR_0 (1, only with PRT_HAS_ALBEDO: without it the albedo is white, relight's rule) and, for
// the glossy stages, the unit normal (3). prtAlbedo() is the albedo; prtClip(p) (the host's)
// the clip position. A host that declares the inputs and the camera itself (three.js's
// ShaderMaterial: hosts/three.glsl) defines PRT_HOST_DECLARES_INPUTS.
#ifndef PRT_HOST_DECLARES_INPUTS
layout(location = 0) in vec3 position;
#ifdef PRT_HAS_ALBEDO
layout(location = 1) in vec3 color;
#endif
PRT_CAMERA_UNIFORMS;
#endif
#ifdef PRT_HAS_ALBEDO
vec3 prtAlbedo() { return color; }
#else
vec3 prtAlbedo() { return vec3(1.0); }
#endif
// PRT_BASE_COLOUR (a base-colour texture, render/base_colour.hpp): the texture's UV set (glTF
// TEXCOORD_0: location 5 on the desktop, three.js's `uv`) goes to the fragment stage, which
// multiplies the texture into vRadiance, the part of the exit radiance it multiplies (the
// diffuse part), and adds vGlossy, the part it does not (the glossy stages' lobe; zero
// otherwise). prtPassBaseColour() sets both; a glossy stage then sets vGlossy.
#ifdef PRT_BASE_COLOUR
#ifndef PRT_HOST_DECLARES_INPUTS
layout(location = 5) in vec2 uv;
#endif
out vec2 vBaseUv;
out vec3 vGlossy;
void prtPassBaseColour() {
  vBaseUv = uv;
  vGlossy = vec3(0.0);
}
#else
void prtPassBaseColour() {}
#endif
