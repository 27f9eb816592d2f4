// image::toneMap then image::linearToSrgb (include/prt/image/color.hpp), per channel; shared by
// the desktop viewer and the web page so both show what `prt render` writes to a PNG.
// op: 0 clamp, 1 reinhard, 2 aces (Narkowicz's fit); scale = 2^exposure.
// Saturates to white however bright the input (color.hpp): the exposed value is clamped to
// [0, 1e30] (image::kToneMapInputMax; a NaN is sent to 0 where the GPU's comparisons allow),
// and ACES's input to 16 (it is 1 from 7.25 on), so neither v·scale nor v² can overflow.
float prtToneMap(float v, float scale, int op) {
  v = v * scale;
  v = v > 0.0 ? min(v, 1e30) : 0.0;
  if (op == 0) return min(v, 1.0);
  if (op == 1) return v / (1.0 + v);
  v = min(v, 16.0);
  return clamp(v * (2.51 * v + 0.03) / (v * (2.43 * v + 0.59) + 0.14), 0.0, 1.0);
}
float prtLinearToSrgb(float v) {
  v = clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}
vec3 prtDisplay(vec3 c, float scale, int op) {
  return vec3(prtLinearToSrgb(prtToneMap(c.r, scale, op)),
              prtLinearToSrgb(prtToneMap(c.g, scale, op)),
              prtLinearToSrgb(prtToneMap(c.b, scale, op)));
}
