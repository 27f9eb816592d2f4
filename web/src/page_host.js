// The page's host for the transfer stages (draw.js): the stages flattened with
// shaders/hosts/webgl2.glsl, as RawShaderMaterials that write linear HDR into the frame's
// half-float target (frame.js tone maps it in a second pass). The radiance stage draws radiance
// made on the CPU (a matrix transfer through an irradiance encoding).
import * as THREE from 'three';
import meshVert from 'prt:shaders/mesh.vert';
import compressedVert from 'prt:shaders/compressed.vert';
import compressedGlossyVert from 'prt:shaders/compressedGlossy.vert';
import lightmapVert from 'prt:shaders/lightmap.vert';
import radianceVert from 'prt:shaders/radiance.vert';
import meshFrag from 'prt:shaders/mesh.frag';

export const pageHost = {
  stages: { 'mesh.vert': meshVert, 'compressed.vert': compressedVert,
            'compressedGlossy.vert': compressedGlossyVert, 'lightmap.vert': lightmapVert,
            'radiance.vert': radianceVert, fragment: meshFrag },
  material: ({ vertexShader, fragmentShader, defines, uniforms }) => new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3, vertexShader, fragmentShader, defines, uniforms, side: THREE.DoubleSide,
  }),
};
