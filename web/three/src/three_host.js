// The three.js module's host for the transfer stages (web/src/draw.js): the page's stages
// flattened with shaders/hosts/three.glsl and its fragment stage three.frag, as
// THREE.ShaderMaterials, so that three.js declares the matrices and attributes, applies the
// renderer's tone mapping and output colour space, and the material sits in any scene.
import * as THREE from 'three';
import meshVert from 'prt:three-shaders/mesh.vert';
import radianceVert from 'prt:three-shaders/radiance.vert';
import compressedVert from 'prt:three-shaders/compressed.vert';
import compressedGlossyVert from 'prt:three-shaders/compressedGlossy.vert';
import lightmapVert from 'prt:three-shaders/lightmap.vert';
import threeFrag from 'prt:three-shaders/three.frag';

/** The host of one bake: its materials share `exposure` ({ value: 2^stops }). */
export function threeHost(exposure) {
  return {
    stages: { 'mesh.vert': meshVert, 'radiance.vert': radianceVert, 'compressed.vert': compressedVert,
              'compressedGlossy.vert': compressedGlossyVert, 'lightmap.vert': lightmapVert,
            fragment: threeFrag },
    uniforms: { uExposureScale: exposure },
    material: ({ vertexShader, fragmentShader, defines, uniforms, hasAlbedo }) => {
      const m = new THREE.ShaderMaterial({ vertexShader, fragmentShader, defines, uniforms,
                                           vertexColors: hasAlbedo, side: THREE.DoubleSide });
      m.name = 'PRTKIT_radiance_transfer';
      return m;
    },
  };
}
