// The one reader of a transfer in the page — one dispatch, as the library's
// (include/prt/relight/shader_transfer.hpp): shaderPath says once how a transfer is drawn
// (dense vectors, CPCA-compressed vectors or matrices on the GPU; dense per-vertex matrices on
// the CPU, through an irradiance encoding: CpuRadiance, encoded_diffuse.js),
// and every later step — reading its rows from the glTF, packing a part's texels, the per-frame
// work, the shader and its uniforms (draw.js) — is looked up by that path, never re-decided from
// the layout or the representation. The pick order is the library's (transferPreference,
// generated into 'prt:constants').
// Per-texel transfer (t.perPixel: rows are the texels of a W × H lightmap, row y·W + x) takes
// the same paths and the same per-row packing, once for the whole bake (every part reads the one
// lightmap); draw.js gives it the per-pixel stage (shaders/prt_lightmap.glsl). Its glossy
// matrices (CPCA only) are shaded at the texels' points, which only prt web can compute: they
// come beside its bake (bake.js, texelPoints), and without them the matrices are refused.
import { bands as kBands, layouts, maxShaderClusters, modes, perTexelMatricesRefusal, shaderPaths,
  transferPreference } from 'prt:constants';
import { bandLimitMessage } from './messages.js';
import { clusterTableImage, packWeights, projectClusters, readCompressed } from './compressed.js';
import { textureShape } from './texels.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/** The page's GPU path of a transfer (relight::shaderPath with matrices on the GPU), or throws
 *  the line saying why the page cannot draw it. */
export function shaderPath(shape, compressed, name, limits) {
  const what = `the ${shape.mode} ${shape.layout} transfer`;
  if (shape.perPixel && shape.layout === 'matrix') {
    // CPCA-compressed, each tap shaded at its texel's point (prt web's texelPoints, bake.js).
    if (!compressed)
      fail(name, `the ${shape.mode} transfer holds dense per-texel glossy matrices; the browser viewers draw them CPCA-compressed only (prt compress)`);
    if (!shape.hasTexelPoints) fail(name, `${perTexelMatricesRefusal} (the ${shape.mode} transfer)`);
    if (shape.bands > kBands.maxShaderGlossy)
      fail(name, bandLimitMessage(`the ${shape.mode} transfer's glossy matrices`, shape.bands, 'the shaders\' glossy response', kBands.maxShaderGlossy));
    return 'CpcaMatrix';
  }
  if (shape.perPixel) {
    // Relit per pixel: the light must fit the fragment shader's uniforms.
    if (shape.bands > limits.maxFragmentBands)
      fail(name, bandLimitMessage(what, shape.bands, 'this page\'s per-pixel light (the fragment shader\'s uniforms)', limits.maxFragmentBands));
    return compressed ? 'CpcaVector' : 'DenseVector';
  }
  if (shape.layout === 'matrix') {
    // Dense matrices are 4·B⁴ bytes per vertex (2.5 KB at 5 bands); compressed 16·⌈(N+1)/4⌉.
    // prtkit's shaders draw them compressed; dense, the browser viewers relight them on the CPU
    // and draw their diffuse part through an irradiance encoding (l2 unless one is chosen).
    if (!compressed) return 'CpuRadiance';
    if (shape.bands > kBands.maxShaderGlossy)
      fail(name, bandLimitMessage(`the ${shape.mode} transfer's glossy matrices`, shape.bands, 'the shaders\' glossy response', kBands.maxShaderGlossy));
    return 'CpcaMatrix';
  }
  // The light must fit the vertex shader's uniforms (limits.maxBands ≤ bands.maxPackedLight).
  if (shape.bands > limits.maxBands)
    fail(name, bandLimitMessage(what, shape.bands, 'this page\'s light (the vertex shader\'s uniforms)', limits.maxBands));
  return compressed ? 'CpcaVector' : 'DenseVector';
}

/** Texels per row of the dense form of t (relight::shaderTexelsPerRow: DenseVector, and
 *  DenseMatrix's B² rows of ⌈B²/4⌉ texels) — what a compressed transfer saves against. */
export function denseTexelsPerRow(t) {
  const n = t.bands * t.bands;
  return t.matrix ? n * Math.ceil(n / 4) : t.channels === 1 ? Math.ceil(n / 4) : n;
}

/** What each path needs from the file and per part (the rows), and per frame. */
const kPaths = {
  DenseVector: {
    // Per vertex: scalar ⌈B²/4⌉ texels of four coefficients, RGB B² texels (r, g, b, 0) —
    // relight::packShaderRows, read from the VEC4 attributes GLTFLoader put on each part.
    // Per texel: the same texels from the SCALAR accessor texelAccessor (B²·C floats a row).
    async read(gltf, json, entry, t, rowCount, name) {
      if (!t.perPixel) return null;
      const idx = (entry.accessors || []).find((i) => json.accessors[i] && json.accessors[i].name === entry.texelAccessor);
      if (idx === undefined) fail(name, `the ${t.mode} transfer lacks its accessor ${entry.texelAccessor}`);
      const a = await gltf.parser.getDependency('accessor', idx);
      const count = rowCount * t.bands * t.bands * t.channels;
      if (!a || a.itemSize !== 1 || a.array.length !== count)
        fail(name, `${entry.texelAccessor} holds ${a ? a.array.length : 0} values, ${count} expected`);
      for (let i = 0; i < a.array.length; ++i) if (!Number.isFinite(a.array[i])) fail(name, `${entry.texelAccessor}: value ${i} is not finite`);
      return a.array;
    },
    texelsPerRow: denseTexelsPerRow,
    rows(t, part, limits, name) {
      if (t.perPixel) return packTexelRows(t, limits, name);
      const g = part.geometry, V = g.getAttribute('position').count;
      const attributes = Math.ceil((t.bands * t.bands * t.channels) / 4);
      const attrs = [];
      for (let k = 0; k < attributes; ++k) {
        const a = g.getAttribute(t.attributePrefix + k);
        if (!a || a.itemSize !== 4 || a.count !== V)
          fail(name, `part '${part.name}' lacks the ${t.mode} transfer attribute ${t.attributePrefix.toUpperCase()}${k}`);
        attrs.push(a);
      }
      const T = t.texelsPerRow, img = textureShape(V * T, limits, name, `the ${t.mode} transfer`, ' (use fewer bands)');
      const row = new Float32Array(attributes * 4), data = img.data;
      for (let v = 0; v < V; ++v) {
        for (let k = 0; k < attributes; ++k) {
          const a = attrs[k];
          row[4 * k] = a.getX(v), row[4 * k + 1] = a.getY(v), row[4 * k + 2] = a.getZ(v), row[4 * k + 3] = a.getW(v);
        }
        const dst = v * T * 4;
        if (t.channels === 1) data.set(row.subarray(0, T * 4), dst);
        else
          for (let i = 0; i < t.bands * t.bands; ++i)
            data[dst + 4 * i] = row[3 * i], data[dst + 4 * i + 1] = row[3 * i + 1], data[dst + 4 * i + 2] = row[3 * i + 2];
      }
      for (let k = 0; k < attributes; ++k) g.deleteAttribute(t.attributePrefix + k);  // in the texture now
      return img;
    },
    table: () => null,
    frame() {},
  },
  CpcaVector: {
    read: readCompressed,
    texelsPerRow: (t) => t.compressed.texelsPerVertex,
    rows: (t, part, limits, name) => t.perPixel
      ? once(t, () => packWeights(t.compressed, 0, t.rowCount, limits, name, t.mode))
      : packWeights(t.compressed, part.first, part.vertices, limits, name, t.mode),
    table: (t, limits, name) => clusterTableImage(t.compressed, limits, name, t.mode),
    // The once-per-frame step: K(N+1) projections of L' (b bands).
    frame: (t, b, rotated, table) => projectClusters(t.compressed, b, t.channels, rotated, table.data),
  },
};
kPaths.CpcaMatrix = kPaths.CpcaVector;
// Dense per-vertex matrices, relit on the CPU through an irradiance encoding (encoded_diffuse.js
// makes each vertex's radiance; draw.js draws it with the radiance stage): the rows stay in JS.
kPaths.CpuRadiance = {
  read: (gltf, json, entry, t, rowCount, name) =>
    readDenseMatrices(gltf, entry, rowCount * t.bands ** 4 * t.channels, name, `the ${t.mode} transfer`, true),
  texelsPerRow: () => 0,
  rows: () => null,
  table: () => null,
  frame() {},
};

/** A dense matrix transfer's rows: the SCALAR float accessor its entry's matrixAccessor names
 *  (element (i, j), channel c of row r at ((r·B² + i)·B² + j)·C + c), `count` values, each
 *  finite if `finite` is asked. */
export async function readDenseMatrices(gltf, entry, count, name, what, finite = false) {
  const json = gltf.parser.json;
  const idx = (entry.accessors || []).find((i) => json.accessors[i] && json.accessors[i].name === entry.matrixAccessor);
  if (idx === undefined) fail(name, `${what} lacks its accessor ${entry.matrixAccessor}`);
  const a = await gltf.parser.getDependency('accessor', idx);
  if (!a || a.itemSize !== 1 || a.array.length !== count)
    fail(name, `${entry.matrixAccessor} holds ${a ? a.array.length : 0} values, ${count} expected`);
  if (finite) for (let i = 0; i < a.array.length; ++i) if (!Number.isFinite(a.array[i])) fail(name, `${what}: value ${i} is not finite`);
  return a.array;
}

/** Per-texel rows are packed once for every part (they are the one lightmap's). */
function once(t, pack) {
  if (!t.packedRows) t.packedRows = pack();
  return t.packedRows;
}

/** Dense per-texel rows (t.texelValues: B²·C floats a row, value e·C + c) packed as
 *  relight::packShaderRows packs them: scalar ⌈B²/4⌉ texels, RGB B² texels (r, g, b, 0). */
function packTexelRows(t, limits, name) {
  return once(t, () => {
    const n = t.bands * t.bands, C = t.channels, T = t.texelsPerRow, x = t.texelValues;
    const img = textureShape(t.rowCount * T, limits, name, `the ${t.mode} transfer`, ' (use fewer bands, or compress it: prt compress)');
    for (let r = 0; r < t.rowCount; ++r) {
      const src = r * n * C, dst = r * T * 4;
      if (C === 1) img.data.set(x.subarray(src, src + n), dst);
      else
        for (let i = 0; i < n; ++i)
          img.data[dst + 4 * i] = x[src + 3 * i], img.data[dst + 4 * i + 1] = x[src + 3 * i + 1], img.data[dst + 4 * i + 2] = x[src + 3 * i + 2];
    }
    return img;
  });
}

/**
 * Reads transfer entry `entry` of the bake (PRTKIT_radiance_transfer): its shape (checked), its path, and what the
 * path reads from the file (the compressed arrays, a per-texel transfer's dense rows). `gltf` is GLTFLoader's
 * result; `rowCount` the domain's rows (the vertices, or the lightmap's texels); `lightmap` { width, height } for
 * per-texel transfer, else null; hasTexelPoints: the bake comes with its texels' points (per-texel
 * glossy matrices need them).
 */
export async function readTransfer(gltf, entry, rowCount, name, limits, lightmap = null, hasTexelPoints = false) {
  const s = entry.settings || {};
  const mode = modes.find((m) => m.name === String(s.mode));
  if (!mode) fail(name, `unknown transfer mode '${s.mode}'`);
  const layout = s.layout || layouts[0];
  if (!layouts.includes(layout)) fail(name, `the ${mode.name} transfer has an unknown layout '${s.layout}'`);
  const bands = s.bands, channels = s.channels;
  if (!Number.isInteger(bands) || bands < 1 || bands > kBands.maxLibrary)
    fail(name, bandLimitMessage(`the ${mode.name} transfer`, bands, 'a bake file', kBands.maxLibrary));
  if (channels !== 1 && channels !== 3) fail(name, `the ${mode.name} transfer has ${channels} channels (1 or 3 expected)`);
  // (response: a matrix transfer's kernels, docs/formats-bake.md; recipeMaterial: the bake's
  // material — glossy.js makes the shading from both.)
  const t = { mode: mode.name, layout, bands, channels, matrix: layout === 'matrix',
              attributePrefix: mode.attributePrefix.toLowerCase(), compressed: null,
              response: entry.response || null, recipeMaterial: s.material || null,
              perPixel: !!lightmap, lightmap, rowCount, hasTexelPoints };
  if ((s.domain === 'texels') !== t.perPixel)
    fail(name, `the ${mode.name} transfer is over ${s.domain || 'vertices'}, the bake over ${lightmap ? 'texels' : 'vertices'}`);
  t.path = shaderPath(t, !!entry.compressed, name, limits);
  t.describe = shaderPaths[t.path] + (t.perPixel ? ' per texel, relit per pixel' : '');
  const p = kPaths[t.path];
  const read = await p.read(gltf, gltf.parser.json, entry, t, rowCount, name, maxShaderClusters);
  if (t.path === 'DenseVector') t.texelValues = read;
  else if (t.path === 'CpuRadiance') t.matrices = read;
  else t.compressed = read;
  t.texelsPerRow = p.texelsPerRow(t);
  return t;
}

/** A part's per-vertex texels of transfer t as a data image (part: { geometry, name, first,
 *  vertices }); of a per-texel transfer, the lightmap's rows (the same image for every part). */
export function packRows(t, part, limits, name) {
  return kPaths[t.path].rows(t, part, limits, name);
}

/** The per-frame table a path fills (null if none). */
export function frameTable(t, limits, name) {
  return kPaths[t.path].table(t, limits, name);
}

/** The per-frame CPU step of t at b bands under the rotated light (b² RGB, zero-padded). */
export function frameStep(t, b, rotated, table) {
  kPaths[t.path].frame(t, b, rotated, table);
}

/** The transfers in the order the library prefers them (io::transferPreference). */
export function preferenceOrder(transfers) {
  const rank = (t) => transferPreference.findIndex((p) => p.mode === t.mode && p.layout === t.layout);
  return transfers.slice().sort((a, b) => rank(a) - rank(b));
}

/** io::pickTransfer over transfers in preference order: the first of `mode` (any if empty or
 *  absent), else the first. */
export function pickTransfer(ordered, mode) {
  return ordered.find((t) => !mode || t.mode === mode) || ordered[0];
}
