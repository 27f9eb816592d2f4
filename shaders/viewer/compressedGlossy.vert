// Desktop viewer, mesh pass for CPCA-compressed glossy (matrix) transfer relit in the vertex
// shader (prt view --glossy-on gpu). The CPU projects the rotated light on every cluster's mean
// and basis matrices once per frame, L'_kj = B_kj L' (B² RGB values each, relight::
// projectClusters); vertex v of cluster k forms the light it receives,
//   L'_v,i = L'_k0,i + Σ_j w_vj L'_kj,i      (prt_compressed.glsl, Q = B² values per vector)
// and shades it as glossy.vert shades M_v L' (include/prt/relight/glossy.hpp):
//   e = Σ_{i<b²} (kd d_i + ks g_i) L'_v,i,  d_i = (A_l/π) Y_i(n),  g_i = Λ_l Y_i(R),
//   R = 2(n·v)n − v,  v = normalize(eye − p).
// Fewer bands b < B: the projections were made with the light cut to b bands (the leading b²
// columns) and only rows i < b² are summed — the leading b² × b² block, as the dense paths.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aAlbedo;  // kd unless uHasKd
layout(location = 3) in vec3 aNormal;  // unit
uniform mat4 uViewProj;
uniform samplerBuffer uWeights;   // GL_RGBA32F, uTexelsPerVertex texels per vertex
uniform samplerBuffer uClusters;  // GL_RGBA32F, K(N + 1)B² texels, rewritten every frame
uniform int uTexelsPerVertex;     // ⌈(N + 1)/4⌉
uniform int uBasisCount;          // N
uniform int uBands;               // b, the bands shown (≤ 8)
uniform int uCoeffs;              // B², values per cluster vector
uniform float uDiffuse[64];       // (A_l/π) · N_lm per coefficient i = l(l+1)+m
uniform float uGlossy[64];        // Λ_l · N_lm
uniform vec3 uKd, uKs, uEye;
uniform bool uHasKd;
out vec3 vRadiance;
vec4 prtWeightTexel(int t) { return texelFetch(uWeights, t); }
vec4 prtClusterTexel(int t) { return texelFetch(uClusters, t); }
#include "prt_compressed.glsl"
#include "prt_sh_basis.glsl"

void main() {
  vec3 n = aNormal;
  vec3 toEye = uEye - aPosition;
  float len = length(toEye);
  vec3 v = len > 0.0 ? toEye / len : n;
  vec3 r = 2.0 * dot(n, v) * n - v;
  float yn[64], yr[64];
  shBasis(n, uBands, yn);
  shBasis(r, uBands, yr);
  vec3 kd = uHasKd ? uKd : aAlbedo;
  int base = gl_VertexID * uTexelsPerVertex;
  int row = prtCompressedRow(base, uBasisCount);
  vec3 e = vec3(0.0);
  for (int i = 0; i < uBands * uBands; ++i)
    e += (kd * (uDiffuse[i] * yn[i]) + uKs * (uGlossy[i] * yr[i])) *
         prtCompressedValue(base, row, uBasisCount, uCoeffs, i);
  vRadiance = e;
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
