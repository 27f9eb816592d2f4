// Web page, mesh pass for CPCA-compressed vector transfer: vertex gl_VertexID reads its cluster
// id and weights from one data texture and this frame's cluster projections from another
// (web/src/compressed.js; shaders/prt_compressed.glsl, shared with the desktop viewer):
// R(v) = albedo(v) ⊙ (c_k + Σ_j w_j d_kj). Texel t at (t mod width, t div width).
precision highp float;
precision highp int;
precision highp sampler2D;
in vec3 position;
#ifdef PRT_HAS_ALBEDO
in vec3 color;  // COLOR_0: the linear per-vertex albedo
#endif
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform sampler2D uWeights;   // RGBA32F, uTexelsPerVertex texels per vertex
uniform int uWeightsWidth;
uniform sampler2D uClusters;  // RGBA32F, K(N + 1) texels, rewritten every frame
uniform int uClustersWidth;
uniform int uTexelsPerVertex;  // ⌈(N + 1)/4⌉
uniform int uBasisCount;       // N
out vec3 vRadiance;
vec4 prtWeightTexel(int t) { return texelFetch(uWeights, ivec2(t % uWeightsWidth, t / uWeightsWidth), 0); }
vec4 prtClusterTexel(int t) { return texelFetch(uClusters, ivec2(t % uClustersWidth, t / uClustersWidth), 0); }
#include "prt_compressed.glsl"
void main() {
#ifdef PRT_HAS_ALBEDO
  vec3 albedo = color;
#else
  vec3 albedo = vec3(1.0);  // relight's rule: no per-vertex albedo means white
#endif
  vRadiance = albedo * prtRelightCompressed(gl_VertexID * uTexelsPerVertex, uBasisCount);
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
