// Camera rays and lat-long lookups, shared by the desktop viewer and the web page.
// A pixel's ray as render::RayGenerator builds it: ndc = (2 px / w − 1, 1 − 2 py / h) with py from
// the top, i.e. 2 gl_FragCoord.xy / viewport − 1 in GL's bottom-up window coordinates;
// d ∝ forward + ndc.x tanX right + ndc.y tanY up.
vec3 prtCameraRay(vec2 ndc, vec3 forward, vec3 rightTan, vec3 upTan) {
  return normalize(forward + ndc.x * rightTan + ndc.y * upTan);
}
// Lat-long texture coordinates of a direction e (envmap/layout.hpp): θ = acos e.y,
// φ = atan2(e.z, e.x), u = φ / 2π + 1/2, v = θ / π (v = 0 is the top row, looking up +Y).
vec2 prtLatLongUv(vec3 e) {
  const float kPi = 3.14159265358979;
  float theta = acos(clamp(e.y, -1.0, 1.0));
  float phi = atan(e.z, e.x);
  return vec2(phi / (2.0 * kPi) + 0.5, theta / kPi);
}
