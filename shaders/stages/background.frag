// The environment behind the mesh, rotated by R: the lat-long image read at Rᵀ d, d the pixel's
// camera ray (prt_latlong.glsl, as prt render).
uniform vec2 uViewport;
uniform vec3 uForward, uRightTan, uUpTan;
uniform mat3 uRotationT;
uniform sampler2D uLatLong;
out vec4 fragColour;
#include "prt_latlong.glsl"
void main() {
  vec3 d = prtCameraRay(2.0 * gl_FragCoord.xy / uViewport - 1.0, uForward, uRightTan, uUpTan);
  fragColour = vec4(max(texture(uLatLong, prtLatLongUv(uRotationT * d)).rgb, vec3(0.0)), 1.0);
}
