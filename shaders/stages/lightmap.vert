// Mesh pass for per-texel transfer (relight::ShaderRows::perPixel; dense or CPCA vectors): the
// vertex passes its lightmap UV (the mesh's lightmap set, Mesh::lightmapUvs: location 4 on the
// desktop, the attribute prtLightmapUv in three.js) and its albedo; the fragment stage, compiled
// with PRT_LIGHTMAP, relights per pixel (prt_fragment.glsl, prt_lightmap.glsl). The rasteriser
// interpolates both perspective-correctly: the barycentrics prt render takes at a ray's hit.
#include "prt_mesh.glsl"
#ifndef PRT_HOST_DECLARES_INPUTS
layout(location = 4)
#endif
in vec2 prtLightmapUv;
centroid out vec2 vLightmapUv;  // centroid: inside the triangle at its edges (MSAA)
out vec3 vAlbedo;
void main() {
  vLightmapUv = prtLightmapUv;
  vAlbedo = prtAlbedo();
  prtPassBaseColour();
  gl_Position = prtClip(position);
}
