// Every mesh pass's fragments: the interpolated exit radiance, into the linear HDR target,
// clamped to what the target holds (PRT_TARGET_MAX, from the host): beyond it a value may turn
// inf, and blending inf (inf · 0) gives NaN, which tone-maps to black. Clamped there, a light of
// 1e20 still saturates to white after any exposure that shows it. The radiance is the vertex
// stage's, or with PRT_LIGHTMAP relit here per pixel (prt_fragment.glsl).
#include "prt_fragment.glsl"
out vec4 fragColour;
void main() { fragColour = vec4(min(prtRadiance(), vec3(PRT_TARGET_MAX)), 1.0); }
