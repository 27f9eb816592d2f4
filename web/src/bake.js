// Reading a prtkit bake (.glb, docs/formats-bake.md) in the page: three.js's GLTFLoader parses
// the glTF (it keeps the custom `_PRT_<MODE>_T<k>` VEC4 attributes, lower-cased), this file
// checks what the page needs and packs each transfer into a data texture. Every problem is an
// Error with one line naming the file; nothing here touches the scene.
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

import { packWeights, readCompressed } from './compressed.js';

// Version 1: vector transfer as vertex attributes; 2 adds glossy matrices (drawn CPCA-compressed
// only); 3 adds CPCA-compressed transfer (prt compress), which the page relights in the
// compressed space (compressed.js); 4 stores the material as structured fields (the page takes
// the material's kernels from prt-data.js, not from the file).
export const kFormatVersions = [1, 2, 3, 4];
// Bands of the glossy shader's SH arrays (64 coefficients; relight/glossy_shader.hpp).
export const kMaxGlossyBands = 8;

const kModeNames = { unshadowed: 'UNSHADOWED', shadowed: 'SHADOWED', interreflected: 'INTERREFLECTED' };

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/**
 * Parses GLB bytes into { name, parts: [{ geometry, hasAlbedo, transfer: { mode → Float32Array
 * texels } }], transfers: [{ mode, bands, channels, texelsPerVertex }], maxBands, vertices,
 * triangles, centre, radius }. `limits` = { maxTextureSize, maxBands }.
 */
export async function parseBake(buffer, name, limits) {
  if (!(buffer instanceof ArrayBuffer) || buffer.byteLength < 20)
    fail(name, 'is not a glTF binary (.glb) file (too short)');
  const head = new DataView(buffer);
  if (head.getUint32(0, true) !== 0x46546c67)  // "glTF"
    fail(name, 'is not a glTF binary (.glb) file (no glTF magic)');
  if (head.getUint32(8, true) !== buffer.byteLength)
    fail(name, `is truncated or padded: the header says ${head.getUint32(8, true)} bytes, the file has ${buffer.byteLength}`);
  let gltf;
  try {
    gltf = await new GLTFLoader().parseAsync(buffer, '');
  } catch (e) {
    fail(name, `cannot be read as glTF (${String(e && e.message ? e.message : e).split('\n')[0]})`);
  }
  const json = gltf.parser.json;
  const prt = json.extras && json.extras.prtkit;
  if (!prt) fail(name, 'is a glTF file but not a prtkit bake (no extras.prtkit; write one with prt bake)');
  if (!kFormatVersions.includes(prt.formatVersion))
    fail(name, `bake format version ${prt.formatVersion} is not supported by this page (it reads versions ${kFormatVersions.join(', ')})`);
  const transfers = Array.isArray(prt.transfers) ? prt.transfers : [];
  if (transfers.length === 0) fail(name, 'the bake holds no transfer (bake it with prt bake --mode ...)');
  const range = prt.vertexRange || {};
  if (range.first !== 0 || range.count !== prt.vertexCount)
    fail(name, `holds transfer for vertices ${range.first}..${range.first + range.count} of ${prt.vertexCount} only (merge the pieces with prt merge first)`);

  const modes = [];
  for (const t of transfers) {
    const s = t.settings || {};
    const mode = String(s.mode);
    if (!kModeNames[mode]) fail(name, `unknown transfer mode '${mode}'`);
    const bands = s.bands, channels = s.channels;
    if (!Number.isInteger(bands) || bands < 1 || bands > limits.maxBands)
      fail(name, `the ${mode} transfer has ${bands} bands; this page draws 1..${limits.maxBands} here (the light must fit in the vertex shader's uniforms)`);
    if (channels !== 1 && channels !== 3) fail(name, `the ${mode} transfer has ${channels} channels (1 or 3 expected)`);
    const matrix = (s.layout || 'vector') === 'matrix';
    if (!matrix && (s.layout || 'vector') !== 'vector') fail(name, `the ${mode} transfer has an unknown layout '${s.layout}'`);
    // Glossy matrices only CPCA-compressed: 16·⌈(N+1)/4⌉ bytes per vertex instead of 4·B⁴.
    if (matrix && !t.compressed)
      fail(name, `the ${mode} transfer holds dense glossy matrices; this page draws them CPCA-compressed only (prt compress)`);
    if (matrix && bands > kMaxGlossyBands)
      fail(name, `the ${mode} transfer's glossy matrices have ${bands} bands; this page draws 1..${kMaxGlossyBands}`);
    const n = bands * bands;
    const entry = { mode, bands, channels, matrix, prefix: `_prt_${kModeNames[mode].toLowerCase()}_t`,
                    attributes: Math.ceil((n * channels) / 4),
                    texelsPerVertex: channels === 1 ? Math.ceil(n / 4) : n, compressed: null };
    if (t.compressed) entry.compressed = await readCompressed(gltf, json, t, entry, prt.vertexCount, name);
    modes.push(entry);
  }

  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  if (meshes.length === 0) fail(name, 'holds no triangle mesh');
  const parts = [];
  let vertices = 0, triangles = 0;
  const lo = new THREE.Vector3(Infinity, Infinity, Infinity), hi = lo.clone().negate();
  for (const m of meshes) {
    const g = m.geometry;
    const pos = g.getAttribute('position');
    if (!pos || !g.index) fail(name, `part '${m.name}' has no positions or indices`);
    const V = pos.count;
    vertices += V;
    triangles += g.index.count / 3;
    g.computeBoundingBox();
    lo.min(g.boundingBox.min);
    hi.max(g.boundingBox.max);
    const part = { geometry: g, hasAlbedo: !!g.getAttribute('color'), texels: {} };
    // The part's first vertex in the file's (global) order: its POSITION window's offset.
    const assoc = gltf.parser.associations.get(m);
    const posAccessor = assoc && json.meshes[assoc.meshes].primitives[assoc.primitives || 0].attributes.POSITION;
    const first = posAccessor !== undefined ? (json.accessors[posAccessor].byteOffset || 0) / 12 : -1;
    for (const t of modes) {
      if (t.compressed) {
        if (!(first >= 0 && first + V <= prt.vertexCount)) fail(name, `part '${m.name}' has no place in the vertex order`);
        part.texels[t.mode] = packWeights(t.compressed, first, V, limits, name, t.mode);
        continue;
      }
      const data = new Float32Array(V * t.texelsPerVertex * 4);
      const attrs = [];
      for (let k = 0; k < t.attributes; ++k) {
        const a = g.getAttribute(t.prefix + k);
        if (!a || a.itemSize !== 4 || a.count !== V)
          fail(name, `part '${m.name}' lacks the ${t.mode} transfer attribute ${t.prefix.toUpperCase()}${k}`);
        attrs.push(a);
      }
      const row = new Float32Array(t.attributes * 4);
      for (let v = 0; v < V; ++v) {
        for (let k = 0; k < t.attributes; ++k) {
          const a = attrs[k];
          row[4 * k] = a.getX(v), row[4 * k + 1] = a.getY(v), row[4 * k + 2] = a.getZ(v), row[4 * k + 3] = a.getW(v);
        }
        const dst = v * t.texelsPerVertex * 4;
        if (t.channels === 1) data.set(row.subarray(0, t.texelsPerVertex * 4), dst);
        else
          for (let i = 0; i < t.bands * t.bands; ++i)
            data[dst + 4 * i] = row[3 * i], data[dst + 4 * i + 1] = row[3 * i + 1], data[dst + 4 * i + 2] = row[3 * i + 2];
      }
      const W = Math.min(limits.maxTextureSize, 4096);
      const texels = V * t.texelsPerVertex;
      const H = Math.max(1, Math.ceil(texels / W));
      if (H > limits.maxTextureSize)
        fail(name, `the ${t.mode} transfer needs ${texels} texels, more than this WebGL's ${limits.maxTextureSize}² textures hold (use fewer bands)`);
      const padded = new Float32Array(W * H * 4);
      padded.set(data);
      part.texels[t.mode] = { data: padded, width: W, height: H };
    }
    // The transfer attributes are in the textures now; drop them so they are not uploaded.
    for (const t of modes) if (!t.compressed) for (let k = 0; k < t.attributes; ++k) g.deleteAttribute(t.prefix + k);
    // Normals stay for glossy matrices (the lobe about the reflected view).
    const keep = ['position', 'color'].concat(modes.some((t) => t.matrix) ? ['normal'] : []);
    for (const a of Object.keys(g.attributes)) if (!keep.includes(a)) g.deleteAttribute(a);
    if (modes.some((t) => t.matrix) && !g.getAttribute('normal')) fail(name, `part '${m.name}' has no normals (glossy transfer needs them)`);
    parts.push(part);
  }
  if (vertices !== prt.vertexCount) fail(name, `has ${vertices} vertices but extras.prtkit says ${prt.vertexCount}`);
  // render::frameMesh: the box's centre, radius to the farthest vertex.
  const centre = lo.clone().add(hi).multiplyScalar(0.5);
  let r2 = 0;
  for (const p of parts) {
    const pos = p.geometry.getAttribute('position');
    for (let v = 0; v < pos.count; ++v) {
      const dx = pos.getX(v) - centre.x, dy = pos.getY(v) - centre.y, dz = pos.getZ(v) - centre.z;
      r2 = Math.max(r2, dx * dx + dy * dy + dz * dz);
    }
  }
  // Richest first, as prt render picks by default: interreflected, shadowed, unshadowed.
  const rank = { interreflected: 0, shadowed: 1, unshadowed: 2 };
  modes.sort((a, b) => rank[a.mode] - rank[b.mode]);
  return { name, parts, transfers: modes, maxBands: Math.max(...modes.map((t) => t.bands)),
           vertices, triangles, centre, radius: Math.max(Math.sqrt(r2), 1e-6) };
}

/**
 * Parses an SH light JSON (docs/formats-light.md): { bands, coefficients: [[r, g, b], ...] }.
 * Returns { bands, coeffs: Float32Array(B² × 3) }.
 */
export function parseLightJson(text, name) {
  let j;
  try {
    j = JSON.parse(text);
  } catch (e) {
    fail(name, `is not JSON (${e.message})`);
  }
  if (!j || typeof j !== 'object' || !('coefficients' in j))
    fail(name, 'is not an SH light (no "coefficients"; write one with prt light)');
  const B = j.bands, c = j.coefficients;
  if (!Number.isInteger(B) || B < 1 || B > 32) fail(name, `"bands" is ${JSON.stringify(B)}, not 1..32`);
  if (!Array.isArray(c) || c.length !== B * B)
    fail(name, `has ${Array.isArray(c) ? c.length : 0} coefficients but ${B} bands need ${B * B}`);
  const coeffs = new Float32Array(B * B * 3);
  c.forEach((row, i) => {
    if (!Array.isArray(row) || row.length !== 3 || !row.every((v) => typeof v === 'number' && Number.isFinite(v)))
      fail(name, `coefficient ${i} is not three finite numbers`);
    coeffs.set(row, 3 * i);
  });
  return { bands: B, coeffs };
}

/**
 * Parses the GAMES202 course's light.txt (docs/formats-light.md): B² lines "r g b", nothing else.
 */
export function parseLightTxt(text, name) {
  const lines = text.split(/\r?\n/).map((l) => l.trim()).filter((l) => l.length > 0);
  const B = Math.round(Math.sqrt(lines.length));
  if (lines.length === 0 || B * B !== lines.length)
    fail(name, `has ${lines.length} lines; a light.txt has B² lines of "r g b"`);
  const coeffs = new Float32Array(lines.length * 3);
  lines.forEach((l, i) => {
    const v = l.split(/\s+/).map(Number);
    if (v.length !== 3 || !v.every(Number.isFinite)) fail(name, `line ${i + 1} is not three numbers`);
    coeffs.set(v, 3 * i);
  });
  return { bands: B, coeffs };
}
