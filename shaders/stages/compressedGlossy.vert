// Mesh pass for CPCA-compressed glossy (matrix) transfer (relight::ShaderPath::CpcaMatrix).
// Once per frame the rotated light is projected on every cluster's mean and basis matrices,
// L'_kj = B_kj L' (B² RGB values each; relight::projectClusters, web/src/compressed.js); vertex
// v of cluster k forms the light it receives,
//   L'_v,i = L'_k0,i + Σ_j w_vj L'_kj,i      (prt_compressed.glsl, Q = B² values per vector)
// and shades it with the glossy response (prt_glossy.glsl). Fewer bands b < B: the projections
// were made with the light cut to b bands (the leading b² columns) and only rows i < b² are
// summed — the leading b² × b² block, as the dense paths.
#include "prt_mesh.glsl"
#ifndef PRT_HOST_DECLARES_INPUTS
layout(location = 3) in vec3 normal;  // unit
#endif
uniform PRT_TEXELS uWeights;   // RGBA32F, uTexelsPerVertex texels per vertex
uniform PRT_TEXELS uClusters;  // RGBA32F, K(N + 1)·uCoeffs texels, rewritten every frame
uniform int uTexelsPerVertex;  // ⌈(N + 1)/4⌉
uniform int uBasisCount;       // N
uniform int uCoeffs;           // values per cluster vector in the table
out vec3 vRadiance;
vec4 prtWeightTexel(int t) { return prtTexel(uWeights, t); }
vec4 prtClusterTexel(int t) { return prtTexel(uClusters, t); }
#include "prt_compressed.glsl"
int gBase, gRow;  // this vertex's first texel and cluster row (set in main)
#include "prt_glossy.glsl"
vec3 prtGlossyLight(int i) { return prtCompressedValue(gBase, gRow, uBasisCount, uCoeffs, i); }
void main() {
  gBase = gl_VertexID * uTexelsPerVertex;
  gRow = prtCompressedRow(gBase, uBasisCount);
  prtPassBaseColour();
#ifdef PRT_BASE_COLOUR
  vRadiance = prtGlossyParts(position, normal, prtAlbedo(), vGlossy);  // the texture's, the lobe
#else
  vRadiance = prtGlossy(position, normal, prtAlbedo());
#endif
  gl_Position = prtClip(position);
}
