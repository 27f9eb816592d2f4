// Mesh pass for dense vector transfer (relight::ShaderPath::DenseVector): relights vertex
// gl_VertexID, R = albedo ⊙ Σ_{i<b²} T_i L'_i (prt_relight.glsl), from a data texture laid out
// as packShaderRows lays it out (include/prt/relight/shader_transfer.hpp).
#include "prt_mesh.glsl"
uniform PRT_TEXELS uTransfer;  // RGBA32F, layout in prt_relight.glsl
uniform int uTexelsPerVertex;  // scalar: roundUp4(B²)/4; RGB: B²
uniform int uCount;            // scalar: texels to read = roundUp4(b²)/4; RGB: b²
uniform bool uRgb;
PRT_LIGHT_UNIFORM;             // D(R) L, (r, g, b, 0) per coefficient, zero past b²
out vec3 vRadiance;
vec4 prtTransferTexel(int t) { return prtTexel(uTransfer, t); }
#include "prt_relight.glsl"
void main() {
  vRadiance = prtAlbedo() * prtRelight(gl_VertexID * uTexelsPerVertex, uCount, uRgb);
  prtPassBaseColour();
  gl_Position = prtClip(position);
}
