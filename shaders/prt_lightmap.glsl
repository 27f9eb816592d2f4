// Per-pixel relighting of per-texel transfer (a W × H lightmap over the mesh's lightmap UVs;
// relight/shader_transfer.hpp, "Per-texel transfer"), shared by the desktop viewer's and the web
// page's fragment stages (prt_fragment.glsl). The rows are packed as per-vertex rows are, row
// y·W + x for texel (x, y), uTexelsPerRow texels each, in the data texture uRows:
//   dense (default)      prt_relight.glsl's layout, against the rotated light uL[]
//   PRT_LIGHTMAP_CPCA    prt_compressed.glsl's ids and weights, against this frame's cluster
//                        table uClusters (the same table as per-vertex CPCA vectors)
//   + PRT_LIGHTMAP_GLOSSY  CPCA glossy matrices (desktop viewer): each tap forms the light its
//                        texel receives, L'_i = L'_k0,i + Σ_j w_j L'_kj,i (uCoeffs values per
//                        cluster vector), and shades it with the glossy response at the texel's
//                        own sample point, normal and albedo (uPoints: three texels per row,
//                        render::packTexelPoints) — the radiance prt render relights each texel
//                        to (render::texelRelight) before its bilinear fetch
// prtLightmapRadiance(uv) is render::texelRadianceShader's fetch (prt render): the four texels
// of geometry/texel_samples.hpp's bilinearTaps — texel centres at ((x + ½)/W, (y + ½)/H), row 0
// at v = 0, indices clamped to the edge — each relit, blended with the bilinear weights in the
// same order. Relighting is linear, so blending relit taps is fetching the relit lightmap.
uniform PRT_TEXELS uRows;
uniform ivec2 uLightmapSize;  // W, H
uniform int uTexelsPerRow;    // T
#ifdef PRT_LIGHTMAP_CPCA
uniform PRT_TEXELS uClusters;  // RGBA32F, K(N + 1) texels, rewritten every frame
uniform int uBasisCount;       // N
vec4 prtWeightTexel(int t) { return prtTexel(uRows, t); }
vec4 prtClusterTexel(int t) { return prtTexel(uClusters, t); }
#include "prt_compressed.glsl"
#ifdef PRT_LIGHTMAP_GLOSSY
uniform PRT_TEXELS uPoints;  // per row: (position, 0), (normal, 0), (albedo, 0)
uniform int uCoeffs;         // values per cluster vector in the table (b²)
int gBase, gRow;             // the tap being shaded: its first weight texel and cluster row
vec3 gTapLobe;               // its lobe (the part a base-colour texture leaves alone)
#include "prt_glossy.glsl"
vec3 prtGlossyLight(int i) { return prtCompressedValue(gBase, gRow, uBasisCount, uCoeffs, i); }
vec3 prtLightmapRow(int r) {
  gBase = r * uTexelsPerRow;
  gRow = prtCompressedRow(gBase, uBasisCount);
  return prtGlossyParts(prtTexel(uPoints, 3 * r).xyz, prtTexel(uPoints, 3 * r + 1).xyz,
                        prtTexel(uPoints, 3 * r + 2).rgb, gTapLobe);
}
#else
vec3 prtLightmapRow(int r) { return prtRelightCompressed(r * uTexelsPerRow, uBasisCount); }
#endif
#else
uniform int uCount;  // scalar: texels to read = roundUp4(b²)/4; RGB: b²
uniform bool uRgb;
PRT_LIGHT_UNIFORM;   // D(R) L, (r, g, b, 0) per coefficient, zero past b²
vec4 prtTransferTexel(int t) { return prtTexel(uRows, t); }
#include "prt_relight.glsl"
vec3 prtLightmapRow(int r) { return prtRelight(r * uTexelsPerRow, uCount, uRgb); }
#endif
// With PRT_LIGHTMAP_GLOSSY the blend is of the taps' diffuse parts (what a base-colour texture
// multiplies); `lobe` gets the blend of their lobes (zero otherwise).
vec3 prtLightmapRadiance(vec2 uv, out vec3 lobe) {
  vec2 p = uv * vec2(uLightmapSize) - 0.5;
  vec2 f = floor(p), w = p - f;
  ivec2 hi = uLightmapSize - 1, i = ivec2(f);
  ivec2 a = clamp(i, ivec2(0), hi), b = clamp(i + 1, ivec2(0), hi);
  int W = uLightmapSize.x;
  int rows[4] = int[4](a.y * W + a.x, a.y * W + b.x, b.y * W + a.x, b.y * W + b.x);
  float weights[4] = float[4]((1.0 - w.x) * (1.0 - w.y), w.x * (1.0 - w.y), (1.0 - w.x) * w.y,
                              w.x * w.y);
  vec3 r = vec3(0.0);
  lobe = vec3(0.0);
  for (int t = 0; t < 4; ++t) {
    r += prtLightmapRow(rows[t]) * weights[t];
#ifdef PRT_LIGHTMAP_GLOSSY
    lobe += gTapLobe * weights[t];
#endif
  }
  return r;
}
