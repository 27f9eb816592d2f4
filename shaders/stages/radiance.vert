// Mesh pass for radiance made on the CPU (relight::ShaderPath::CpuRadiance: glossy matrices
// relit by relight::Relighter toward the eye, the desktop viewer's default): passes each
// vertex's exit radiance through. Desktop viewer only.
#include "prt_mesh.glsl"
layout(location = 2) in vec3 radiance;  // albedo ⊙ diffuse + ks ⊙ glossy, done
out vec3 vRadiance;
void main() {
  vRadiance = radiance;
  gl_Position = prtClip(position);
}
