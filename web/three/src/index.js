// prtkit-three: prtkit bakes in three.js (docs/three.md). A GLTFLoader plugin reads a bake's
// transfer and dresses its meshes in materials that relight them from SH lights on the GPU —
// dense vectors, CPCA-compressed vectors and CPCA-compressed glossy matrices — with the light's
// rotation and the exposure as properties, through the same GLSL as prtkit's page and desktop
// viewer (shaders/, hosts/three.glsl). A probe bake (prt probes) gives a ProbeGridLighting: the
// light at any point of its grid, relit on the CPU, for LightProbes and engines. A relit lightmap
// exported as glTF (prt export --format lightmap -o NAME.glb) gives a PRTLightmap: its layers as
// textures, the plain one as three.js's lightMap. A Haar bake (prt bake --basis haar) gives a
// HaarLighting: all-frequency shadows relit on the CPU under a light turned from an
// environment's cube (haarEnvironment) or a Haar light file (parseHaarLight).
export { PRTKitRadianceTransfer } from './plugin.js';
export { PRTBake } from './prt_bake.js';
export { ProbeGridLighting } from './probe_grid_lighting.js';
export { HaarLighting, haarEnvironment, parseHaarLight } from './haar_lighting.js';
export { lightProbeGridAtlas, lightProbeGridParameters } from './irradiance_volume.js';
export { PRTLightmap, readLightmap } from './lightmap.js';
export { parseLight, lightFromSphericalHarmonics3, lightToSphericalHarmonics3 } from './light.js';
export { rotateLight, rotationRows } from './rotation.js';
