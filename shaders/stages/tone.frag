// Exposure, tone map and sRGB encode of the resolved HDR frame (prt_display.glsl).
uniform sampler2D uHdr;
uniform float uScale;  // 2^exposure
uniform int uToneMap;  // int(image::ToneMap): 0 clamp, 1 reinhard, 2 aces
out vec4 fragColour;
#include "prt_display.glsl"
void main() {
  fragColour = vec4(prtDisplay(texelFetch(uHdr, ivec2(gl_FragCoord.xy), 0).rgb, uScale, uToneMap), 1.0);
}
