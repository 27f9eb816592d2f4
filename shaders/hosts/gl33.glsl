// The desktop viewer's host interface (apps/viewer, OpenGL 3.3 core), put before every stage by
// the shader resolver (cmake/Shaders.cmake). The renderer compiles `#version 330 core` and the
// defines it takes from the C++ constants (PRT_LIGHT_VEC4S = relight::kMaxPackedCoeffs,
// PRT_GLOSSY_COEFFS = bands::kMaxShaderGlossy²) in front of it; hosts/webgl2.glsl is the page's.
//
//   PRT_TEXELS            the type of an RGBA32F data texture: a texture buffer here
//   prtTexel(s, t)        texel t of one
//   PRT_LIGHT_UNIFORM     the rotated light uL[] (r, g, b, -) per coefficient: a std140 block
//   PRT_CAMERA_UNIFORMS   the uniforms prtClip reads (declared once, by prt_mesh.glsl)
//   prtClip(p)            clip position of world point p (the parts are in world space)
//   PRT_TARGET_MAX        the largest value the HDR target holds (RGBA32F here: float's)
//   PRT_HAS_ALBEDO        defined: the renderer always feeds location 1 (the albedo, or one
//                         constant colour when the mesh has none)
//   PRT_BASE_COLOUR       defined: the renderer always binds a base-colour texture and feeds
//                         its UVs (location 5), white and constant without one; uBaseColourOn
//                         says whether it applies
#define PRT_TEXELS samplerBuffer
vec4 prtTexel(samplerBuffer s, int t) { return texelFetch(s, t); }
#define PRT_LIGHT_UNIFORM layout(std140) uniform Light { vec4 uL[PRT_LIGHT_VEC4S]; }
#define PRT_CAMERA_UNIFORMS uniform mat4 uViewProj
#define prtClip(p) (uViewProj * vec4(p, 1.0))
#define PRT_TARGET_MAX 3.4028235e38
#define PRT_HAS_ALBEDO 1
#define PRT_BASE_COLOUR 1
