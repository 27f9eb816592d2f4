// node haar_check.mjs GENDIR BAKE.glb PRT-DATA.js LIGHT.json QUERY.json: a Haar bake relit in
// JavaScript, for tests/web/test_haar_web.cpp to hold to the library (io::decodeBake's rows,
// haar::turnedLight, relight::relightHaar, io::parseHaarLightJson). QUERY = { rotate: [[X, Y, Z]
// degrees (prt render --rotate's)...], terms: K }. Prints one JSON object:
//   rows       the page's reader's rows (web/src/bake.js parseBake, haar_bake.js), flat: per
//              row the kind, the pairs and, inter-reflected, the bounce
//   transfer   what the reader made of the transfer: mode, channels, bounceBands
//   lights     per rotation, the light the page makes from prt web's environment cube
//              (haar_light.js turnedLight, R from sh.js's rotationEulerXYZ): index, value,
//              unshadowed, bright, energyKept, fullSh (haarLightFullSh: what a bounce is relit
//              against)
//   radiance   per rotation, every vertex relit under it (haar_relight.js), in the file's order
//   file       every vertex relit under LIGHT (parseHaarLight), and that light's fullSh
//   three      prtkit-three's plugin and HaarLighting under the cube (haarEnvironment), turned by
//              a THREE.Euler 'ZYX' of the first rotation: every vertex's radiance, and the
//              refusal of a turned light file
// The sources run as they are bundled: 'prt:' imports resolve into GENDIR (bake_verdicts/hooks.mjs).
import fs from 'node:fs';
import path from 'node:path';
import { register } from 'node:module';

const [gen, bakeFile, dataFile, lightFile, queryFile] = process.argv.slice(2);
if (!queryFile) {
  console.error('usage: node haar_check.mjs GENDIR BAKE.glb PRT-DATA.js LIGHT.json QUERY.json');
  process.exit(2);
}
register('../bake_verdicts/hooks.mjs', import.meta.url, { data: { gen: path.resolve(gen) } });
const web = new URL('../../../web/', import.meta.url);
const THREE = await import(new URL('node_modules/three/build/three.module.js', web));
const { GLTFLoader } = await import(new URL('node_modules/three/examples/jsm/loaders/GLTFLoader.js', web));
const { parseBake } = await import(new URL('src/bake.js', web));
const { rotationEulerXYZ } = await import(new URL('src/sh.js', web));
const { base64Bytes, decodeRgbe } = await import(new URL('src/environment.js', web));
const { environmentCube, parseHaarLight, turnedLight } = await import(new URL('src/haar_light.js', web));
const { relightHaar } = await import(new URL('src/haar_relight.js', web));
const { packed } = await import(new URL('src/radiance_mesh.js', web));
const three = await import(new URL('three/src/index.js', web));

const bytes = () => { const b = fs.readFileSync(bakeFile); return b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength); };
const name = path.basename(bakeFile);
const data = (() => { const s = fs.readFileSync(dataFile, 'utf8'); return JSON.parse(s.slice(s.indexOf('=') + 1).trim().replace(/;$/, '')); })();
const env = data.environments[0];
const q = JSON.parse(fs.readFileSync(queryFile, 'utf8'));
const limits = { maxTextureSize: 16384, maxBands: 32, maxFragmentBands: 32 };

/** Every vertex of the bake's parts relit under `light`, in the file's vertex order. */
function relightAll(bake, t, light) {
  const out = new Array(3 * bake.vertices).fill(0);
  for (const p of bake.parts) {
    const normals = packed(p.geometry.getAttribute('normal'));
    const colour = p.geometry.getAttribute('color');
    const rgb = relightHaar(t, light, normals, t.kd || (colour ? packed(colour) : null), new Float32Array(3 * p.vertices), p.first, p.vertices);
    for (let i = 0; i < rgb.length; ++i) out[3 * p.first + i] = rgb[i];
  }
  return out;
}

async function page() {
  const bake = await parseBake(bytes(), name, limits);
  if (!bake.haar) throw new Error(`${name}: the page did not read Haar transfer`);
  const t = bake.transfers[0], n = t.haar.resolution;
  const cube = environmentCube(env.haar.resolution, base64Bytes(env.haar.rgbe), env.haar.sh, env.name, decodeRgbe);
  const lights = [], radiance = [];
  for (const r of q.rotate) {
    const light = turnedLight(cube, n, q.terms, rotationEulerXYZ(...r));
    lights.push({ index: Array.from(light.index), value: Array.from(light.value), unshadowed: Array.from(light.unshadowed),
                  bright: light.bright, energyKept: light.energyKept, fullSh: Array.from(light.fullSh) });
    radiance.push(relightAll(bake, t, light));
  }
  const fileLight = parseHaarLight(fs.readFileSync(lightFile, 'utf8'), lightFile);
  const file = relightAll(bake, t, fileLight);
  return { rows: Array.from(t.rows), transfer: { mode: t.mode, channels: t.channels, bounceBands: t.haar.bounceBands },
           lights, radiance, file, fileFullSh: Array.from(fileLight.fullSh) };
}

async function module() {
  const gltf = await new GLTFLoader().register((parser) => new three.PRTKitRadianceTransfer(parser, { name, required: true }))
    .parseAsync(bytes(), '');
  const lighting = gltf.userData.prtkit;
  if (!lighting || !lighting.isHaarLighting) throw new Error(`${name}: the plugin left no HaarLighting`);
  lighting.setLight(three.haarEnvironment(env.haar, env.name));
  lighting.terms = q.terms;
  const d = Math.PI / 180, r = q.rotate[0];
  lighting.lightRotation.setFromEuler(new THREE.Euler(r[0] * d, r[1] * d, r[2] * d, 'ZYX'));
  lighting.update();
  const out = [];
  lighting.meshes.forEach((m) => {
    const a = m.geometry.getAttribute('radiance'), first = lighting._bake.parts.find((p) => p.mesh === m).first;
    for (let i = 0; i < a.array.length; ++i) out[3 * first + i] = a.array[i];
  });
  // A light file holds one rotation: turned, it is refused.
  let refusal = '';
  lighting.setLight(three.parseHaarLight(fs.readFileSync(lightFile, 'utf8'), lightFile));
  lighting.lightRotation.setFromEuler(new THREE.Euler(0.3, 0, 0, 'ZYX'));
  try {
    lighting.update();
  } catch (e) {
    refusal = e.message;
  }
  return { radiance: out, meshes: lighting.meshes.length, refusal };
}

console.warn = () => {};
try {
  console.log(JSON.stringify({ page: await page(), three: await module() }));
} catch (e) {
  console.log(JSON.stringify({ error: String(e && e.stack ? e.stack : e) }));
  process.exit(1);
}
