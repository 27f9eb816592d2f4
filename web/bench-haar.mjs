// Time of a Haar bake's relighting in the page and prtkit-three, per frame the light turns
// (issue 33: "relight in JS or on the GPU — measure"): the light made from prt web's
// environment cube at that turn (src/haar_light.js turnedLight: splat the 4N cube into the N
// one, transform, keep the K largest) and every vertex relit under it (src/haar_relight.js).
// Usage (figures in docs/web.md, "Haar bakes"):
//   prt bake bunny.obj 'builtin:plane?y=-1' --mode shadowed --basis haar --terms 64 -o haar.glb
//   prt web haar.glb --light builtin:sky -o haar-web
//   node web/bench-haar.mjs build/web/gen haar.glb haar-web/prt-data.js [TERMS=200]
// GENDIR holds the generated constants.js the sources import as 'prt:constants'.
import fs from 'node:fs';
import path from 'node:path';
import { register } from 'node:module';

const [gen, bakeFile, dataFile, termsArg] = process.argv.slice(2);
if (!dataFile) {
  console.error('usage: node web/bench-haar.mjs GENDIR BAKE.glb PRT-DATA.js [TERMS]');
  process.exit(2);
}
register('../tests/web/bake_verdicts/hooks.mjs', import.meta.url, { data: { gen: path.resolve(gen) } });
const { parseBake } = await import('./src/bake.js');
const { rotationEulerXYZ } = await import('./src/sh.js');
const { base64Bytes, decodeRgbe } = await import('./src/environment.js');
const { environmentCube, turnedLight } = await import('./src/haar_light.js');
const { relightHaar } = await import('./src/haar_relight.js');
const { packed } = await import('./src/radiance_mesh.js');

// Bad input: one line naming the file, exit 1 (no stack).
process.on('uncaughtException', (e) => {
  console.error(`bench-haar: ${e.message.split('\n')[0]}`);
  process.exit(1);
});
const terms = Number(termsArg || 200);
if (!(Number.isInteger(terms) && terms >= 1)) throw new Error(`TERMS must be a positive integer, not ${termsArg}`);
const b = fs.readFileSync(bakeFile);
const name = path.basename(bakeFile);
const bake = await parseBake(b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength), name,
                             { maxTextureSize: 16384, maxBands: 32, maxFragmentBands: 32 });
if (!bake.haar) throw new Error(`${name}: not a Haar bake`);
const data = (() => { const s = fs.readFileSync(dataFile, 'utf8'); return JSON.parse(s.slice(s.indexOf('=') + 1).trim().replace(/;$/, '')); })();
const env = data.environments[0];
const t = bake.transfers[0], n = t.haar.resolution;
const cube = environmentCube(env.haar.resolution, base64Bytes(env.haar.rgbe), env.haar.sh, env.name, decodeRgbe);
const parts = bake.parts.map((p) => ({ p, normals: packed(p.geometry.getAttribute('normal')), out: new Float32Array(3 * p.vertices) }));

const frames = 40;
const lightMs = [], relightMs = [];
for (let f = -5; f < frames; ++f) {  // five frames of warm-up
  const t0 = performance.now();
  const light = turnedLight(cube, n, terms, rotationEulerXYZ(0, 7 * f, 0));
  const t1 = performance.now();
  for (const q of parts) relightHaar(t, light, q.normals, t.kd || null, q.out, q.p.first, q.p.vertices);
  const t2 = performance.now();
  if (f >= 0) lightMs.push(t1 - t0), relightMs.push(t2 - t1);
}
const median = (a) => { const b = [...a].sort((x, y) => x - y); return b[b.length >> 1]; };
const frame = lightMs.map((x, i) => x + relightMs[i]);
const bounce = t.haar.bounceBands > 0 ? `, a bounce in ${t.haar.bounceBands} SH bands (${t.channels === 3 ? 'RGB' : 'scalar'})` : '';
console.log(`${name}: ${bake.vertices} vertices, ${t.haar.terms} terms a vertex over a ${n}² cube${bounce}; light of ${terms} terms`);
console.log(`turned light ${median(lightMs).toFixed(1)} ms, relight ${median(relightMs).toFixed(1)} ms, ` +
            `frame ${median(frame).toFixed(1)} ms (one thread, median of ${frames}; fastest frame ${Math.min(...frame).toFixed(1)} ms)`);
