// Web page, mesh pass: relights vertex gl_VertexID (shaders/prt_relight.glsl, shared with the
// desktop viewer) from a 2D data texture: texel t at (t mod width, t div width).
precision highp float;
precision highp int;
precision highp sampler2D;
in vec3 position;
#ifdef PRT_HAS_ALBEDO
in vec3 color;  // COLOR_0: the linear per-vertex albedo
#endif
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform sampler2D uTransfer;  // RGBA32F, layout in prt_relight.glsl
uniform int uTexWidth;
uniform int uTexelsPerVertex;  // scalar: roundUp4(B²)/4; RGB: B²
uniform int uCount;            // scalar: roundUp4(b²)/4; RGB: b²
uniform bool uRgb;
uniform vec4 uL[PRT_LIGHT_VEC4S];  // D(R) L, (r, g, b, 0) per coefficient, zero past b²
out vec3 vRadiance;
vec4 prtTransferTexel(int t) { return texelFetch(uTransfer, ivec2(t % uTexWidth, t / uTexWidth), 0); }
#include "prt_relight.glsl"
void main() {
#ifdef PRT_HAS_ALBEDO
  vec3 albedo = color;
#else
  vec3 albedo = vec3(1.0);  // relight's rule: no per-vertex albedo means white
#endif
  vRadiance = albedo * prtRelight(gl_VertexID * uTexelsPerVertex, uCount, uRgb);
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
