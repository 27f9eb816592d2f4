// Desktop viewer, mesh pass: relights vertex gl_VertexID (prt_relight.glsl) from a texture buffer,
// or (uDirect: glossy transfer, relit on the CPU) passes its exit radiance through.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aAlbedo;
layout(location = 2) in vec3 aRadiance;  // uDirect: albedo ⊙ diffuse + ks ⊙ glossy, done
uniform mat4 uViewProj;
uniform samplerBuffer uTransfer;  // GL_RGBA32F, layout in prt_relight.glsl
uniform int uTexelsPerVertex;     // scalar: roundUp4(B²)/4; RGB: B²
uniform int uCount;               // scalar: texels to read = roundUp4(b²)/4; RGB: b²
uniform bool uRgb;
uniform bool uDirect;
layout(std140) uniform Light { vec4 uL[1024]; };  // D(R) L, (r, g, b, -) per coefficient
out vec3 vRadiance;
vec4 prtTransferTexel(int t) { return texelFetch(uTransfer, t); }
#include "prt_relight.glsl"
void main() {
  vRadiance = uDirect ? aRadiance
                      : aAlbedo * prtRelight(gl_VertexID * uTexelsPerVertex, uCount, uRgb);
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
