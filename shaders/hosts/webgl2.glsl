// The web page's host interface (web/, WebGL2 through three.js's RawShaderMaterial), put before
// every stage by the shader resolver (cmake/Shaders.cmake). three.js puts `#version 300 es` and
// the material's defines in front of it (PRT_LIGHT_VEC4S from the bake's bands,
// PRT_GLOSSY_COEFFS from the generated constants, PRT_HAS_ALBEDO when the part has COLOR_0);
// hosts/gl33.glsl is the desktop viewer's, with the same names:
//
//   PRT_TEXELS            the type of an RGBA32F data texture: a 2D texture here, texel t at
//                         (t mod width, t div width)
//   prtTexel(s, t)        texel t of one
//   PRT_LIGHT_UNIFORM     the rotated light uL[] (r, g, b, 0) per coefficient: a uniform array
//   PRT_CAMERA_UNIFORMS   the uniforms prtClip reads (declared once, by prt_mesh.glsl)
//   prtClip(p)            clip position of world point p (three.js's matrices; the parts are
//                         in world space)
//   PRT_TARGET_MAX        the largest value the HDR target holds (a half-float target here)
precision highp float;
precision highp int;
#include "prt_texel_2d.glsl"
#define PRT_LIGHT_UNIFORM uniform vec4 uL[PRT_LIGHT_VEC4S]
#define PRT_CAMERA_UNIFORMS uniform mat4 modelViewMatrix; uniform mat4 projectionMatrix
#define prtClip(p) (projectionMatrix * modelViewMatrix * vec4(p, 1.0))
#define PRT_TARGET_MAX 65504.0
