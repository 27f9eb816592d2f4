// The three.js module's fragments (host three only): the interpolated exit radiance times
// 2^exposure, clamped to PRT_TARGET_MAX as mesh.frag clamps it, then the renderer's tone map
// and output colour space exactly as three.js's own materials apply them (its
// tonemapping_fragment and colorspace_fragment; toneMapping() is declared when the renderer
// tone maps this draw), so a prtkit bake sits in an ordinary scene beside MeshStandardMaterial.
// The radiance is the vertex stage's, or with PRT_LIGHTMAP relit here per pixel
// (prt_fragment.glsl).
#include "prt_fragment.glsl"
uniform float uExposureScale;  // 2^exposure
void main() {
  gl_FragColor = vec4(min(prtRadiance() * uExposureScale, vec3(PRT_TARGET_MAX)), 1.0);
#ifdef TONE_MAPPING
  gl_FragColor.rgb = toneMapping(gl_FragColor.rgb);
#endif
  gl_FragColor = linearToOutputTexel(gl_FragColor);
}
