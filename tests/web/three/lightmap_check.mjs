// prtkit-three's readLightmap under node, as an app uses it: the glTF that `prt export
// --format lightmap | lightmap-sh -o NAME.glb` wrote (run.sh) opens in three.js's GLTFLoader with
// the bake's meshes; every PRTKIT_lightmap layer reads back as the floats in the file (split here
// from the GLB independently of GLTFLoader), its texture holds them to half-float precision on
// the lightmap's UV set, the plain lightmap becomes every mesh's lightMap (intensity π: f is
// E/π), an SH lightmap is refused as a lightMap by name, and broken extensions are refused by
// name. Exits non-zero on the first failure.
import fs from 'node:fs';
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { readLightmap } from 'prtkit-three';

let failures = 0;
function check(ok, what) {
  if (!ok) {
    console.error(`FAIL: ${what}`);
    ++failures;
  }
}
async function rejects(promise, pattern, what) {
  try {
    await promise;
    check(false, `${what}: accepted`);
  } catch (e) {
    check(pattern.test(e.message), `${what}: refused with "${e.message}"`);
  }
}

/** The GLB's JSON and a FLOAT accessor's values, read straight from the bytes (glTF 2.0 §4.4). */
function splitGlb(buf) {
  const dv = new DataView(buf.buffer, buf.byteOffset, buf.byteLength);
  const jsonLength = dv.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(buf.subarray(20, 20 + jsonLength)));
  const bin = buf.subarray(20 + jsonLength + 8);
  const floats = (i) => {
    const a = json.accessors[i], v = json.bufferViews[a.bufferView], at = (v.byteOffset || 0) + (a.byteOffset || 0);
    return new Float32Array(Uint8Array.from(bin.subarray(at, at + a.count * 3 * 4)).buffer);  // a copy: aligned, own buffer
  };
  return { json, floats };
}
const load = (bytes) => new GLTFLoader().parseAsync(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '');

for (const [file, kind, names] of [['lm.glb', 'lightmap', ['f']], ['lm-l1.glb', 'lightmap-sh', ['L0', 'L1x', 'L1y', 'L1z']],
                                   ['lm-l2.glb', 'lightmap-sh', ['sh0', 'sh1', 'sh2', 'sh3', 'sh4', 'sh5', 'sh6', 'sh7', 'sh8']]]) {
  const bytes = fs.readFileSync(file), raw = splitGlb(bytes);
  const gltf = await load(bytes);
  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  check(meshes.length === raw.json.meshes.length && meshes.length > 1, `${file}: three.js opens the bake's ${raw.json.meshes.length} meshes (got ${meshes.length})`);
  const lm = await readLightmap(gltf, file);
  check(lm.kind === kind && lm.width === 16 && lm.height === 16, `${file}: a ${kind} of 16 x 16 (${lm.kind}, ${lm.width} x ${lm.height})`);
  check([...lm.layers.keys()].join() === names.join(), `${file}: layers ${[...lm.layers.keys()].join()}`);
  raw.json.extensions.PRTKIT_lightmap.layers.forEach((l) => {
    const want = raw.floats(l.accessor), got = lm.layers.get(l.name);
    check(got.length === 768 && got.every((x, i) => x === want[i]), `${file}: layer ${l.name} is the file's floats`);
    const t = lm.texture(l.name);
    let worst = 0;
    for (let i = 0; i < 256; ++i)
      for (let c = 0; c < 3; ++c)
        worst = Math.max(worst, Math.abs(THREE.DataUtils.fromHalfFloat(t.image.data[4 * i + c]) - want[3 * i + c]) / Math.max(Math.abs(want[3 * i + c]), 1e-3));
    check(worst < 1e-3 && t.channel === lm.texCoord && t.flipY === false && t.image.width === 16, `${file}: texture ${l.name} holds the layer (worst relative ${worst})`);
  });
  if (kind === 'lightmap') {
    const given = lm.applyTo(gltf.scene);
    check(given.length === meshes.length && given.every((m) => m.material.lightMap === lm.texture('f') && m.material.lightMapIntensity === Math.PI),
          `${file}: every mesh's lightMap is f, intensity π`);
    check(lm.layers.get('f').some((x) => x > 0), `${file}: the lightmap is lit`);
  } else {
    let refused = '';
    try { lm.applyTo(gltf.scene); } catch (e) { refused = e.message; }
    check(refused.startsWith(`${file}: holds a lightmap-sh`), `${file}: an SH lightmap is no lightMap ("${refused}")`);
  }
  lm.dispose();
}

// Broken extensions, each refused by name.
const good = fs.readFileSync('lm.glb');
async function broken(edit, pattern, what) {
  const gltf = await load(good);
  edit(gltf.parser.json.extensions.PRTKIT_lightmap, gltf.parser.json);
  await rejects(readLightmap(gltf, 'bad.glb'), pattern, what);
}
await broken((e) => { e.lightmap.width = 17; }, /^bad\.glb: PRTKIT_lightmap: layer 'f' is 256 VEC3/, 'a size the layers do not fill');
await broken((e) => { e.lightmap.width = 0; }, /^bad\.glb: PRTKIT_lightmap: lightmap size 0 x 16/, 'a zero width');
await broken((e) => { e.lightmap.texCoord = 3; }, /^bad\.glb: PRTKIT_lightmap: texCoord 3/, 'a UV set out of range');
await broken((e) => { e.kind = 'volume'; }, /^bad\.glb: PRTKIT_lightmap: unknown kind 'volume'/, 'an unknown kind');
await broken((e) => { e.layers[0].accessor = 9999; }, /^bad\.glb: PRTKIT_lightmap: layer 'f' names accessor 9999/, 'a missing accessor');
await broken((e) => { e.layers.push({ ...e.layers[0] }); }, /^bad\.glb: PRTKIT_lightmap: layer 'f' named twice/, 'a layer twice');
await broken((e) => { e.layers[0].name = 'g'; }, /^bad\.glb: PRTKIT_lightmap: a plain lightmap without its layer 'f'/, 'no layer f');
await broken((e, j) => { j.accessors[e.layers[0].accessor].type = 'VEC4'; j.accessors[e.layers[0].accessor].count = 192; }, /VEC4.*FLOAT VEC3 expected/, 'a VEC4 layer');
await broken((e, j) => { delete j.extensions; }, /^bad\.glb: holds no PRTKIT_lightmap/, 'no extension');
if (failures) process.exit(1);
console.log('prtkit-three lightmaps under node: all checks passed');
