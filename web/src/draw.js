// The GPU side of a transfer in the page, by path (transfer.js decides the path once): the
// stage that draws it (shaders/stages/, flattened for WebGL2 by cmake/Shaders.cmake), its
// uniforms, and what each frame sets — as the desktop viewer's renderer does per path.
import * as THREE from 'three';
import { bands as kBands } from 'prt:constants';
import { denseTexelsPerRow } from './transfer.js';
import meshVert from 'prt:shaders/mesh.vert';
import compressedVert from 'prt:shaders/compressed.vert';
import compressedGlossyVert from 'prt:shaders/compressedGlossy.vert';
import meshFrag from 'prt:shaders/mesh.frag';

const kGlossyCoeffs = kBands.maxShaderGlossy * kBands.maxShaderGlossy;

const compressedUniforms = () => ({
  uWeights: { value: null }, uClusters: { value: null },
  uTexelsPerVertex: { value: 1 }, uBasisCount: { value: 0 },
});
function setCompressed(u, t, rows, table) {
  u.uWeights.value = rows;
  u.uClusters.value = table;
  u.uTexelsPerVertex.value = t.compressed.texelsPerVertex;
  u.uBasisCount.value = t.compressed.basisCount;
}

const kDraw = {
  DenseVector: {
    stage: meshVert,
    uniforms: (light) => ({ uTransfer: { value: null }, uTexelsPerVertex: { value: 1 }, uCount: { value: 0 },
                            uRgb: { value: false }, uL: light }),
    set(u, t, f) {
      u.uTransfer.value = f.rows;
      u.uTexelsPerVertex.value = t.texelsPerRow;
      u.uRgb.value = t.channels === 3;
      u.uCount.value = t.channels === 3 ? f.bands * f.bands : Math.ceil((f.bands * f.bands) / 4);
    },
  },
  CpcaVector: {
    stage: compressedVert,
    uniforms: compressedUniforms,
    set: (u, t, f) => setCompressed(u, t, f.rows, f.table),
  },
  CpcaMatrix: {
    stage: compressedGlossyVert,
    uniforms: () => Object.assign(compressedUniforms(), {
      uBands: { value: 1 }, uCoeffs: { value: 1 }, uDiffuse: { value: new Float32Array(kGlossyCoeffs) },
      uGlossy: { value: new Float32Array(kGlossyCoeffs) }, uKd: { value: new THREE.Vector3() },
      uKs: { value: new THREE.Vector3() }, uEye: { value: new THREE.Vector3() }, uHasKd: { value: false },
    }),
    set(u, t, f) {
      setCompressed(u, t, f.rows, f.table);
      // The shaded bands, the table's values per cluster vector (the transfer cut to them), the
      // material's kernels, kd (else the albedo), ks, and each vertex seen from the camera's eye.
      u.uBands.value = Math.min(f.bands, kBands.maxShaderGlossy);
      u.uCoeffs.value = f.bands * f.bands;
      u.uDiffuse.value.set(t.material.diffuse);
      u.uGlossy.value.set(t.material.lobe);
      u.uHasKd.value = !!t.material.kd;
      if (t.material.kd) u.uKd.value.fromArray(t.material.kd);
      u.uKs.value.fromArray(t.material.ks);
      u.uEye.value.copy(f.eye);
    },
  },
};

/** The material that draws transfer t on a part (light: the shared uL uniform, vec4s: its
 *  length; hasAlbedo: the part has COLOR_0). */
export function transferMaterial(t, light, vec4s, hasAlbedo) {
  const d = kDraw[t.path];
  const defines = { PRT_LIGHT_VEC4S: vec4s, PRT_GLOSSY_COEFFS: kGlossyCoeffs };
  if (hasAlbedo) defines.PRT_HAS_ALBEDO = 1;
  return new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3, vertexShader: d.stage, fragmentShader: meshFrag, defines,
    uniforms: d.uniforms(light), side: THREE.DoubleSide,
  });
}

/** Sets a frame's uniforms of t's material: f = { bands, rows, table, eye } (rows and table:
 *  the part's and the frame's textures). */
export function setTransferUniforms(material, t, f) {
  kDraw[t.path].set(material.uniforms, t, f);
}

/** What the status line says about how t is drawn. */
export function describeTransfer(t) {
  const lines = [];
  if (t.matrix) lines.push(`glossy ${t.material.material}, toward the eye`);
  if (t.compressed) {
    const c = t.compressed, dense = 16 * denseTexelsPerRow(t);
    lines.push(`relit compressed: CPCA ${c.clusters} x ${c.basisCount}, ${16 * c.texelsPerVertex} bytes/vertex ` +
               `(dense ${dense}), ${16 * c.clusters * (c.basisCount + 1) * c.coeffs} bytes of cluster table per frame`);
  }
  return lines;
}
