// The glossy response, once for every glossy stage (the desktop's glossy.vert and
// compressedGlossy.vert, the page's compressedGlossy.vert): exit radiance toward the eye of a
// vertex at p with unit normal n that receives the light L' (its SH, r g b per coefficient),
// as PreparedMaterial::responses and relight.hpp compute it on the CPU
// (include/prt/transfer/prepared_material.hpp, material.hpp has the maths):
//   e = Σ_{i<b²} (kd d_i + ks g_i) L'_i,   d_i = (A_l/π) Y_i(n),   g_i = Λ_l Y_i(R),
//   R = 2(n·v)n − v,   v = normalize(eye − p)   (v = n at the eye itself),
// kd the material's (uHasKd) or else the vertex albedo. The kernels arrive multiplied by the SH
// normalisation N_lm that prt_sh_basis.glsl leaves out (relight::shaderKernel).
// The host defines vec3 prtGlossyLight(int i), L'_i for i < b² (declared here, so the host may
// define it after this file and use the uniforms above).
#include "prt_sh_basis.glsl"
uniform int uBands;                        // b, the bands shaded (≤ bands::kMaxShaderGlossy)
uniform float uDiffuse[PRT_GLOSSY_COEFFS];  // (A_l/π) · N_lm per coefficient i = l(l+1)+m
uniform float uGlossy[PRT_GLOSSY_COEFFS];   // Λ_l · N_lm
uniform vec3 uKd, uKs, uEye;
uniform bool uHasKd;
vec3 prtGlossyLight(int i);
// The two parts apart: returns Σ kd d_i L'_i (what a base-colour texture multiplies,
// render/base_colour.hpp), `lobe` = Σ ks g_i L'_i (added untextured).
vec3 prtGlossyParts(vec3 p, vec3 n, vec3 albedo, out vec3 lobe) {
  vec3 toEye = uEye - p;
  float len = length(toEye);
  vec3 v = len > 0.0 ? toEye / len : n;
  vec3 r = 2.0 * dot(n, v) * n - v;
  float yn[PRT_GLOSSY_COEFFS], yr[PRT_GLOSSY_COEFFS];
  shBasis(n, uBands, yn);
  shBasis(r, uBands, yr);
  vec3 kd = uHasKd ? uKd : albedo;
  vec3 d = vec3(0.0), g = vec3(0.0);
  for (int i = 0; i < uBands * uBands; ++i) {
    vec3 l = prtGlossyLight(i);
    d += (uDiffuse[i] * yn[i]) * l;
    g += (uGlossy[i] * yr[i]) * l;
  }
  lobe = uKs * g;
  return kd * d;
}
vec3 prtGlossy(vec3 p, vec3 n, vec3 albedo) {
  vec3 lobe;
  vec3 d = prtGlossyParts(p, n, albedo, lobe);
  return d + lobe;
}
