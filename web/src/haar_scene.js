// The page's Haar mode (docs/haar.md, docs/web.md "Haar bakes"): a Haar bake's parts drawn from
// radiance made on the CPU (shaders/stages/radiance.vert, mesh.frag) — per texel a relit
// lightmap drawn per pixel (haar_texels.js) — as prt render and prt view draw one. When the environment, the light's rotation, its terms or the transfer change, the
// light is made again — the environment's fine cube (prt web's) turned by R and cut to its K
// largest terms (haar_light.js, haar::turnedLight) — and every vertex relit from its sparse
// terms (haar_relight.js, relight::relightHaar) — an inter-reflected row's bounce against the
// light's full SH (haarLightFullSh, made with the light) — with the recipe's kd, else the
// vertices' albedo.
import * as THREE from 'three';
import radianceVert from 'prt:shaders/radiance.vert';
import meshFrag from 'prt:shaders/mesh.frag';
import { haar as kHaar } from 'prt:constants';
import { base64Bytes, decodeRgbe } from './environment.js';
import { environmentCube, turnedLight } from './haar_light.js';
import { relightHaar } from './haar_relight.js';
import { radianceMesh } from './radiance_mesh.js';
import { haarTexelDrawing } from './haar_texels.js';
import { pageHost } from './page_host.js';

function pageRadianceMaterial() {
  return new THREE.RawShaderMaterial({ glslVersion: THREE.GLSL3, vertexShader: radianceVert, fragmentShader: meshFrag,
                                       side: THREE.DoubleSide });
}

/** The cube of environment `e` (environment.js) for a Haar bake over an n cube, decoded once;
 *  throws one line when prt web wrote none for it, or one for another cube. */
export function haarCubeOf(e, n) {
  const h = e.haarSource;
  if (!h)
    throw new Error(`${e.name}: a Haar bake is relit from its environment's cube, which prt web writes beside each environment of a Haar bake's page (prt web BAKE.glb --env ENV); this light holds SH only`);
  if (h.resolution !== kHaar.fineCubeFactor * n)
    throw new Error(`${e.name}: its cube is ${h.resolution}² a face, for Haar bakes over ${h.resolution / kHaar.fineCubeFactor}² cubes; this bake's cube is ${n}² (write the page for this bake: prt web BAKE.glb)`);
  if (!e.haarCube) e.haarCube = environmentCube(h.resolution, base64Bytes(h.rgbe), h.sh, e.name, decodeRgbe);
  return e.haarCube;
}

/**
 * The GPU side of a Haar bake `b` (haar_bake.js): { bake, meshes, haar: { frame(f), light,
 * seconds } }. frame(f) brings it up to date for f = { transfer, env, rotation (rows), terms }:
 * the light and the relighting only when one of them changed.
 */
export function uploadHaarScene(b, limits) {
  // Per texel: the relit lightmap drawn per pixel (haar_texels.js); per vertex: radiance.
  const texels = b.lightmap ? haarTexelDrawing(b, limits, pageHost) : null;
  const parts = b.parts.map((p, i) => {
    if (!texels) return { part: p, m: radianceMesh(p.geometry, pageRadianceMaterial()) };
    const mesh = new THREE.Mesh(p.geometry, texels.material(i, b.transfers[0]));
    mesh.frustumCulled = false;
    return { part: p, m: { mesh } };
  });
  const scene = { light: null, seconds: 0, lightSeconds: 0 };
  let last = null;
  scene.frame = (f) => {
    const t = f.transfer, n = t.haar.resolution;
    const key = [t.key, f.env.name, f.terms, ...f.rotation.flat()].join(' ');
    if (key === last) return false;
    const t0 = performance.now();
    scene.light = turnedLight(haarCubeOf(f.env, n), n, f.terms, f.rotation);
    const t1 = performance.now();
    if (texels) {
      texels.relight(t, scene.light);
      parts.forEach(({ m }, i) => { m.mesh.material = texels.material(i, t); });
    } else {
      for (const { part, m } of parts) {
        relightHaar(t, scene.light, m.normals, t.kd || m.albedo, m.radiance.array, part.first, part.vertices);
        m.radiance.needsUpdate = true;
      }
    }
    scene.lightSeconds = (t1 - t0) / 1000;
    scene.seconds = (performance.now() - t1) / 1000;
    last = key;
    return true;
  };
  return { bake: b, meshes: parts.map(({ m }) => m.mesh), haar: scene, texels };
}

/** Frees the materials (and a per-texel bake's lightmap) uploadHaarScene made (the geometries
 *  are the meshes' to free). */
export function disposeHaarScene(gpu) {
  if (gpu.texels) gpu.texels.dispose();
  else for (const m of gpu.meshes) m.material.dispose();
}

/** The status lines of a Haar bake on screen. */
export function describeHaar(t, scene) {
  const l = scene.light;
  return [t.describe,
          l ? `light: its ${l.index.length} largest terms (${(100 * l.energyKept).toFixed(3)}% of its energy), made in ` +
              `${(1000 * scene.lightSeconds).toFixed(1)} ms, relit in ${(1000 * scene.seconds).toFixed(1)} ms` : 'light: not yet made'];
}
