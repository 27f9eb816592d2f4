// Desktop viewer, mesh pass for glossy (matrix) transfer relit in the vertex shader (prt view
// --glossy-on gpu; the default relights on the CPU, docs/viewer.md). Per vertex p, seen from
// uEye (include/prt/relight/glossy.hpp):
//   e_c = Σ_i (kd_c d_i + ks_c g_i) (M_p L'_c)_i,  d_i = (A_l/π) Y_i(n),  g_i = Λ_l Y_i(R),
//   R = 2(n·v)n − v,  v = normalize(eye − p)
// M_p row-major in a texture buffer, each row of B² entries padded to a multiple of four
// (uRowTexels texels per row), rows i < b² read up to ceil(b²/4) texels against the rotated
// light uL (zero past b², so the padding meets zero light).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aAlbedo;  // kd unless uHasKd
layout(location = 3) in vec3 aNormal;  // unit
uniform mat4 uViewProj;
uniform samplerBuffer uTransfer;
uniform int uBands;         // b, the bands shown (≤ 8)
uniform int uRowTexels;     // ceil(B²/4), B the transfer's bands
uniform int uVertexTexels;  // B² · uRowTexels
uniform float uDiffuse[64];  // (A_l/π) · N_lm per coefficient i = l(l+1)+m
uniform float uGlossy[64];   // Λ_l · N_lm
uniform vec3 uKd, uKs, uEye;
uniform bool uHasKd;
layout(std140) uniform Light { vec4 uL[1024]; };  // D(R) L, (r, g, b, -) per coefficient
out vec3 vRadiance;

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
  int nb = uBands * uBands, texels = (nb + 3) / 4;
  int base = gl_VertexID * uVertexTexels;
  vec3 e = vec3(0.0);
  for (int i = 0; i < nb; ++i) {
    vec3 row = vec3(0.0);  // (M_p L')_i
    int t0 = base + i * uRowTexels;
    for (int t = 0; t < texels; ++t) {
      vec4 m = texelFetch(uTransfer, t0 + t);
      int j = 4 * t;
      row += m.x * uL[j].rgb + m.y * uL[j + 1].rgb + m.z * uL[j + 2].rgb + m.w * uL[j + 3].rgb;
    }
    e += (kd * (uDiffuse[i] * yn[i]) + uKs * (uGlossy[i] * yr[i])) * row;
  }
  vRadiance = e;
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
