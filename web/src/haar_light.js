// Lighting in the Haar basis for the page and prtkit-three (docs/haar.md): the library's
// include/prt/haar/ in JavaScript, function for function, so that a Haar bake is relit in the
// browser under the light prt render would make —
//   cube geometry     envmap::cubeFaceDirection, cubeTexelSolidAngles (envmap/layout.hpp);
//                     haar::texelGeometry, clampedCosine (haar/cube_texels.hpp)
//   the transform     haar::forward, supportSide (haar/cube_haar.hpp, resolution.hpp)
//   the light         haar::approximate, unshadowedPart (haar/project_light.hpp): the K
//                     largest area-weighted terms, the 16 brightest texels and the 5-band SH of
//                     the rest
//   turning it        haar::turnCubeMeans, turnedLight (haar/turned_cube.hpp): the cube's means
//                     splatted from the environment's finer cube (prt web's, 4N a side) at each
//                     turn R of the light — Haar wavelets do not rotate; the environment is
//                     resampled
//   a light file      io::parseHaarLightJson (prt light --basis haar), a light that cannot turn
//   its full SH       the environment's SH before the bright texels were taken out of it: the
//                     rest plus each bright texel's constant patch, what an inter-reflected Haar
//                     row's bounce (SH) is relit against (haarLightFullSh)
// A HaarLight here is { resolution, index: Uint32Array(K) ascending, value: Float32Array(3K),
// unshadowed: Float32Array(25·3) (coefficient-major), bright: [{ texel, radiance: [r, g, b] }],
// fullSh: Float64Array(25·3) (haarLightFullSh, made with the light), energyKept }.
// tests/web/test_haar_web.cpp holds every step to the library.
import { haar as kHaar } from 'prt:constants';
import { rotateLight } from './sh.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/** envmap::cubeFaceDirection: the direction (not normalised) of (s, t) ∈ [−1, 1]² on a face
 *  (+X −X +Y −Y +Z −Z, OpenGL's orientation). */
export function cubeFaceDirection(face, s, t) {
  switch (face) {
    case 0: return [1, -t, -s];
    case 1: return [-1, -t, s];
    case 2: return [s, 1, t];
    case 3: return [s, -1, -t];
    case 4: return [s, -t, 1];
    default: return [-s, -t, -1];
  }
}

/** The face a direction falls on and its (s, t) (turned_cube.cpp's faceCoords, in double). */
function faceCoords(x, y, z, out) {
  const ax = Math.abs(x), ay = Math.abs(y), az = Math.abs(z);
  if (ax >= ay && ax >= az) {
    out[1] = (x > 0 ? -z : z) / ax, out[2] = -y / ax, out[0] = x > 0 ? 0 : 1;
  } else if (ay >= az) {
    out[1] = x / ay, out[2] = (y > 0 ? z : -z) / ay, out[0] = y > 0 ? 2 : 3;
  } else {
    out[1] = (z > 0 ? x : -x) / az, out[2] = -y / az, out[0] = z > 0 ? 4 : 5;
  }
  return out;
}

/** envmap::cubeTexelSolidAngles: the exact solid angle of each texel of one n × n face. */
export function cubeTexelSolidAngles(n) {
  const area = (a, b) => Math.atan2(a * b, Math.sqrt(a * a + b * b + 1));
  const edge = new Float64Array(n + 1);
  for (let i = 0; i <= n; ++i) edge[i] = (2 * i) / n - 1;
  const out = new Float64Array(n * n);
  for (let y = 0; y < n; ++y)
    for (let x = 0; x < n; ++x)
      out[y * n + x] = area(edge[x + 1], edge[y + 1]) - area(edge[x], edge[y + 1]) -
                       area(edge[x + 1], edge[y]) + area(edge[x], edge[y]);
  return out;
}

export const validResolution = (n) =>
  Number.isInteger(n) && n >= kHaar.minResolution && n <= kHaar.maxResolution && (n & (n - 1)) === 0;

/** haar::supportSide: the side in texels of coefficient `index`'s support on its face. */
export function supportSide(index, n) {
  const r = index % (n * n), m = Math.max(r % n, Math.floor(r / n));
  return m === 0 ? n : n / (1 << (31 - Math.clz32(m)));
}

/** haar::forward of one channel of a cube (6 n² values, in place): per face, level by level,
 *  every 2×2 block to its scaling and three details. */
export function forwardHaar(cube, n) {
  const block = new Float64Array(n * n);
  for (let f = 0; f < 6; ++f) {
    const face = cube.subarray(f * n * n, (f + 1) * n * n);
    for (let s = n; s > 1; s /= 2) {
      const h = s / 2;
      block.set(face);
      for (let j = 0; j < h; ++j)
        for (let i = 0; i < h; ++i) {
          const a = block[2 * j * n + 2 * i], b = block[2 * j * n + 2 * i + 1];
          const c = block[(2 * j + 1) * n + 2 * i], d = block[(2 * j + 1) * n + 2 * i + 1];
          face[j * n + i] = 0.5 * (a + b + c + d);
          face[j * n + h + i] = 0.5 * (a - b + c - d);
          face[(h + j) * n + i] = 0.5 * (a + b - c - d);
          face[(h + j) * n + h + i] = 0.5 * (a - b - c + d);
        }
    }
  }
  return cube;
}

// ---- The cube's texels as pieces of the sphere (haar/cube_texels.hpp) -------------------------

const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => { const l = Math.hypot(a[0], a[1], a[2]); return [a[0] / l, a[1] / l, a[2] / l]; };

/** ½ Σ Θ_i u_i over the closed polygon: ∫_P ω dω up to its orientation's sign (Arvo 1995). */
function polygonMoment(v) {
  const sum = [0, 0, 0];
  for (let i = 0; i < v.length; ++i) {
    const a = v[i], b = v[(i + 1) % v.length], c = cross(a, b), s = Math.hypot(c[0], c[1], c[2]);
    if (s <= 0) continue;
    const k = Math.atan2(s, dot(a, b)) / s;
    sum[0] += c[0] * k, sum[1] += c[1] * k, sum[2] += c[2] * k;
  }
  return [0.5 * sum[0], 0.5 * sum[1], 0.5 * sum[2]];
}

/** haar::texelGeometry: texel j's corners (unit, around it) and its moment ∫_j ω dω. */
export function texelGeometry(j, n) {
  const face = Math.floor(j / (n * n)), r = j % (n * n), x = r % n, y = Math.floor(r / n);
  const s0 = (2 * x) / n - 1, s1 = (2 * (x + 1)) / n - 1, t0 = (2 * y) / n - 1, t1 = (2 * (y + 1)) / n - 1;
  const corners = [[s0, t0], [s1, t0], [s1, t1], [s0, t1]].map(([s, t]) => normalize(cubeFaceDirection(face, s, t)));
  let moment = polygonMoment(corners);
  const centre = normalize(corners.reduce((a, c) => [a[0] + c[0], a[1] + c[1], a[2] + c[2]], [0, 0, 0]));
  if (dot(moment, centre) < 0) moment = moment.map((m) => -m);
  return { corners, moment };
}

/** haar::clampedCosine: (1/π) ∫_texel max(n·ω, 0) dω, exactly, for a unit normal n — the texel
 *  clipped to n's hemisphere (Sutherland–Hodgman) where the horizon crosses it. */
export function clampedCosine(g, n) {
  let above = 0;
  for (const v of g.corners) above += dot(v, n) >= 0 ? 1 : 0;
  if (above === 0) return 0;
  if (above === 4) return Math.max(0, dot(n, g.moment)) / Math.PI;
  const clipped = [];
  for (let i = 0; i < 4; ++i) {
    const a = g.corners[i], b = g.corners[(i + 1) % 4], da = dot(n, a), db = dot(n, b);
    if (da >= 0) clipped.push(a);
    if ((da >= 0) !== (db >= 0)) {
      const x = [(b[0] * da - a[0] * db) / (da - db), (b[1] * da - a[1] * db) / (da - db), (b[2] * da - a[2] * db) / (da - db)];
      const len = Math.hypot(x[0], x[1], x[2]);
      if (len > 0) clipped.push([x[0] / len, x[1] / len, x[2] / len]);
    }
  }
  if (clipped.length < 3) return 0;
  return Math.abs(dot(n, polygonMoment(clipped))) / Math.PI;
}

// ---- The light (haar/project_light.hpp) -------------------------------------------------------

/** haar::approximate: the `terms` largest coefficients (|c|·side², ties to the lower index) of
 *  the transform of `means` (6 n² RGB texel means, Float32Array), ascending, and the share of
 *  the wavelet energy they hold. */
export function approximate(means, n, terms) {
  const count = 6 * n * n;
  const c = [0, 1, 2].map((ch) => {
    const x = new Float64Array(count);
    for (let k = 0; k < count; ++k) x[k] = means[3 * k + ch];
    return forwardHaar(x, n);
  });
  const norm2 = new Float64Array(count), score = new Float64Array(count);
  let total = 0;
  for (let k = 0; k < count; ++k) {
    norm2[k] = c[0][k] * c[0][k] + c[1][k] * c[1][k] + c[2][k] * c[2][k];
    total += norm2[k];
    const side = supportSide(k, n);
    score[k] = Math.sqrt(norm2[k]) * side * side;
  }
  const order = Array.from({ length: count }, (_, k) => k);
  order.sort((a, b) => (score[a] !== score[b] ? score[b] - score[a] : a - b));
  const kept = order.slice(0, Math.min(terms, count)).sort((a, b) => a - b);
  const index = Uint32Array.from(kept), value = new Float32Array(3 * kept.length);
  let energy = 0;
  kept.forEach((k, t) => {
    value[3 * t] = c[0][k], value[3 * t + 1] = c[1][k], value[3 * t + 2] = c[2][k];
    energy += norm2[k];
  });
  return { resolution: n, index, value, energyKept: total > 0 ? Math.min(1, energy / total) : 1 };
}

/** Y_i(d), i < 25, at a unit direction: sh.js's recurrence with the normalisations tabled (the
 *  unshadowed part evaluates it at every vertex). */
const kBands = kHaar.unshadowedBands, kCoeffs = kBands * kBands;
const kNorm = (() => {
  const out = new Float64Array(kCoeffs);
  for (let l = 0; l < kBands; ++l)
    for (let m = 0; m <= l; ++m) {
      let k = (2 * l + 1) / (4 * Math.PI);
      for (let f = l - m + 1; f <= l + m; ++f) k /= f;
      out[l * (l + 1) + m] = m === 0 ? Math.sqrt(k) : Math.SQRT2 * Math.sqrt(k);
    }
  return out;
})();
export function shBasis(x, y, z, out) {
  let cm = 1, sm = 0, pmm = 1;
  for (let m = 0; m < kBands; ++m) {
    if (m > 0) {
      pmm *= -(2 * m - 1);
      const c = cm * x - sm * y, s = cm * y + sm * x;
      cm = c, sm = s;
    }
    let prev2 = 0, prev1 = 0;
    for (let l = m; l < kBands; ++l) {
      const p = l === m ? pmm : l === m + 1 ? z * (2 * m + 1) * pmm
        : ((2 * l - 1) * z * prev1 - (l + m - 1) * prev2) / (l - m);
      prev2 = prev1, prev1 = p;
      const k = kNorm[l * (l + 1) + m];
      if (m === 0) out[l * (l + 1)] = k * p;
      else out[l * (l + 1) + m] = k * p * cm, out[l * (l + 1) - m] = k * p * sm;
    }
  }
  return out;
}

/** haar::unshadowedPart from the environment's SH (25 × 3, unturned): that SH turned by R, less
 *  the constant patch of each of the 16 texels of `means` with the largest luminance power
 *  (each patch's SH integrated 16 × 16 over its texel), and those texels (and their patches,
 *  texelPatchSh's, for haarLightFullSh). */
export function unshadowedPart(environmentSh, means, n, R) {
  const sh = Float64Array.from(rotateLight(kBands, R, environmentSh, new Float64Array(kCoeffs * 3)));
  const omega = cubeTexelSolidAngles(n), face = n * n, count = 6 * face;
  const p = new Float64Array(count);
  for (let k = 0; k < count; ++k)
    p[k] = (0.2126 * means[3 * k] + 0.7152 * means[3 * k + 1] + 0.0722 * means[3 * k + 2]) * omega[k % face];
  const order = Array.from({ length: count }, (_, k) => k).sort((a, b) => (p[a] !== p[b] ? p[b] - p[a] : a - b));
  const bright = [], patches = [];
  for (let i = 0; i < Math.min(kHaar.brightTexels, count); ++i) {
    const j = order[i];
    if (!(p[j] > 0)) break;
    const l = [means[3 * j], means[3 * j + 1], means[3 * j + 2]];
    bright.push({ texel: j, radiance: l });
    const patch = texelPatchSh(j, n);
    patches.push(patch);
    for (let k = 0; k < kCoeffs; ++k)
      for (let ch = 0; ch < 3; ++ch) sh[3 * k + ch] -= l[ch] * patch[k];
  }
  return { sh: Float32Array.from(sh), bright, patches };
}

/** The SH (25) of texel j of an n cube as a constant patch of unit radiance: Σ over its 16 × 16
 *  midpoints of Y(d̂) dA/|d|³, in float (unshadowedPart's, project_light.cpp's). */
export function texelPatchSh(j, n) {
  const face = n * n, f = Math.floor(j / face), x = j % n, yy = Math.floor((j % face) / n);
  const sub = 16, step = 2 / n / sub, y = new Float64Array(kCoeffs), patch = new Float64Array(kCoeffs);
  for (let b = 0; b < sub; ++b)
    for (let a = 0; a < sub; ++a) {
      const s = -1 + (2 * x) / n + (a + 0.5) * step, t = -1 + (2 * yy) / n + (b + 0.5) * step;
      const d = cubeFaceDirection(f, s, t), len = Math.hypot(d[0], d[1], d[2]);
      shBasis(d[0] / len, d[1] / len, d[2] / len, y);
      const w = (step * step) / (len * len * len);
      for (let k = 0; k < kCoeffs; ++k) patch[k] += y[k] * w;
    }
  return Float32Array.from(patch);
}

/** The light's full SH (25 × 3, coefficient-major, Float64Array): its environment's SH before
 *  the bright texels were taken out — the rest (`unshadowed`) plus, for each bright texel b,
 *  radiance_b times b's constant patch (texelPatchSh; `patches`, one per bright texel, where the
 *  caller has them). An inter-reflected Haar row's bounce is relit against its first bands
 *  (haar_relight.js). Made once per light (turnedLight, parseHaarLight keep it as
 *  light.fullSh), not per vertex. */
export function haarLightFullSh(light, patches = null) {
  const full = Float64Array.from(light.unshadowed);
  for (const [i, b] of light.bright.entries()) {
    const patch = patches ? patches[i] : texelPatchSh(b.texel, light.resolution), l = b.radiance;
    for (let k = 0; k < kCoeffs; ++k)
      for (let ch = 0; ch < 3; ++ch) full[3 * k + ch] += l[ch] * patch[k];
  }
  return full;
}

// ---- Turning it (haar/turned_cube.hpp) --------------------------------------------------------

/** An environment's cube as prt web writes it (prt-data.js: environments[i].haar): { resolution
 *  M, means: Float32Array(6 M² · 3), sh: Float32Array(25 · 3) }, from its RGBE texels
 *  (`rgbeBytes`, decoded by `decodeRgbe`) and its SH (25 [r, g, b]). */
export function environmentCube(resolution, rgbeBytes, sh, name, decodeRgbe) {
  if (!validResolution(resolution / kHaar.fineCubeFactor) || rgbeBytes.length !== 6 * resolution * resolution * 4)
    fail(name, `its Haar cube holds ${rgbeBytes.length / 4} texels at ${resolution}² a face`);
  const flat = Float32Array.from(sh.flat());
  if (flat.length !== kCoeffs * 3 || !flat.every(Number.isFinite))
    fail(name, `its Haar cube's SH holds ${flat.length / 3} coefficients, ${kCoeffs} finite ones expected`);
  return { resolution, means: decodeRgbe(rgbeBytes), sh: flat };
}

/** haar::turnCubeMeans: the n cube's means of the environment turned by R (rows), splatted from
 *  the fine cube — each fine texel's power in kSplatPoints² equal parts, each to the coarse
 *  texel its point turns to (R d), over the coarse texel's exact solid angle. Power is kept.
 *  Float32Array(6 n² · 3). */
export function turnCubeMeans(cube, n, R) {
  const m = cube.resolution, q = kHaar.splatPoints, coarse = cubeTexelSolidAngles(n);
  const { length: len, power: w } = splatPoints(cube);
  const L = cube.means, power = new Float64Array(6 * n * n * 3), fc = [0, 0, 0];
  const [r0, r1, r2] = R;
  for (let f = 0, t = 0, p = 0; f < 6; ++f) {
    // cubeFaceDirection(f, s, t) = c + s·a + t·b, each of c, a, b a signed axis (so exactly),
    // without an array per point.
    const [c0, c1, c2] = cubeFaceDirection(f, 0, 0), a = cubeFaceDirection(f, 1, 0), b = cubeFaceDirection(f, 0, 1);
    const a0 = a[0] - c0, a1 = a[1] - c1, a2 = a[2] - c2, b0 = b[0] - c0, b1 = b[1] - c1, b2 = b[2] - c2;
    for (let y = 0; y < m; ++y)
      for (let x = 0; x < m; ++x, ++t) {
        const r = L[3 * t] * w[t], g = L[3 * t + 1] * w[t], bl = L[3 * t + 2] * w[t];
        for (let j = 0; j < q; ++j)
          for (let i = 0; i < q; ++i, ++p) {
            const s = (2 * (x + (i + 0.5) / q)) / m - 1, u = (2 * (y + (j + 0.5) / q)) / m - 1, l = len[p];
            const dx = (c0 + s * a0 + u * b0) / l, dy = (c1 + s * a1 + u * b1) / l, dz = (c2 + s * a2 + u * b2) / l;
            faceCoords(r0[0] * dx + r0[1] * dy + r0[2] * dz, r1[0] * dx + r1[1] * dy + r1[2] * dz, r2[0] * dx + r2[1] * dy + r2[2] * dz, fc);
            const cx = Math.min(Math.max(Math.trunc((fc[1] + 1) * 0.5 * n), 0), n - 1);
            const cy = Math.min(Math.max(Math.trunc((fc[2] + 1) * 0.5 * n), 0), n - 1);
            const k = 3 * (fc[0] * n * n + cy * n + cx);
            power[k] += r, power[k + 1] += g, power[k + 2] += bl;
          }
      }
  }
  const out = new Float32Array(6 * n * n * 3);
  for (let k = 0; k < 6 * n * n; ++k)
    for (let c = 0; c < 3; ++c) out[3 * k + c] = power[3 * k + c] / coarse[k % (n * n)];
  return out;
}

/** What every turn of a cube splats alike, made once per cube and kept on it: the length of
 *  each splat point's cubeFaceDirection (kSplatPoints² a fine texel, in the texel's order; 8
 *  bytes a point, 12.6 MB at N = 64) and the share of its fine texel's solid angle each point
 *  carries. */
function splatPoints(cube) {
  if (cube.splat) return cube.splat;
  const m = cube.resolution, q = kHaar.splatPoints, fine = cubeTexelSolidAngles(m);
  const length = new Float64Array(6 * m * m * q * q), power = new Float64Array(6 * m * m);
  let p = 0;
  for (let f = 0; f < 6; ++f)
    for (let y = 0; y < m; ++y)
      for (let x = 0; x < m; ++x) {
        power[f * m * m + y * m + x] = fine[y * m + x] / (q * q);
        for (let j = 0; j < q; ++j)
          for (let i = 0; i < q; ++i) {
            const d = cubeFaceDirection(f, (2 * (x + (i + 0.5) / q)) / m - 1, (2 * (y + (j + 0.5) / q)) / m - 1);
            length[p++] = Math.hypot(d[0], d[1], d[2]);
          }
      }
  cube.splat = { length, power };
  return cube.splat;
}

/** haar::turnedLight: the light a Haar bake over an n cube is relit with, its environment
 *  turned by R (rows, sh.js's), its `terms` largest terms. */
export function turnedLight(cube, n, terms, R) {
  const means = turnCubeMeans(cube, n, R);
  const light = approximate(means, n, terms);
  const part = unshadowedPart(cube.sh, means, n, R);
  light.unshadowed = part.sh;
  light.bright = part.bright;
  light.fullSh = haarLightFullSh(light, part.patches);
  return light;
}

// ---- A light file (io/haar_light_file.hpp) ----------------------------------------------------

/** A Haar light file (`prt light ENV --basis haar`, JSON text or its parsed object) as a
 *  HaarLight, checked as io::parseHaarLightJson and HaarLight::check check it. It holds its
 *  environment turned once: it does not turn (`fixed`). */
export function parseHaarLight(text, name) {
  let j = text;
  if (typeof text === 'string') {
    try {
      j = JSON.parse(text);
    } catch (e) {
      fail(name, `invalid JSON (${String(e.message).split('\n')[0].slice(0, 120)})`);
    }
  }
  if (!j || typeof j !== 'object' || Array.isArray(j)) fail(name, 'expected a JSON object');
  if (j.basis !== 'haar')
    fail(name, 'is not a Haar light (no "basis": "haar"; an SH light relights SH bakes: make one with prt light --basis haar)');
  const n = j.resolution;
  if (!Number.isInteger(n)) fail(name, '"resolution" must be an integer');
  if (!validResolution(n)) fail(name, `"resolution" ${n} is not a power of two from ${kHaar.minResolution} to ${kHaar.maxResolution}`);
  const count = 6 * n * n;
  if (!Array.isArray(j.terms)) fail(name, 'missing "terms" array');
  if (j.terms.length === 0 || j.terms.length > count) fail(name, `holds ${j.terms.length} terms; a ${n}² cube has 1 to ${count}`);
  const finite3 = (r, from) => [r[from], r[from + 1], r[from + 2]].every((x) => typeof x === 'number' && Number.isFinite(x));
  const index = new Uint32Array(j.terms.length), value = new Float32Array(3 * j.terms.length);
  j.terms.forEach((r, t) => {
    if (!Array.isArray(r) || r.length !== 4 || !Number.isInteger(r[0]) || r[0] < 0) fail(name, `term ${t} is not [index, r, g, b]`);
    if (!finite3(r, 1)) fail(name, `term ${t} is not a finite number triple`);
    if (r[0] >= count) fail(name, `term ${t} has index ${r[0]}, past the ${count} coefficients of the cube`);
    if (t > 0 && r[0] <= index[t - 1]) fail(name, `term indices must ascend (term ${t})`);
    index[t] = r[0];
    value.set([r[1], r[2], r[3]], 3 * t);
  });
  const u = j.unshadowed;
  if (!u || typeof u !== 'object' || !Array.isArray(u.coefficients)) fail(name, 'missing "unshadowed" {"bands", "coefficients"}');
  if (u.coefficients.length !== kCoeffs) fail(name, `"unshadowed" holds ${u.coefficients.length} coefficients, expected ${kCoeffs}`);
  const sh = new Float32Array(3 * kCoeffs);
  u.coefficients.forEach((c, i) => {
    if (!Array.isArray(c) || c.length !== 3 || !finite3(c, 0)) fail(name, `unshadowed coefficient ${i} is not [r, g, b]`);
    sh.set(c, 3 * i);
  });
  if (!Array.isArray(u.bright) || u.bright.length > kHaar.brightTexels)
    fail(name, `"unshadowed"."bright" must be an array of at most ${kHaar.brightTexels} [texel, r, g, b]`);
  const bright = u.bright.map((r, b) => {
    if (!Array.isArray(r) || r.length !== 4 || !Number.isInteger(r[0]) || r[0] < 0 || !finite3(r, 1)) fail(name, `bright texel ${b} is not [texel, r, g, b]`);
    if (r[0] >= count) fail(name, `bright texel ${r[0]} is past the cube's ${count}`);
    return { texel: r[0], radiance: [r[1], r[2], r[3]] };
  });
  bright.forEach((b, i) => { if (bright.slice(0, i).some((c) => c.texel === b.texel)) fail(name, `bright texel ${b.texel} twice`); });
  const energyKept = typeof j.energyKept === 'number' ? j.energyKept : 1;
  if (!(energyKept >= 0 && energyKept <= 1 + 1e-6)) fail(name, 'the energy kept must lie in [0, 1]');
  const light = { resolution: n, index, value, unshadowed: sh, bright, energyKept, fixed: true };
  light.fullSh = haarLightFullSh(light);
  return light;
}
