// Relighting Haar transfer in the page and prtkit-three: relight::relightHaar
// (include/prt/relight/relight_haar.hpp) in JavaScript. Per row, from its sparse terms and the
// light's (haar_light.js):
//     occluded-part row   R = kd ⊙ ( U(n)·L − Σ_t D̃_t L̃[k_t] )
//     visible-part row    R = kd ⊙ Σ_t T̃_t L̃[k_t]
// with U(n)·L = Σ_b L_b U_b(n) + Σ_lm (A_l/π) L'_lm Y_lm(n): the light's 16 brightest texels
// exactly (their clamped-cosine integrals at the row's normal) and the rest in 5-band SH. The
// light's K terms are laid out densely (6 N² RGB), so each kept transfer term is one gather.
// An inter-reflected row adds its bounce, B² SH coefficients (C = 1: the same for r, g, b; C =
// 3: one a channel, the bounce albedos folded in) against the light's full SH (the rest and the
// bright texels' patches: haarLightFullSh) at its first B bands, inside kd:
//     R += kd ⊙ Σ_{i < B²} B_{i,c} L_{i,c}
import { clampedCosine, haarLightFullSh, shBasis, texelGeometry } from './haar_light.js';

const kBands = 5, kCoeffs = kBands * kBands;

/** sh::clampedCosineKernel(5) over π: A_l/π of the clamped cosine, l = 0..4. */
const kLobe = (() => {
  const k = [Math.PI, (2 * Math.PI) / 3, 0, 0, 0];
  let c = 0.5;
  for (let l = 2; l < kBands; l += 2) {
    const sign = (l / 2 - 1) % 2 === 0 ? 1 : -1;
    k[l] = ((2 * Math.PI * sign) / ((l + 2) * (l - 1))) * c;
    c *= (l + 1) / (l + 2);
  }
  return k.map((x) => x / Math.PI);
})();

/** relight_haar.cpp's BrightCone: a bright texel as each row meets it — n·Φ/π wholly above n's
 *  horizon, nothing wholly below, the clipped polygon only where the horizon crosses it; a cone
 *  about the texel's centre (half-angle α: n·c ≥ sin α puts every corner above, ≤ −sin α below)
 *  decides which with one dot product. */
function brightCone(g, radiance) {
  const s = [0, 1, 2].map((i) => g.corners.reduce((a, v) => a + v[i], 0)), len = Math.hypot(s[0], s[1], s[2]);
  const c = s.map((v) => v / len);
  const cosAlpha = Math.min(1, ...g.corners.map((v) => c[0] * v[0] + c[1] * v[1] + c[2] * v[2]));
  return { g, l: radiance, c, sin: Math.sqrt(Math.max(0, 1 - cosAlpha * cosAlpha)) + 1e-5, m: g.moment.map((v) => v / Math.PI) };
}

/**
 * Exit radiance of rows first .. first + count − 1 of Haar transfer `t` (haar_bake.js's:
 * t.haar = { resolution, terms, bounceBands }, t.channels, t.rows = Float32Array of rows × (1 +
 * 2·terms + bounceBands²·channels): the kind, the (index, value) pairs, then the bounce) under
 * `light` (its fullSh made with it, else made here), at `normals` (Float32Array, 3 for each of
 * the `count` rows), with `albedo` (Float32Array likewise, [r, g, b] for every row, or null:
 * white), into `out` (Float32Array, 3 for each row): a part's vertices, whose rows start at
 * `first`.
 */
export function relightHaar(t, light, normals, albedo, out, first = 0, count = normals.length / 3) {
  const n = t.haar.resolution, terms = t.haar.terms, pairs = 1 + 2 * terms;
  const B = t.haar.bounceBands || 0, C = t.channels === 3 ? 3 : 1, stride = pairs + B * B * C;
  if (light.resolution !== n)
    throw new Error(`relight: the light's cube is ${light.resolution}² per face and the transfer's ${n}² (project the light at the transfer's resolution)`);
  const dense = new Float32Array(6 * n * n * 3);
  light.index.forEach((k, i) => dense.set(light.value.subarray(3 * i, 3 * i + 3), 3 * k));
  const lobe = new Float64Array(kCoeffs * 3);
  for (let l = 0; l < kBands; ++l)
    for (let i = l * l; i < (l + 1) * (l + 1); ++i)
      for (let c = 0; c < 3; ++c) lobe[3 * i + c] = light.unshadowed[3 * i + c] * kLobe[l];
  const bright = light.bright.map((b) => brightCone(texelGeometry(b.texel, n), b.radiance));
  // The bounce's light: the full SH's first B² coefficients, RGB each.
  const full = B > 0 ? light.fullSh || haarLightFullSh(light) : null, shCount = B * B;
  const y = new Float64Array(kCoeffs), nrm = [0, 0, 0], rows = t.rows;
  const one = albedo && albedo.length === 3;
  for (let r = 0; r < count; ++r) {
    const p = (first + r) * stride, occluded = rows[p] === 0;
    let x = 0, g = 0, z = 0;
    if (occluded) {
      nrm[0] = normals[3 * r], nrm[1] = normals[3 * r + 1], nrm[2] = normals[3 * r + 2];
      shBasis(nrm[0], nrm[1], nrm[2], y);
      for (let i = 0; i < kCoeffs; ++i) x += y[i] * lobe[3 * i], g += y[i] * lobe[3 * i + 1], z += y[i] * lobe[3 * i + 2];
      for (const b of bright) {
        const side = nrm[0] * b.c[0] + nrm[1] * b.c[1] + nrm[2] * b.c[2];
        if (side <= -b.sin) continue;  // wholly below the horizon: nothing
        const u = side >= b.sin ? Math.max(0, nrm[0] * b.m[0] + nrm[1] * b.m[1] + nrm[2] * b.m[2]) : clampedCosine(b.g, nrm);
        x += u * b.l[0], g += u * b.l[1], z += u * b.l[2];
      }
    }
    const sign = occluded ? -1 : 1;
    for (let k = 0; k < terms; ++k) {
      const c = 3 * rows[p + 1 + 2 * k], v = sign * rows[p + 2 + 2 * k];
      x += v * dense[c], g += v * dense[c + 1], z += v * dense[c + 2];
    }
    if (C === 1) {
      for (let i = 0, q = p + pairs; i < shCount; ++i) {
        const v = rows[q + i];
        x += v * full[3 * i], g += v * full[3 * i + 1], z += v * full[3 * i + 2];
      }
    } else {
      for (let i = 0, q = p + pairs; i < shCount; ++i)
        x += rows[q + 3 * i] * full[3 * i], g += rows[q + 3 * i + 1] * full[3 * i + 1], z += rows[q + 3 * i + 2] * full[3 * i + 2];
    }
    const a = !albedo ? null : one ? 0 : 3 * r;
    out[3 * r] = a === null ? x : albedo[a] * x;
    out[3 * r + 1] = a === null ? g : albedo[a + 1] * g;
    out[3 * r + 2] = a === null ? z : albedo[a + 2] * z;
  }
  return out;
}
