// Irradiance in the compact forms engines store (issue 34), in JavaScript: step for step the
// library's src/sh/encode_irradiance.cpp and the de-ringing of src/sh/window.cpp, so that the
// page and prtkit-three draw an encoding as `prt render --encoding` does (encoded_diffuse.js).
// The encodings, their formulas and their papers: include/prt/sh/irradiance_encoding.hpp —
//
//   l2, l2-deringed          the irradiance SH of bands 0..2 (Ramamoorthi & Hanrahan 2001), and
//                            under the mildest Hanning window that leaves it non-negative (Sloan,
//                            "Deringing Spherical Harmonics", 2017)
//   l1, l1-windowed          bands 0..1, and band 1 scaled by min(1, E₀/|d|) per channel
//   l1-geomerics             Hazel's non-linear reconstruction of the same 12 numbers (2014)
//   zh3, zh3-optimal,        l1 plus band 2 along one axis: the luminance's band-1 direction,
//   zh3-hallucinated         the axis that holds the most of band 2 (a search), or guessed from
//                            band 1 (Roughton, Sloan et al., "ZH3: Quadratic Zonal Harmonics",
//                            I3D 2024)
//   zh3-shared               our variant: one zonal number shared by the channels in proportion
//                            to their L₀₀, about the axis where that colour holds the most of
//                            band 2 (a search)
//
// The names, the numbers each stores, the clamped cosine's kernel Λ_l and the luminance weights
// come from the library ('prt:constants'); the search and fit constants below are the library's,
// and tests/web/golden holds encode and evaluate to the C++ on the same lights (1e-5).
// Coefficients are RGB, coefficient-major (i·3 + c), in prtkit's SH basis (sh.js).
import { clampedCosine, irradianceEncodings, luminance, messages } from 'prt:constants';
import { fill } from './messages.js';
import { evalSh } from './sh.js';

/** The encodings' names, in the order the library's tables list them (kIrradianceEncodings). */
export const encodingNames = irradianceEncodings.map((e) => e.name);

const f = Math.fround;  // the library's float RgbSh, where it rounds the irradiance to floats
const kY00 = 1 / Math.sqrt(4 * Math.PI);         // Y₀₀
const kY1 = Math.sqrt(3 / (4 * Math.PI));        // |Y₁ₘ| along its axis
const kY20 = Math.sqrt(5 / (16 * Math.PI));      // Y₂₀(t) = √(5/16π) (3t² − 1)
const kZonalScale = Math.sqrt(4 * Math.PI / 5);  // the addition theorem's √(4π/5)

/** The encoding called `name` ({ name, numbers, rows, zonal }), or throws the library's line
 *  (sh::parseIrradianceEncoding's). */
export function encodingSpec(name) {
  const spec = irradianceEncodings.find((e) => e.name === name);
  if (!spec) throw new Error(fill(messages.encoding, { name }));
  return spec;
}

/** The band-1 direction of coefficients c[1..3] of channel ch (sh::bandOneVector): Y₁,₋₁ ∝ −y,
 *  Y₁,₀ ∝ z, Y₁,₁ ∝ −x, so c₁·Y₁(n) = kY1 v·n with v = (−c₃, −c₁, c₂). */
function bandOne(c, ch) {
  return [-c[9 + ch], -c[3 + ch], c[6 + ch]];
}
const dot3 = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const length3 = (a) => Math.sqrt(dot3(a, a));
const normalize3 = (a) => {
  const n = length3(a);
  return [a[0] / n, a[1] / n, a[2] / n];
};

/** The zonal axis: the luminance's band-1 direction (+Z when it has none). */
function luminanceAxis(l) {
  const lum = (i) => luminance[0] * l[3 * i] + luminance[1] * l[3 * i + 1] + luminance[2] * l[3 * i + 2];
  const v = [-lum(3), -lum(1), lum(2)];
  const len = length3(v);
  return len > 0 ? [v[0] / len, v[1] / len, v[2] / len] : [0, 0, 1];
}

/** z(a) = Σ_m L₂ₘ Y₂ₘ(a) per channel: band 2 projected on the zonal harmonic about a, up to
 *  √(4π/5) (Y₂₀(a·ω) = √(4π/5) Σ_m Y₂ₘ(a) Y₂ₘ(ω)). */
function zonalProjection(l, a, y = new Float64Array(9)) {
  evalSh(3, a[0], a[1], a[2], y);
  const z = [0, 0, 0];
  for (let m = 4; m < 9; ++m) for (let c = 0; c < 3; ++c) z[c] += l[3 * m + c] * y[m];
  return z;
}

/** Duff et al. 2017's orthonormal frame (t, b) about unit n (core/vec.hpp orthonormalBasis). */
function orthonormalBasis(n) {
  const sign = n[2] < 0 || Object.is(n[2], -0) ? -1 : 1;
  const a = -1 / (sign + n[2]), c = n[0] * n[1] * a;
  return [[1 + sign * n[0] * n[0] * a, sign * c, -sign * n[0]], [c, sign + n[1] * n[1] * a, -n[1]]];
}

/** The maximum over the sphere of score(a) (zh3-optimal's and zh3-shared's quartics in a), by a
 *  Fibonacci search of 2,000 directions (a hemisphere: a and −a are the same zonal harmonic)
 *  refined by halving steps from 0.05 toward the best of four neighbours. */
function bestAxis(score) {
  const kSearch = 2000, golden = Math.PI * (3 - Math.sqrt(5));
  let best = [0, 0, 1], bestE = -1;
  for (let i = 0; i < kSearch; ++i) {
    const z = 1 - (i + 0.5) / kSearch, r = Math.sqrt(1 - z * z), phi = golden * i;
    const a = [r * Math.cos(phi), r * Math.sin(phi), z];
    const e = score(a);
    if (e > bestE) bestE = e, best = a;
  }
  for (let step = 0.05; step > 1e-7; step *= 0.5) {
    const [t, b] = orthonormalBasis(best);
    let moved = true;
    while (moved) {
      moved = false;
      for (const d of [t, [-t[0], -t[1], -t[2]], b, [-b[0], -b[1], -b[2]]]) {
        const a = normalize3([best[0] + d[0] * step, best[1] + d[1] * step, best[2] + d[2] * step]);
        const e = score(a);
        if (e > bestE) bestE = e, best = a, moved = true;
      }
    }
  }
  return best;
}

/** zh3-optimal's axis: the one that holds the most of band 2 summed over the channels,
 *  the maximum of Σ_c z_c(a)². */
function bestZonalAxis(l) {
  const y = new Float64Array(9);
  return bestAxis((a) => {
    const z = zonalProjection(l, a, y);
    return dot3(z, z);
  });
}

/** zh3-shared's axis for the colour w (the channels' L₀₀): the maximum of (Σ_c w_c z_c(a))²,
 *  what the least-squares zonal term s w Y₂₀(a·ω) removes of band 2. */
function bestSharedAxis(l, w) {
  const y = new Float64Array(9);
  return bestAxis((a) => {
    const p = dot3(zonalProjection(l, a, y), w);
    return p * p;
  });
}

// ---- de-ringing (sh::dering, window.cpp) ------------------------------------------------------
// The grid minima are taken on: Gauss–Legendre with n = max(48, 8B) rings of 2n directions
// (gaussLegendreSphere), B = 3 here. Built once: the directions' Y values, 9 a direction.
let ringGrid = null;
function minimumGrid() {
  if (ringGrid) return ringGrid;
  const n = 48, nphi = 2 * n, y = new Float64Array(n * nphi * 9), one = new Float64Array(9);
  for (let i = 0; i < n; ++i) {
    const z = gaussLegendreNode(n, i), s = Math.sqrt(Math.max(0, 1 - z * z));
    for (let j = 0; j < nphi; ++j) {
      const phi = 2 * Math.PI * (j + 0.5) / nphi;
      evalSh(3, s * Math.cos(phi), s * Math.sin(phi), z, one);
      y.set(one, (i * nphi + j) * 9);
    }
  }
  return (ringGrid = { count: n * nphi, y });
}

/** Node i of the n-point Gauss–Legendre rule (core/quadrature.cpp): Newton's method on P_n from
 *  cos(π (i + 3/4) / (n + 1/2)). */
function gaussLegendreNode(n, i) {
  let x = Math.cos(Math.PI * (i + 0.75) / (n + 0.5));
  for (let it = 0; it < 100; ++it) {
    let p0 = 1, p1 = x;
    for (let k = 2; k <= n; ++k) {
      const pk = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
      p0 = p1, p1 = pk;
    }
    const pn = n === 1 ? x : p1, pm = n === 1 ? 1 : p0;
    const dp = n * (x * pn - pm) / (x * x - 1);
    const dx = pn / dp;
    x -= dx;
    if (Math.abs(dx) < 1e-16) break;
  }
  return x;
}

/** The Hanning window of width w over 3 bands (sh::hanningWindow): ½(1 + cos(πl/w)) for l < w. */
const hanning = (w) => [0, 1, 2].map((l) => (l < w ? 0.5 * (1 + Math.cos(Math.PI * l / w)) : 0));

/**
 * sh::dering of a 3-band RGB function e (27 floats, in place): if it is negative somewhere on
 * the grid, the widest Hanning window W in [1, 3] (bisection to 10⁻³, non-negativity taken as
 * monotone in W) whose windowed function stays ≥ 10⁻³ × its maximum on the grid (a minimum of
 * exactly 0 can hide negative values between nodes), applied as the library applies it (floats).
 * Each band's part at every node is summed once, so a window costs 3 products a node and channel.
 */
function dering(e) {
  const grid = minimumGrid(), N = grid.count, part = new Float64Array(N * 9);
  for (let k = 0; k < N; ++k) {
    const y = grid.y.subarray(9 * k, 9 * k + 9);
    for (let l = 0; l < 3; ++l)
      for (let c = 0; c < 3; ++c) {
        let s = 0;
        for (let i = l * l; i < (l + 1) * (l + 1); ++i) s += e[3 * i + c] * y[i];
        part[9 * k + 3 * l + c] = s;
      }
  }
  const extremes = (w) => {
    let lo = Infinity, hi = -Infinity;
    for (let k = 0; k < N; ++k)
      for (let c = 0; c < 3; ++c) {
        const v = w[0] * part[9 * k + c] + w[1] * part[9 * k + 3 + c] + w[2] * part[9 * k + 6 + c];
        if (v < lo) lo = v;
        if (v > hi) hi = v;
      }
    return [lo, hi];
  };
  if (extremes([1, 1, 1])[0] >= 0) return;  // nothing to do
  const kMargin = 1e-3;
  const ok = (width) => {
    const [lo, hi] = extremes(hanning(width));
    return lo >= kMargin * hi;
  };
  let good = 1, bad = 3;
  if (ok(bad)) good = bad;
  else
    for (let it = 0; it < 30 && bad - good > 1e-3; ++it) {
      const mid = 0.5 * (good + bad);
      if (ok(mid)) good = mid;
      else bad = mid;
    }
  const w = hanning(good);
  for (let l = 0; l < 3; ++l)
    for (let i = l * l; i < (l + 1) * (l + 1); ++i)
      for (let c = 0; c < 3; ++c) e[3 * i + c] = f(e[3 * i + c] * f(w[l]));
}

/**
 * Encodes the irradiance of `radiance` (bands² RGB coefficients, any bands ≥ 1: what it lacks of
 * bands 0..2 counts as zero, bands past 2 are not read) in encoding `name` (sh::encodeIrradiance):
 * { encoding, sh: Float64Array(rows·3) of irradiance SH E_lm = Λ_l L_lm (9 rows for l2 and
 * l2-deringed, 4 for the others, windowed ones already windowed), axis: [x, y, z] (the zh3 forms'
 * zonal axis, else +Z), zonal: [r, g, b] (each channel's coefficient of Y₂₀(axis·n) in the
 * irradiance, Λ₂ times the radiance's) }. Throws the library's line for an unknown name.
 */
export function encode(radiance, bands, name) {
  const spec = encodingSpec(name);
  // l: the radiance's bands 0..2 as the library's float RgbSh holds them; e: their irradiance
  // SH, scaled by Λ_l in floats as convolveZonal scales an RgbSh.
  const l = new Float64Array(27), e = new Float64Array(27);
  const n = Math.min(9, bands * bands);
  for (let i = 0; i < n; ++i)
    for (let c = 0; c < 3; ++c) {
      l[3 * i + c] = f(radiance[3 * i + c]);
      e[3 * i + c] = f(l[3 * i + c] * f(clampedCosine[i < 1 ? 0 : i < 4 ? 1 : 2]));
    }
  if (name === 'l2-deringed') dering(e);
  const sh = e.slice(0, 3 * spec.rows);
  if (name === 'l1-windowed') {
    // E(n) = E₀ + d·n has its minimum E₀ − |d| at n = −d̂: scaling band 1 by min(1, E₀/|d|) is
    // the mildest window that leaves it non-negative (zero where E₀ ≤ 0: no window can).
    for (let ch = 0; ch < 3; ++ch) {
      const e0 = sh[ch] * kY00, d = kY1 * length3(bandOne(sh, ch));
      const w = d <= Math.max(e0, 0) ? 1 : Math.max(e0, 0) / d;
      for (let i = 1; i < 4; ++i) sh[3 * i + ch] *= w;
    }
  }
  let axis = [0, 0, 1], zonal = [0, 0, 0];
  if (spec.zonal) {
    // The zonal coefficient is made from the radiance's bands, then convolved.
    const lambda2 = clampedCosine[2];
    if (name === 'zh3-shared') {
      // One zonal number s shared in proportion to the channels' L₀₀, about the axis where that
      // colour holds the most of band 2: s = Σ_c L₀₀,c ẑ_c / Σ_c L₀₀,c² (least squares),
      // ẑ = √(4π/5) z(a). No L₀₀: nothing to share, the luminance axis kept.
      const w = [l[0], l[1], l[2]], w2 = dot3(w, w);
      axis = w2 > 0 ? bestSharedAxis(l, w) : luminanceAxis(l);
      const s = w2 > 0 ? kZonalScale * dot3(zonalProjection(l, axis), w) / w2 : 0;
      zonal = w.map((x) => x * (s * lambda2));
    } else if (name !== 'zh3-hallucinated') {
      // z = √(4π/5) Σ_m L₂ₘ Y₂ₘ(a): the best one number along a fixed axis can hold of band 2.
      axis = name === 'zh3-optimal' ? bestZonalAxis(l) : luminanceAxis(l);
      zonal = zonalProjection(l, axis).map((z) => z * (kZonalScale * lambda2));
    } else {
      axis = luminanceAxis(l);
      // Roughton et al. 2024's fit from band 1 alone: r = |L₁·a| / L₀ per channel,
      // z = L₀ (0.08 r + 0.6 r²) (their SHHallucinateZH3Irradiance, RGB form).
      for (let ch = 0; ch < 3; ++ch) {
        const l0 = l[ch];
        if (l0 <= 0) continue;
        const r = Math.abs(dot3(bandOne(l, ch), axis)) / l0;
        zonal[ch] = lambda2 * l0 * (0.08 * r + 0.6 * r * r);
      }
    }
  }
  return { encoding: name, sh, axis, zonal };
}

/** Hazel's (Geomerics 2014) non-negative reconstruction of one channel from its mean E₀ and
 *  band-1 vector d: s = min(|d|/2E₀, 1), p = 1 + 2s, a = (1 − s)/(1 + s), q = (1 + d̂·n)/2,
 *  E = E₀ (a + (1 − a)(p + 1) q^p): mean E₀, band 1 exact at s → 0 and s = 1. */
function geomerics(e0, d, n) {
  const len = length3(d);
  if (e0 <= 0 || len === 0) return e0 + dot3(d, n);
  const s = Math.min(len / (2 * e0), 1);
  const p = 1 + 2 * s, a = (1 - s) / (1 + s);
  const q = 0.5 * (1 + dot3(d, n) / len);
  return e0 * (a + (1 - a) * (p + 1) * Math.pow(Math.max(q, 0), p));
}

/** The encoded irradiance at unit normal (nx, ny, nz), as an engine reconstructs it
 *  (sh::evaluate): into out = [r, g, b]. `y` is scratch (Float64Array(9)). */
export function evaluate(enc, nx, ny, nz, out = [0, 0, 0], y = new Float64Array(9)) {
  const c = enc.sh;
  if (enc.encoding === 'l1-geomerics') {
    const n = [nx, ny, nz];
    for (let ch = 0; ch < 3; ++ch) {
      const d = bandOne(c, ch);
      out[ch] = geomerics(c[ch] * kY00, [kY1 * d[0], kY1 * d[1], kY1 * d[2]], n);
    }
    return out;
  }
  const rows = c.length / 3, bands = rows === 9 ? 3 : 2;
  evalSh(bands, nx, ny, nz, y);
  let r = 0, g = 0, b = 0;
  for (let i = 0; i < rows; ++i) r += c[3 * i] * y[i], g += c[3 * i + 1] * y[i], b += c[3 * i + 2] * y[i];
  // The zh3 forms' zonal harmonic (zero for the others).
  const t = enc.axis[0] * nx + enc.axis[1] * ny + enc.axis[2] * nz, z = kY20 * (3 * t * t - 1);
  r += enc.zonal[0] * z, g += enc.zonal[1] * z, b += enc.zonal[2] * z;
  out[0] = r, out[1] = g, out[2] = b;
  return out;
}
