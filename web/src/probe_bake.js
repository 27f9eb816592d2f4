// Probe bakes in the page and prtkit-three (docs/probes.md; bake format 7): a grid of points in
// space, at each a B² × B² matrix per colour channel, (M_p)_ij = ∫ Y_i(ω) V(p,ω) Y_j(ω) dω (+ the
// light the scene's surfaces bounce to p), so that the SH of the light arriving at p is
// L'_p = M_p L (Sloan, Kautz & Snyder 2002, §7). Probe (x, y, z) sits at origin + (x·sx, y·sy,
// z·sz) and is row x + nx·(y + ny·z) (include/prt/transfer/probe_grid.hpp).
//
// This file checks a probe grid's JSON as io::decodeBake checks it (src/io/bake_file.cpp and
// transfer/probe_grid.cpp's checkProbeGrid, with the library's limits from 'prt:constants'), and
// reads a checked probe bake's matrices (dense, or CPCA-compressed and reconstructed here as
// Transfer::reconstructRow does) and mesh. Relighting them is probe_lighting.js.
import { bands as kBands, maxShaderClusters, probeGrid as kGrid } from 'prt:constants';
import { readCompressed } from './compressed.js';
import { meshParts } from './parts.js';
import { preferenceOrder, readDenseMatrices } from './transfer.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

const isObject = (o) => o !== null && typeof o === 'object' && !Array.isArray(o);
const has = (o, key) => isObject(o) && o[key] !== undefined && o[key] !== null;

/** Probes in a grid { count: [nx, ny, nz] }. */
export function probeCount(grid) {
  return grid.count[0] * grid.count[1] * grid.count[2];
}

/**
 * decodeBake's probe-grid branch: `prt` the bake's object, `where` its name in messages,
 * `version` the file's format version, `texels` whether the file also holds a lightmap, `r` the
 * reader of bake.js (r.fail, r.member). Returns { origin, spacing, count } (arrays of three;
 * origin and spacing as the floats the library keeps). Throws one line naming the file.
 */
export function checkProbeGridDocument(prt, where, version, texels, r) {
  if (version < kGrid.firstVersion)
    r.fail(`${where} holds a probe grid in a version ${version} file (probes need version ${kGrid.firstVersion})`);
  if (texels || has(prt, 'vertexRange'))
    r.fail(`${where} has a probeRange beside a ${texels ? 'texelRange' : 'vertexRange'}`);
  const gw = `${where}.probeGrid`, g = r.member(prt, 'probeGrid', where);
  const triple = (key) => {
    const a = r.member(g, key, gw);
    if (!Array.isArray(a) || a.length !== 3) r.fail(`${gw}.${key} is not an array of 3 numbers`);
    return a;
  };
  const origin = triple('origin'), spacing = triple('spacing'), count = triple('count');
  const grid = { origin: [0, 0, 0], spacing: [0, 0, 0], count: [0, 0, 0] };
  for (let a = 0; a < 3; ++a) {
    const finite = (v, what) => {
      if (typeof v !== 'number' || !Number.isFinite(v) || Math.abs(v) > kGrid.maxNumber)
        r.fail(`${gw}.${what}[${a}] is not a finite number`);
      return Math.fround(v);  // the library keeps a float
    };
    grid.origin[a] = finite(origin[a], 'origin');
    grid.spacing[a] = finite(spacing[a], 'spacing');
    if (!(grid.spacing[a] > 0)) r.fail(`${gw}.spacing[${a}] is not positive`);
    const n = count[a];
    if (!(typeof n === 'number' && Number.isInteger(n) && n >= 1 && n <= kGrid.maxSide))
      r.fail(`${gw}.count[${a}] is not an integer in 1..${kGrid.maxSide}`);
    grid.count[a] = n;
  }
  if (probeCount(grid) > kGrid.maxProbes)
    r.fail(`${gw}: a probe grid of ${probeCount(grid)} probes is over the ${kGrid.maxProbes} a bake holds`);
  return grid;
}

/** The grid of a checked bake object, as checkProbeGridDocument returns it. */
function gridOf(prt) {
  const g = prt.probeGrid;
  return { origin: g.origin.map(Math.fround), spacing: g.spacing.map(Math.fround), count: g.count.slice() };
}

/** A CPCA-compressed transfer's rows made dense (Transfer::reconstructRow): x̂_p = M_k +
 *  Σ_j w_pj B_kj, summed in j order, for every probe p of cluster k. */
async function reconstructedMatrices(gltf, entry, shape, probes, name) {
  const c = await readCompressed(gltf, gltf.parser.json, entry, shape, probes, name, maxShaderClusters);
  const D = c.stride, N = c.basisCount, out = new Float32Array(probes * D);
  for (let p = 0; p < probes; ++p) {
    const k = c.cluster[p], m = k * D, w = p * N;
    for (let i = 0; i < D; ++i) {
      let s = c.means[m + i];
      for (let j = 0; j < N; ++j) s = Math.fround(s + Math.fround(c.weights[w + j] * c.basis[(k * N + j) * D + i]));
      out[p * D + i] = s;
    }
  }
  return out;
}

/** One transfer of a probe bake: { key, mode, layout: 'matrix', bands, channels, compressed,
 *  matrices: Float32Array(P · B⁴ · C) — probe p's element (i, j), channel c at
 *  ((p·B² + i)·B² + j)·C + c, row i arriving, column j source }. */
async function readProbeTransfer(gltf, entry, probes, name) {
  const s = entry.settings || {};
  const bands = s.bands, channels = s.channels, mode = String(s.mode);
  if (!Number.isInteger(bands) || bands < 1 || bands > kBands.maxLibrary || (channels !== 1 && channels !== 3))
    fail(name, `the ${mode} probe transfer has ${bands} bands and ${channels} channels`);
  const shape = { mode, layout: 'matrix', bands, channels, matrix: true, perPixel: false };
  const count = probes * bands ** 4 * channels;
  const matrices = entry.compressed
    ? await reconstructedMatrices(gltf, entry, shape, probes, name)
    : await readDenseMatrices(gltf, entry, count, name, `the ${mode} probe transfer`);
  for (let i = 0; i < matrices.length; ++i) if (!Number.isFinite(matrices[i])) fail(name, `the ${mode} probe transfer: value ${i} is not finite`);
  return { key: `${mode} matrix`, mode, layout: 'matrix', bands, channels, compressed: !!entry.compressed,
           probes: true, matrices };
}

/**
 * Reads a checked probe bake from GLTFLoader's result: { name, grid: { origin, spacing, count },
 * probes: true, transfers (the library's preference order), parts (meshParts': the scene's mesh,
 * kept in the file; their normals and albedo stay), maxBands, vertices, triangles, centre,
 * radius, lightmap: null }. The grid must be complete (prt merge joins pieces first).
 */
export async function readProbeBake(gltf, prt, name) {
  const grid = gridOf(prt), probes = probeCount(grid), range = prt.probeRange || {};
  if (range.first !== 0 || range.count !== probes)
    fail(name, `holds transfer for probes ${range.first}..${range.first + range.count} of ${probes} only (merge the pieces with prt merge first)`);
  const read = [];
  for (const e of prt.transfers) read.push(await readProbeTransfer(gltf, e, probes, name));
  const transfers = preferenceOrder(read);
  const mesh = meshParts(gltf, prt, name);
  for (const p of mesh.parts) {
    if (!p.geometry.getAttribute('normal')) fail(name, `part '${p.name}' has no normals (probes shade it)`);
    for (const a of Object.keys(p.geometry.attributes))
      if (!['position', 'normal', 'color'].includes(a)) p.geometry.deleteAttribute(a);
  }
  return { name, grid, probes: true, transfers, parts: mesh.parts, lightmap: null, texelPoints: null,
           maxBands: Math.max(...transfers.map((t) => t.bands)), vertices: mesh.vertices,
           triangles: mesh.triangles, centre: mesh.centre, radius: mesh.radius };
}
