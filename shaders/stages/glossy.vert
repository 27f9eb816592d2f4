// Mesh pass for dense glossy (matrix) transfer relit in the vertex shader
// (relight::ShaderPath::DenseMatrix, prt view --glossy-on gpu; desktop viewer only — the page
// draws glossy matrices CPCA-compressed). M_p row-major in a data texture, each row of B²
// entries padded to a multiple of four (uRowTexels texels per row); the light vertex p receives
// is L'_p = M_p L', rows i < b² read up to ⌈b²/4⌉ texels against the rotated light uL (zero
// past b², so the padding meets zero light); then the glossy response (prt_glossy.glsl).
#include "prt_mesh.glsl"
#ifndef PRT_HOST_DECLARES_INPUTS
layout(location = 3) in vec3 normal;  // unit
#endif
uniform PRT_TEXELS uTransfer;
uniform int uRowTexels;     // ⌈B²/4⌉, B the transfer's bands
uniform int uVertexTexels;  // B² · uRowTexels
PRT_LIGHT_UNIFORM;          // D(R) L, (r, g, b, -) per coefficient
out vec3 vRadiance;
#include "prt_glossy.glsl"
vec3 prtGlossyLight(int i) {  // (M_p L')_i
  int texels = (uBands * uBands + 3) / 4;
  int t0 = gl_VertexID * uVertexTexels + i * uRowTexels;
  vec3 row = vec3(0.0);
  for (int t = 0; t < texels; ++t) {
    vec4 m = prtTexel(uTransfer, t0 + t);
    int j = 4 * t;
    row += m.x * uL[j].rgb + m.y * uL[j + 1].rgb + m.z * uL[j + 2].rgb + m.w * uL[j + 3].rgb;
  }
  return row;
}
void main() {
  prtPassBaseColour();
#ifdef PRT_BASE_COLOUR
  vRadiance = prtGlossyParts(position, normal, prtAlbedo(), vGlossy);  // the texture's, the lobe
#else
  vRadiance = prtGlossy(position, normal, prtAlbedo());
#endif
  gl_Position = prtClip(position);
}
