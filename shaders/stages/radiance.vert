// Mesh pass for radiance made on the CPU (relight::ShaderPath::CpuRadiance: glossy matrices
// relit by relight::Relighter toward the eye, the desktop viewer's default): passes each
// vertex's exit radiance through. Desktop viewer only.
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
