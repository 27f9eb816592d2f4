// Mesh pass for radiance made on the CPU: passes each vertex's exit radiance through. The
// desktop viewer's glossy matrices relit by relight::Relighter toward the eye
// (relight::ShaderPath::CpuRadiance, its default), and a probe bake's scene and ball lit through
// the relit probes in JavaScript (the page and prtkit-three: web/src/probe_lighting.js).
#include "prt_mesh.glsl"
layout(location = 2) in vec3 radiance;  // albedo ⊙ diffuse + ks ⊙ glossy, done
#ifdef PRT_BASE_COLOUR
layout(location = 6) in vec3 lobe;  // under a texture: radiance its part, this the lobe's
#endif
out vec3 vRadiance;
void main() {
  vRadiance = radiance;
  prtPassBaseColour();
#ifdef PRT_BASE_COLOUR
  vGlossy = lobe;
#endif
  gl_Position = prtClip(position);
}
