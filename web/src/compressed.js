// CPCA-compressed transfer in the page (prt compress, bake format version 3; docs/compress.md),
// relit in the compressed space as Sloan, Hall, Hart & Snyder 2003 do on the GPU and as the
// desktop viewer does (include/prt/relight/shader_transfer.hpp holds the layouts; transfer.js
// dispatches to this file for the CpcaVector and CpcaMatrix paths):
//   per vertex, once:  its cluster id k and N weights w_j in T = ⌈(N+1)/4⌉ RGBA32F texels
//                      (slot 0 = k as a float, slot 1 + j = w_j, zero padding);
//   per frame, in JS:  the rotated light L' (first b bands) projected onto every cluster's mean
//                      and basis, c_k = M_k·L', d_kj = B_kj·L' (K(N+1)·b²·3 multiply-adds),
//                      texel k(N+1) + j = (r, g, b, 0), j = 0 the mean;
//   per vertex, GPU:   R(v) = albedo(v) ⊙ (c_k + Σ_j w_j d_kj)   (shaders/prt_compressed.glsl).
// Glossy matrices (Q = b² values per cluster vector at b shown bands: the transfer cut to b
// bands, as the desktop viewer cuts it): the table holds L'_kj = B_kj L' (texel
// (k(N + 1) + j)·b² + i), and the vertex shader forms L'_v = L'_k0 + Σ_j w_j L'_kj and shades it
// (shaders/stages/compressedGlossy.vert, as prt view --glossy-on gpu).
// tests/web/golden_check.mjs checks projectClusters and packWeights against the library.
import { textureShape } from './texels.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/**
 * Reads a transfer's compressed arrays (docs/formats-bake.md, "Compressed (CPCA) transfer"):
 * returns { clusters K, basisCount N, stride D, texelsPerVertex, cluster, weights, means, basis }.
 * Every count is checked against the accessors and every id against K.
 */
export async function readCompressed(gltf, json, t, shape, vertexCount, name, maxClusters) {
  const c = t.compressed;
  const what = `the ${shape.mode} transfer's compressed form`;
  if (!c || c.method !== 'cpca') fail(name, `${what} is not CPCA (method ${c && c.method})`);
  const n = shape.bands * shape.bands;
  const K = c.clusters, N = c.basisCount, D = (shape.matrix ? n * n : n) * shape.channels;
  if (!Number.isInteger(K) || K < 1 || K > vertexCount || K > maxClusters)
    fail(name, `${what} has ${K} clusters (1..${Math.min(vertexCount, maxClusters)} expected)`);
  if (!Number.isInteger(N) || N < 0 || N > D) fail(name, `${what} has ${N} basis vectors (0..${D} expected)`);
  const prefix = String(c.accessorPrefix || '');
  const byPart = {};
  for (const idx of t.accessors || []) {
    const a = json.accessors && json.accessors[idx];
    if (a && typeof a.name === 'string' && a.name.startsWith(prefix)) byPart[a.name.slice(prefix.length)] = idx;
  }
  const get = async (part, count) => {
    if (byPart[part] === undefined) fail(name, `${what} lacks its accessor ${prefix}${part}`);
    const a = await gltf.parser.getDependency('accessor', byPart[part]);
    if (!a || a.itemSize !== 1 || a.array.length !== count)
      fail(name, `${prefix}${part} holds ${a ? a.array.length : 0} values, ${count} expected`);
    return a.array;
  };
  const cluster = await get('CLUSTER', vertexCount);
  const weights = N ? await get('WEIGHTS', vertexCount * N) : new Float32Array(0);
  const means = await get('MEANS', K * D);
  const basis = N ? await get('BASIS', K * N * D) : new Float32Array(0);
  for (let v = 0; v < vertexCount; ++v)
    if (!(cluster[v] < K)) fail(name, `${prefix}CLUSTER: ${shape.perPixel ? "texel" : "vertex"} ${v} names cluster ${cluster[v]} of ${K}`);
  for (const [part, arr] of [['WEIGHTS', weights], ['MEANS', means], ['BASIS', basis]])
    for (let i = 0; i < arr.length; ++i) if (!Number.isFinite(arr[i])) fail(name, `${prefix}${part}: value ${i} is not finite`);
  return { clusters: K, basisCount: N, stride: D, texelsPerVertex: Math.ceil((N + 1) / 4),
           coeffs: shape.matrix ? n : 1, bands: shape.bands,
           cluster, weights, means, basis };
}

/** The per-vertex texels of vertices first .. first + count − 1 (one part), as a data image. */
export function packWeights(c, first, count, limits, name, mode) {
  const T = c.texelsPerVertex, N = c.basisCount;
  const img = textureShape(count * T, limits, name, `the ${mode} transfer's weights`);
  for (let v = 0; v < count; ++v) {
    const dst = v * T * 4, g = first + v;
    img.data[dst] = c.cluster[g];
    for (let j = 0; j < N; ++j) img.data[dst + 1 + j] = c.weights[g * N + j];
  }
  return img;
}

/** The per-frame cluster table's image (filled by projectClusters), sized for all B bands. */
export function clusterTableImage(c, limits, name, mode) {
  return textureShape(c.clusters * (c.basisCount + 1) * c.coeffs, limits, name, `the ${mode} transfer's cluster table`);
}

/**
 * The once-per-frame step (relight::projectClusters + packClusterTable): for every cluster k and j = 0..N,
 * texel k(N+1) + j = Σ_{i<b²} x_i L'_i per channel, x = M_k (j = 0) or B_k,j−1, with
 * x_i = x[i·C + c] (C = 1: the same value for the three channels). `light` holds b² (r, g, b).
 */
export function projectClusters(c, bands, channels, light, out) {
  if (c.coeffs > 1) return projectClusterMatrices(c, bands, channels, light, out);
  const D = c.stride, N = c.basisCount, W = N + 1, nb = bands * bands;
  for (let k = 0; k < c.clusters; ++k)
    for (let j = 0; j < W; ++j) {
      const x = j === 0 ? c.means : c.basis, o = j === 0 ? k * D : (k * N + j - 1) * D;
      let r = 0, g = 0, b = 0;
      if (channels === 1) {
        for (let i = 0; i < nb; ++i) {
          const t = x[o + i];
          r += t * light[3 * i], g += t * light[3 * i + 1], b += t * light[3 * i + 2];
        }
      } else {
        for (let i = 0; i < nb; ++i) {
          r += x[o + 3 * i] * light[3 * i];
          g += x[o + 3 * i + 1] * light[3 * i + 1];
          b += x[o + 3 * i + 2] * light[3 * i + 2];
        }
      }
      const q = 4 * (k * W + j);
      out[q] = r, out[q + 1] = g, out[q + 2] = b, out[q + 3] = 0;
    }
}

/**
 * The matrix form, of the transfer cut to b bands: texel (k(N+1) + j)·b² + i = (X L')_i =
 * Σ_{l<b²} X[(i·B² + l)·C + c] L'_l,c for every row i < b², X = M_k or B_k,j−1.
 */
function projectClusterMatrices(c, bands, channels, light, out) {
  const D = c.stride, N = c.basisCount, W = N + 1, nB = c.coeffs, nb = bands * bands, C = channels;
  for (let k = 0; k < c.clusters; ++k)
    for (let j = 0; j < W; ++j) {
      const x = j === 0 ? c.means : c.basis, o = j === 0 ? k * D : (k * N + j - 1) * D;
      for (let i = 0; i < nb; ++i) {
        let r = 0, g = 0, b = 0;
        const row = o + i * nB * C;
        for (let l = 0; l < nb; ++l) {
          const e = row + l * C;
          if (C === 1) {
            const t = x[e];
            r += t * light[3 * l], g += t * light[3 * l + 1], b += t * light[3 * l + 2];
          } else {
            r += x[e] * light[3 * l], g += x[e + 1] * light[3 * l + 1], b += x[e + 2] * light[3 * l + 2];
          }
        }
        const q = 4 * ((k * W + j) * nb + i);
        out[q] = r, out[q + 1] = g, out[q + 2] = b, out[q + 3] = 0;
      }
    }
}
