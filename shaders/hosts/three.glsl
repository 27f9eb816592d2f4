// The three.js module's host interface (web/three, docs/three.md: the stages as a
// THREE.ShaderMaterial in anyone's scene), put before every stage by the shader resolver
// (cmake/Shaders.cmake). three.js puts in front of it `#version 300 es`, its precision, the
// material's defines (as the page's: PRT_LIGHT_VEC4S, PRT_GLOSSY_COEFFS, PRT_HAS_ALBEDO) and
// its own declarations — the matrices, the attributes `position`, `normal` and, for a material
// with vertexColors, `color`; in fragment stages `gl_FragColor`, toneMapping() and
// linearToOutputTexel() — so the stages declare no inputs or camera here
// (PRT_HOST_DECLARES_INPUTS). The names are hosts/webgl2.glsl's:
//
//   PRT_TEXELS, prtTexel(s, t)  an RGBA32F data texture, texel t at (t mod width, t div width)
//   PRT_LIGHT_UNIFORM           the rotated light uL[] (r, g, b, 0) per coefficient
//   prtClip(p)                  clip position of point p of the mesh (three.js's matrices: the
//                               mesh may be placed anywhere in the scene)
//   PRT_TARGET_MAX              the largest radiance written (a half-float target's)
#define PRT_HOST_DECLARES_INPUTS
#include "prt_texel_2d.glsl"
#define PRT_LIGHT_UNIFORM uniform vec4 uL[PRT_LIGHT_VEC4S]
#define prtClip(p) (projectionMatrix * modelViewMatrix * vec4(p, 1.0))
#define PRT_TARGET_MAX 65504.0
