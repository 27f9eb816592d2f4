// The exit radiance a mesh pass's fragment writes (mesh.frag, three.frag): the vertex stages'
// interpolated radiance, or with PRT_LIGHTMAP (per-texel transfer, lightmap.vert) relit here,
// per pixel, at the interpolated lightmap UV, times the interpolated albedo (prt_lightmap.glsl)
// — what prt render does at a ray's hit.
#ifdef PRT_LIGHTMAP
centroid in vec2 vLightmapUv;
in vec3 vAlbedo;
#include "prt_lightmap.glsl"
#ifdef PRT_LIGHTMAP_GLOSSY
vec3 prtRadiance() { return prtLightmapRadiance(vLightmapUv); }  // the rows hold their albedo
#else
vec3 prtRadiance() { return vAlbedo * prtLightmapRadiance(vLightmapUv); }
#endif
#else
in vec3 vRadiance;
vec3 prtRadiance() { return vRadiance; }
#endif
