// Diffuse exit radiance through an engine's irradiance encoding in the browser viewers — the
// page's and prtkit-three's `encoding` option (docs/web.md, docs/three.md) — as the library's
// relight/encoded_diffuse.cpp computes it for `prt render --encoding`:
//
//   f_v = kd_v ⊙ Ê_v(n_v) / π
//
// per vertex v of a matrix transfer: L'_v = M_v L the light arriving there (its first min(3, b)
// bands, the light's b bands through the transfer cut to b: relight/incident_light.hpp), Ê_v its
// encoded irradiance as an engine reconstructs it (irradiance_encoding.js), n_v the vertex
// normal and kd_v the material's kd when it sets one, else the vertex albedo (COLOR_0, else
// white: transfer/albedo.hpp). L'_v comes from the dense matrices (M_v L, b²·b² products a
// channel) or, CPCA-compressed, from the frame's cluster table (L'_k0 + Σ_j w_vj L'_kj, the sum
// the glossy vertex shader forms: compressed.js). Diffuse only: an encoding holds irradiance,
// which no view-dependent lobe can be shaded from.
//
// Which transfers take an encoding, and the one line refusing the others (as prt render refuses
// them), live here too, for both viewers.
import { encode, encodingSpec, evaluate } from './irradiance_encoding.js';

/** The encoding a transfer is drawn through: `encoding` ('none' or a name) for a per-vertex
 *  matrix transfer, else none (null); dense matrices, which the browser viewers draw on the CPU
 *  only, through 'l2' when none is chosen (the exact irradiance of bands 0..2). */
export function shownEncoding(t, encoding) {
  if (!t.matrix || t.perPixel || t.probes) return null;
  if (encoding && encoding !== 'none') return encoding;
  return t.path === 'CpuRadiance' ? 'l2' : null;
}

/**
 * Why transfer t of bake `b` cannot be drawn through `encoding` (a name, checked: the library's
 * line for an unknown one), as one line naming the file; null when it can ('none' always can).
 */
export function encodingRefusal(b, t, encoding) {
  if (!encoding || encoding === 'none') return null;
  try {
    encodingSpec(encoding);
  } catch (e) {
    return `${b.name}: ${e.message}`;
  }
  const asked = `encoding ${encoding}`;
  if (b.probes)
    return `${b.name}: holds a probe grid: ${asked} draws a surface's matrix transfer through an irradiance encoding (prt bake --transfer matrix)`;
  if (!t.matrix)
    return `${b.name}: holds the ${t.mode} vector transfer: ${asked} encodes the light arriving at each row, which a matrix bake holds ` +
           '(prt bake --transfer matrix); vector (diffuse) transfer has already integrated it against the normal';
  if (t.perPixel)
    return `${b.name}: holds the ${t.mode} matrices per texel: the browser viewers draw ${asked} per vertex only (prt render --encoding draws it per texel)`;
  return null;
}

/** Whether the material t is shaded with has a glossy lobe, which an encoding leaves out. */
export function lobeLeftOut(t) {
  return !!(t.material && t.material.ks && t.material.ks.some((k) => k > 0));
}

/**
 * The light arriving at rows of matrix transfer t, b bands shown: a function (row, out) filling
 * out with the first min(3, b)² RGB coefficients of L'_row (coefficient-major). `rotated` is the
 * rotated light (b² RGB); `table` the frame's cluster table (CPCA: compressed.js
 * projectClusters at b bands, texel (k(N + 1) + j)·b² + i).
 */
export function incidentRows(t, b, rotated, table) {
  const nb = b * b, n = Math.min(9, nb);
  if (t.compressed) {
    const c = t.compressed, N = c.basisCount, W = N + 1;
    return (row, out) => {
      const k = c.cluster[row], w = c.weights;
      for (let i = 0; i < n; ++i) {
        let q = 4 * (k * W * nb + i);
        let r = table[q], g = table[q + 1], bl = table[q + 2];
        for (let j = 0; j < N; ++j) {
          q = 4 * ((k * W + 1 + j) * nb + i);
          const x = w[row * N + j];
          r += x * table[q], g += x * table[q + 1], bl += x * table[q + 2];
        }
        out[3 * i] = r, out[3 * i + 1] = g, out[3 * i + 2] = bl;
      }
    };
  }
  // Dense: element (i, j), channel c of row v at ((v·B² + i)·B² + j)·C + c, summed over the
  // shown columns j < b² in a fixed order.
  const B2 = t.bands * t.bands, C = t.channels, M = t.matrices;
  return (row, out) => {
    for (let i = 0; i < n; ++i) {
      const base = (row * B2 + i) * B2 * C;
      let r = 0, g = 0, bl = 0;
      for (let j = 0; j < nb; ++j) {
        const e = base + j * C;
        r += M[e] * rotated[3 * j];
        g += M[e + (C === 1 ? 0 : 1)] * rotated[3 * j + 1];
        bl += M[e + (C === 1 ? 0 : 2)] * rotated[3 * j + 2];
      }
      out[3 * i] = r, out[3 * i + 1] = g, out[3 * i + 2] = bl;
    }
  };
}

/**
 * f_v = kd_v ⊙ Ê_v(n_v)/π for the vertices of one part into `out` (3 floats a vertex): rows
 * `first`.. of the transfer (incidentRows' function `incident`, at b bands), unit `normals` (3
 * floats a vertex), `albedo` (3 floats a vertex, or null: white) unless `kd` ([r, g, b], the
 * material's) replaces it, through `encoding`.
 */
export function shadeEncoded(incident, b, encoding, first, normals, albedo, kd, out) {
  const bands = Math.min(3, b), L = new Float64Array(27), y = new Float64Array(9), e = [0, 0, 0];
  for (let v = 0, V = normals.length / 3; v < V; ++v) {
    incident(first + v, L);
    const o = 3 * v;
    evaluate(encode(L, bands, encoding), normals[o], normals[o + 1], normals[o + 2], e, y);
    for (let c = 0; c < 3; ++c) out[o + c] = (kd ? kd[c] : albedo ? albedo[o + c] : 1) * (e[c] / Math.PI);
  }
  return out;
}
