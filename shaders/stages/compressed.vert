// Mesh pass for CPCA-compressed vector transfer (relight::ShaderPath::CpcaVector;
// prt_compressed.glsl, layouts in include/prt/relight/shader_transfer.hpp): vertex v =
// gl_VertexID of cluster k reads its id and N weights and this frame's cluster projections
// c_k = M_k·L', d_kj = B_kj·L' (relight::projectClusters on the desktop, web/src/compressed.js
// in the page) and forms R(v) = albedo(v) ⊙ (c_k + Σ_j w_vj d_kj).
#include "prt_mesh.glsl"
uniform PRT_TEXELS uWeights;   // RGBA32F, uTexelsPerVertex texels per vertex
uniform PRT_TEXELS uClusters;  // RGBA32F, K(N + 1) texels, rewritten every frame
uniform int uTexelsPerVertex;  // ⌈(N + 1)/4⌉
uniform int uBasisCount;       // N
out vec3 vRadiance;
vec4 prtWeightTexel(int t) { return prtTexel(uWeights, t); }
vec4 prtClusterTexel(int t) { return prtTexel(uClusters, t); }
#include "prt_compressed.glsl"
void main() {
  vRadiance = prtAlbedo() * prtRelightCompressed(gl_VertexID * uTexelsPerVertex, uBasisCount);
  prtPassBaseColour();
  gl_Position = prtClip(position);
}
