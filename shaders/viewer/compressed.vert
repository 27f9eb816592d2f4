// Desktop viewer, mesh pass for CPCA-compressed vector transfer (prt_compressed.glsl; layouts in
// include/prt/relight/cluster_table.hpp): vertex v = gl_VertexID of cluster k reads its id and N
// weights and this frame's cluster projections c_k = M_k·L', d_kj = B_kj·L' (made on the CPU by
// relight::projectClusters) and forms R(v) = albedo(v) ⊙ (c_k + Σ_j w_vj d_kj).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aAlbedo;
uniform mat4 uViewProj;
uniform samplerBuffer uWeights;   // GL_RGBA32F, uTexelsPerVertex texels per vertex
uniform samplerBuffer uClusters;  // GL_RGBA32F, K(N + 1) texels, rewritten every frame
uniform int uTexelsPerVertex;     // ⌈(N + 1)/4⌉
uniform int uBasisCount;          // N
out vec3 vRadiance;
vec4 prtWeightTexel(int t) { return texelFetch(uWeights, t); }
vec4 prtClusterTexel(int t) { return texelFetch(uClusters, t); }
#include "prt_compressed.glsl"
void main() {
  vRadiance = aAlbedo * prtRelightCompressed(gl_VertexID * uTexelsPerVertex, uBasisCount);
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
