// Web page, mesh pass for CPCA-compressed glossy (matrix) transfer, as the desktop viewer's
// shaders/viewer/compressedGlossy.vert: vertex v of cluster k forms the light it receives,
//   L'_v,i = L'_k0,i + Σ_j w_j L'_kj,i     (prt_compressed.glsl; the table made in JS per frame)
// and shades it (include/prt/relight/glossy.hpp):
//   e = Σ_{i<b²} (kd d_i + ks g_i) L'_v,i,  d_i = (A_l/π) Y_i(n),  g_i = Λ_l Y_i(R),
//   R = 2(n·v)n − v,  v = normalize(eye − p); kd the material's, else the vertex albedo.
precision highp float;
precision highp int;
precision highp sampler2D;
in vec3 position;
in vec3 normal;  // unit
#ifdef PRT_HAS_ALBEDO
in vec3 color;  // COLOR_0: the linear per-vertex albedo
#endif
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform sampler2D uWeights;   // RGBA32F, uTexelsPerVertex texels per vertex
uniform int uWeightsWidth;
uniform sampler2D uClusters;  // RGBA32F, K(N + 1)B² texels, rewritten every frame
uniform int uClustersWidth;
uniform int uTexelsPerVertex;  // ⌈(N + 1)/4⌉
uniform int uBasisCount;       // N
uniform int uBands;            // b, the bands shown (≤ 8)
uniform int uCoeffs;           // B², values per cluster vector
uniform float uDiffuse[64];    // (A_l/π) · N_lm per coefficient (relight/glossy_shader.hpp)
uniform float uGlossy[64];     // Λ_l · N_lm
uniform vec3 uKd, uKs, uEye;
uniform bool uHasKd;
out vec3 vRadiance;
vec4 prtWeightTexel(int t) { return texelFetch(uWeights, ivec2(t % uWeightsWidth, t / uWeightsWidth), 0); }
vec4 prtClusterTexel(int t) { return texelFetch(uClusters, ivec2(t % uClustersWidth, t / uClustersWidth), 0); }
#include "prt_compressed.glsl"
#include "prt_sh_basis.glsl"
void main() {
#ifdef PRT_HAS_ALBEDO
  vec3 albedo = color;
#else
  vec3 albedo = vec3(1.0);  // relight's rule: no per-vertex albedo means white
#endif
  vec3 n = normal;
  vec3 toEye = uEye - position;
  float len = length(toEye);
  vec3 v = len > 0.0 ? toEye / len : n;
  vec3 r = 2.0 * dot(n, v) * n - v;
  float yn[64], yr[64];
  shBasis(n, uBands, yn);
  shBasis(r, uBands, yr);
  vec3 kd = uHasKd ? uKd : albedo;
  int base = gl_VertexID * uTexelsPerVertex;
  int row = prtCompressedRow(base, uBasisCount);
  vec3 e = vec3(0.0);
  for (int i = 0; i < uBands * uBands; ++i)
    e += (kd * (uDiffuse[i] * yn[i]) + uKs * (uGlossy[i] * yr[i])) *
         prtCompressedValue(base, row, uBasisCount, uCoeffs, i);
  vRadiance = e;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
