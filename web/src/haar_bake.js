// Reading a Haar bake (prt bake --basis haar; docs/formats-bake.md, "Haar transfer") in the page
// and prtkit-three: its settings and its four quantised accessors — five with an inter-reflected
// transfer's bounce (format 9) — checked as the library's reader checks them (io/bake_schema.cpp
// readSettings, transfer_codecs.cpp's HaarRowsCodec, haar::checkRow and Transfer::check), then
// the rows decoded into the form the library holds in memory — per row its kind (0: the occluded
// part D = U − T, 1: the visible part T), `terms` (index, value) float pairs and, inter-reflected,
// its bounce (B² SH coefficients × C channels, channels innermost) — for haar_relight.js. What
// the browser viewers relight (haar_scene.js, prtkit-three's HaarLighting): per vertex, or per
// texel with the texel points prt web ships beside its bake (haar_texels.js), a cube of at most
// haar.maxTurnedResolution² a face (the light is turned from the environment's cube 4 times
// finer), no base-colour texture; as prt web holds a bake to (apps/prt/web.cpp,
// checkHaarForPage), each refusal one line naming the file.
import { domains, haar as kHaar, modes } from 'prt:constants';
import { preferenceOrder } from './transfer.js';
import { meshParts } from './parts.js';
import { validResolution } from './haar_light.js';
import { texelNormalsOf } from './haar_texels.js';
import { rowDomain, useLightmapUvs } from './row_domain.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

const kUbyte = 5121, kShort = 5122, kUshort = 5123, kUint = 5125, kFloat = 5126;
/** The first format whose Haar transfer may hold a bounce (settings.haar.bounceBands). */
const kFirstBounceVersion = kHaar.firstBounceVersion;

/** Whether transfer entry `t` (its JSON) is Haar. */
export const isHaarEntry = (t) => t && t.settings && t.settings.basis === 'haar';

/**
 * The Haar part of bake.js's checkTransfers for entry `t` (settings `s`, at `tw`/`sw` in the
 * JSON), `rows` rows of a bake of format `version`: { resolution, terms, bounceBands, channels }
 * after checking the shape (haar.resolution a power of two in range, terms 1..6 N², bounceBands
 * absent or 1..5 — from format 9, exactly when the transfer is interreflected with bounces ≥ 1 —
 * vector layout, not probes, one channel or, with a bounce, three) and every row of the four
 * accessors (KIND ubyte 0/1, SCALE finite ≥ 0, INDEX ushort — uint past 6·104² — below 6 N²,
 * ascending over the kept terms, 0 in the padding, VALUE short ≥ −32767) and of the fifth, the
 * bounce's (BOUNCE float, rows · B² · C, finite). `ar`, `r`: bake.js's accessor reader and schema
 * reader.
 */
export function checkHaarTransfer(t, s, tw, sw, version, layout, domain, rows, ar, r) {
  if (version < kHaar.firstVersion)
    r.fail(`${sw} is Haar transfer in a version ${version} file (Haar needs version ${kHaar.firstVersion})`);
  const hw = `${sw}.haar`, h = r.member(s, 'haar', sw);
  if (h === null || typeof h !== 'object' || Array.isArray(h)) r.fail(`${hw} is not an object`);
  const n = r.integer(h, 'resolution', hw, kHaar.minResolution, kHaar.maxResolution);
  const count = 6 * n * n, terms = r.integer(h, 'terms', hw, 1, count);
  if (!validResolution(n))
    r.fail(`${sw}: the Haar cube's resolution must be a power of two from ${kHaar.minResolution} to ${kHaar.maxResolution}, got ${n}`);
  // The bounce of an inter-reflected row (format 9): SH of 1..5 bands, recorded only when there is one.
  const B = h.bounceBands !== undefined && h.bounceBands !== null ? r.integer(h, 'bounceBands', hw, 1, kHaar.unshadowedBands) : 0;
  if (B > 0 && version < kFirstBounceVersion)
    r.fail(`${hw}.bounceBands: inter-reflected Haar transfer in a version ${version} file (its bounce needs version ${kFirstBounceVersion})`);
  // A row holds a bounce exactly when its transfer bounced light (inter-reflected, bounces ≥ 1).
  const bounced = s.mode === 'interreflected' && r.integer(s, 'bounces', sw, 0, Number.MAX_SAFE_INTEGER) >= 1;
  if ((B > 0) !== bounced)
    r.fail(B > 0 ? `${hw} holds a bounce, but the transfer is ${s.mode} with ${s.bounces} bounces`
                 : `${hw}.bounceBands is missing: the transfer is interreflected with ${s.bounces} bounces`);
  if (layout !== 'vector' || domain === domains[2]) r.fail(`${sw}: Haar transfer is diffuse (vector rows) over vertices or texels`);
  const channels = r.integer(s, 'channels', sw, 1, 3);
  if (channels === 2) r.fail(`${sw}.channels must be 1 or 3`);
  if (channels !== 1 && B === 0)
    r.fail(`${sw}: Haar transfer is scalar, and RGB only in its inter-reflected bounce, got ${channels} channels`);
  const acc = r.member(t, 'accessors', tw), want = B > 0 ? 5 : 4;
  if (!Array.isArray(acc) || acc.length !== want)
    r.fail(`${tw}.accessors must list ${want} accessors for the Haar rows (kind, scale, index, value${B > 0 ? ', bounce' : ''})`);
  acc.forEach((i, k) => { if (!(Number.isInteger(i) && i >= 0 && i <= 2147483647)) r.fail(`${tw}.accessors[${k}] is not an index`); });
  const what = `${s.mode} Haar rows`, K = rows * terms;
  const kind = ar.exact(acc[0], 1, kUbyte, rows, `${what} kinds`);
  const scale = ar.exact(acc[1], 1, kFloat, rows, `${what} scales`);
  const index = ar.exact(acc[2], 1, count > 65536 ? kUint : kUshort, K, `${what} indices`);
  const value = ar.exact(acc[3], 1, kShort, K, `${what} values`);
  for (let i = 0; i < rows; ++i) {
    if (!Number.isFinite(scale[i]) || scale[i] < 0) r.fail(`${tw}: Haar row ${i} has scale ${scale[i]} (a finite number >= 0)`);
    if (kind[i] !== 0 && kind[i] !== 1) r.fail(`${tw}: ${what}: row ${i}: its kind must be 0 (occluded part) or 1 (visible part)`);
    let last = -1;
    for (let k = 0; k < terms; ++k) {
      const q = value[i * terms + k], x = index[i * terms + k];
      const term = `${tw}: ${what}: row ${i}, term ${k}`;
      if (q < -kHaar.valueSteps) r.fail(`${tw}: Haar row ${i}, term ${k}: value ${q} is off the grid (-${kHaar.valueSteps}..${kHaar.valueSteps})`);
      if (x >= count) r.fail(`${term}: the index is not a coefficient of the ${n}² cube`);
      if (q === 0 || scale[i] === 0) {
        if (x !== 0) r.fail(`${term}: a padding term (value 0) must have index 0`);
        continue;
      }
      if (x <= last) r.fail(`${term}: the indices of the kept terms must ascend`);
      last = x;
    }
  }
  if (B > 0) {
    const S = B * B * channels;
    const bounce = ar.exact(acc[4], 1, kFloat, rows * S, `${what} bounce values`);
    for (let i = 0; i < rows; ++i)
      for (let k = 0; k < S; ++k)
        if (!Number.isFinite(bounce[i * S + k])) r.fail(`${tw}: ${what}: row ${i}: bounce value ${k} is not finite`);
  }
  return { resolution: n, terms, bounceBands: B, channels };
}

/** One Haar transfer's rows as the library holds them: Float32Array(rows × stride), a row its
 *  kind, its `terms` (index, value) pairs and its bounce's `bounce` floats (0: none). */
async function readRows(gltf, entry, rows, terms, bounce, name) {
  const parts = [], accessors = [[0, 'kinds'], [1, 'scales'], [2, 'indices'], [3, 'values']].concat(bounce > 0 ? [[4, 'bounce values']] : []);
  for (const [k, what] of accessors) {
    const a = await gltf.parser.getDependency('accessor', entry.accessors[k]);
    const want = k < 2 ? rows : k < 4 ? rows * terms : rows * bounce;
    if (!a || a.itemSize !== 1 || a.array.length !== want) fail(name, `the Haar ${what} hold ${a ? a.array.length : 0} values, ${want} expected`);
    parts.push(a.array);
  }
  const [kind, scale, index, value, sh] = parts, pairs = 1 + 2 * terms, stride = pairs + bounce;
  const out = new Float32Array(rows * stride);
  for (let i = 0; i < rows; ++i) {
    out[i * stride] = kind[i];
    for (let k = 0; k < terms; ++k) {
      out[i * stride + 1 + 2 * k] = index[i * terms + k];
      // haar::dequantizeHaarValue: float(scale · q / 32767), in double.
      out[i * stride + 2 + 2 * k] = (scale[i] * value[i * terms + k]) / kHaar.valueSteps;
    }
    if (bounce > 0) out.set(sh.subarray(i * bounce, (i + 1) * bounce), i * stride + pairs);
  }
  return out;
}

/**
 * A checked bake holding Haar transfer (bake.js's readBake, GLTFLoader's `gltf`, the bake's
 * object `prt`) as the browser viewers relight it: { name, haar: true, transfers (in the
 * library's preference order: [{ key, mode, layout, bands: 0, channels (the bounce's: 1, or 3
 * for coloured inter-reflection), haar: { resolution, terms, bounceBands (0: no bounce) }, rows
 * (readRows'), kd (the recipe's kd or null), perPixel, lightmap, describe }]), parts (each keeping
 * its positions, normals and colours, and per texel its lightmap UVs as prtLightmapUv), lightmap
 * ({ width, height } per texel, else null), texelNormals (per texel: extras.texelPoints' normals,
 * three floats a texel; else null), maxBands: 0, vertices, triangles, centre, radius }.
 * extras.texelPoints: what prt web writes beside a per-texel bake (render::packTexelPoints' twelve
 * floats a texel); without them a per-texel bake is refused.
 */
export async function readHaarBake(gltf, prt, name, extras = {}) {
  const entries = prt.transfers;
  if (!entries.every(isHaarEntry)) fail(name, 'holds Haar and SH transfer; the viewers relight one basis a file');
  // The domain: the vertices, or the texels of one lightmap, relit at the texels' normals prt
  // web ships beside its bake (haar_texels.js); whole.
  const domain = rowDomain(prt, name), { lightmap, rowCount } = domain;
  if (lightmap && !extras.texelPoints) fail(name, kPageHaarTexelsRefusal);
  const texelNormals = lightmap ? texelNormalsOf(extras.texelPoints, rowCount, name) : null;
  const json = gltf.parser.json;
  const pbr = Array.isArray(json.materials) && json.materials[0] && json.materials[0].pbrMetallicRoughness;
  if (pbr && pbr.baseColorTexture !== undefined)
    fail(name, 'holds Haar transfer on a mesh with a base-colour texture, which prt render folds into the vertices\' albedo; the browser viewers do not read a texture\'s pixels (view it with prt view)');
  const read = [];
  for (const e of entries) {
    const s = e.settings, n = s.haar.resolution, terms = s.haar.terms, bounceBands = Number(s.haar.bounceBands || 0);
    const channels = Number(s.channels) === 3 ? 3 : 1, h = { resolution: n, terms, bounceBands };
    if (n > kHaar.maxTurnedResolution)
      fail(name, `holds Haar transfer over a ${n}² cube; the page turns its light from a cube ${kHaar.fineCubeFactor} times finer and takes cubes up to ${kHaar.maxTurnedResolution}² (bake with --resolution ${kHaar.maxTurnedResolution} or less, or view it with prt view)`);
    const mode = modes.find((m) => m.name === s.mode);
    const kd = s.material && Array.isArray(s.material.kd) ? s.material.kd : null;
    read.push({ key: `${mode.name} vector`, mode: mode.name, layout: 'vector', bands: 0, channels, matrix: false,
                compressed: null, haar: h, kd, perPixel: !!lightmap, lightmap,
                rows: await readRows(gltf, e, rowCount, terms, bounceBands * bounceBands * channels, name),
                describe: describeHaarTransfer(h, channels, lightmap) });
  }
  const transfers = preferenceOrder(read);
  const mesh = meshParts(gltf, prt, name);
  for (const p of mesh.parts) {
    const g = p.geometry;
    if (!g.getAttribute('normal')) fail(name, `part '${p.name}' has no normals (a Haar row's unshadowed light is its normal's)`);
    useLightmapUvs(p, domain, prt, name);  // per texel, where the lightmap stage reads them
    for (const a of Object.keys(g.attributes))
      if (!['position', 'normal', 'color', 'prtLightmapUv'].includes(a)) g.deleteAttribute(a);
  }
  return { name, haar: true, transfers, parts: mesh.parts, lightmap, texelNormals, texelPoints: null, maxBands: 0,
           vertices: mesh.vertices, triangles: mesh.triangles, centre: mesh.centre, radius: mesh.radius };
}

/** Why the browser viewers refuse a per-texel Haar bake without its texel points. */
export const kPageHaarTexelsRefusal =
  'holds per-texel Haar transfer, relit at its texels\' normals, which prt web writes beside its own bake (write a page for this file with prt web; prt view and prt render draw it)';

/** A Haar transfer in one phrase (TransferShape::describe's words): its cube, its terms and, when
 *  inter-reflected, its bounce. */
export function describeHaarTransfer(h, channels, lightmap = null) {
  const bounce = h.bounceBands > 0 ? `, bounce in ${h.bounceBands} SH bands (${channels === 3 ? 'RGB' : 'scalar'})` : '';
  const where = lightmap ? `, drawn per pixel from a ${lightmap.width} x ${lightmap.height} lightmap` : '';
  return `Haar ${h.resolution}² cube, ${h.terms} terms a ${lightmap ? 'texel' : 'vertex'}${bounce}, relit on the CPU${where}`;
}
