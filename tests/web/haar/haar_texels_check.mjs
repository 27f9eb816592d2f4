// node haar_texels_check.mjs GENDIR BAKE.glb PRT-DATA.js QUERY.json: a per-texel Haar bake relit
// in JavaScript as the page and prtkit-three relight it (web/src/haar_texels.js, at the texel
// normals prt web wrote beside the bake), for tests/web/test_haar_web.cpp to hold to the library
// (render::texelRelight's normals, haar::turnedLight, relight::relightHaar). QUERY = { rotate:
// [[X, Y, Z] degrees...], terms: K }. Prints one JSON object:
//   refusal    what the page's reader says of the bake without its texel points
//   rows       the rows it read (the lightmap's texels)
//   radiance   per rotation, every texel relit (haarTexelDrawing's relight), row by row
// The sources run as they are bundled: 'prt:' imports resolve into GENDIR (bake_verdicts/hooks.mjs).
import fs from 'node:fs';
import path from 'node:path';
import { register } from 'node:module';

const [gen, bakeFile, dataFile, queryFile] = process.argv.slice(2);
if (!queryFile) {
  console.error('usage: node haar_texels_check.mjs GENDIR BAKE.glb PRT-DATA.js QUERY.json');
  process.exit(2);
}
register('../bake_verdicts/hooks.mjs', import.meta.url, { data: { gen: path.resolve(gen) } });
const web = new URL('../../../web/', import.meta.url);
const { parseBake } = await import(new URL('src/bake.js', web));
const { rotationEulerXYZ } = await import(new URL('src/sh.js', web));
const { base64Bytes, decodeRgbe } = await import(new URL('src/environment.js', web));
const { environmentCube, turnedLight } = await import(new URL('src/haar_light.js', web));
const { haarTexelDrawing } = await import(new URL('src/haar_texels.js', web));

const bytes = () => { const b = fs.readFileSync(bakeFile); return b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength); };
const name = path.basename(bakeFile);
const data = (() => { const s = fs.readFileSync(dataFile, 'utf8'); return JSON.parse(s.slice(s.indexOf('=') + 1).trim().replace(/;$/, '')); })();
const env = data.environments[0];
const q = JSON.parse(fs.readFileSync(queryFile, 'utf8'));
const limits = { maxTextureSize: 16384, maxBands: 32, maxFragmentBands: 32 };
// A host that makes plain objects: the drawing's materials are not what is checked here.
const host = { stages: {}, material: ({ uniforms }) => ({ uniforms, dispose() {} }) };

console.warn = () => {};
try {
  let refusal = '';
  try {
    await parseBake(bytes(), name, limits);
  } catch (e) {
    refusal = e.message;
  }
  const p = data.bake.texelPoints;
  const beside = () => { const b = fs.readFileSync(path.join(path.dirname(dataFile), p.file)); return b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength); };
  const points = new Float32Array(p.base64 ? base64Bytes(p.base64).buffer : beside());
  const bake = await parseBake(bytes(), name, limits, { texelPoints: points });
  const t = bake.transfers[0], n = t.haar.resolution;
  const cube = environmentCube(env.haar.resolution, base64Bytes(env.haar.rgbe), env.haar.sh, env.name, decodeRgbe);
  const drawing = haarTexelDrawing(bake, limits, host);
  const radiance = q.rotate.map((r) => Array.from(drawing.relight(t, turnedLight(cube, n, q.terms, rotationEulerXYZ(...r)))));
  console.log(JSON.stringify({ refusal, rows: bake.lightmap.width * bake.lightmap.height, radiance }));
} catch (e) {
  console.log(JSON.stringify({ error: String(e && e.stack ? e.stack : e) }));
  process.exit(1);
}
