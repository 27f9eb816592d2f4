// prtkit relighting, shared by the desktop viewer (GLSL 3.30) and the web page (GLSL ES 3.00).
// Exit radiance of a vertex before albedo: Σ_{i < b²} T_i L'_i, with L' the rotated light.
// The host declares, before this file:
//   the light  uL[]               vec4 (r, g, b, -) per coefficient i = l(l+1)+m, zero past b²
//   vec4 prtTransferTexel(int t)  texel t of the transfer (RGBA32F)
// Transfer layout per vertex, starting at texel `base`: scalar transfer as B² coefficients
// padded to a multiple of four, four coefficients per texel; RGB transfer as one texel
// (r, g, b, 0) per coefficient. `count` is the texels to read: scalar ⌈b²/4⌉, RGB b².
vec3 prtRelight(int base, int count, bool rgb) {
  vec3 r = vec3(0.0);
  if (rgb) {
    for (int i = 0; i < count; ++i) r += prtTransferTexel(base + i).rgb * uL[i].rgb;
  } else {
    for (int k = 0; k < count; ++k) {
      vec4 t = prtTransferTexel(base + k);
      int i = 4 * k;
      r += t.x * uL[i].rgb + t.y * uL[i + 1].rgb + t.z * uL[i + 2].rgb + t.w * uL[i + 3].rgb;
    }
  }
  return r;
}
