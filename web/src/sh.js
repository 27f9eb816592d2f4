// Spherical harmonics for the page: rotation of an RGB light and evaluation for backgrounds.
// Conventions as the C++ library (include/prt/sh/sh.hpp, docs/conventions.md): bands B means
// degrees l = 0..B−1, B² coefficients, index i = l(l+1)+m; real orthonormal SH with the
// Condon–Shortley phase, evaluated on world (x, y, z), +Y up.
//
// Rotation: rotating a light by R gives L'(ω) = L(Rᵀ ω); band l transforms by a (2l+1)² matrix
// M_l(R). We build the matrices by the Ivanic–Ruedenberg recurrence (J. Phys. Chem. 100 (1996)
// 6342, with the errata of J. Phys. Chem. A 102 (1998) 9099), which works in the basis without
// the Condon–Shortley phase, then change basis: M_mn ← (−1)^(m+n) M_mn. The C++ library's fast
// path (zxzxz, src/sh/rotate.cpp) differs; tests/web checks both agree to 1e-5.

/** R = Rz Ry Rx from Euler degrees (about X, then Y, then Z), as `prt render --rotate X,Y,Z`. */
export function rotationEulerXYZ(degX, degY, degZ) {
  const d2r = Math.PI / 180;
  return mul3(mul3(axisAngle([0, 0, 1], degZ * d2r), axisAngle([0, 1, 0], degY * d2r)),
              axisAngle([1, 0, 0], degX * d2r));
}

/** Rotation by `angle` radians about the unit axis a, row-major [[..], [..], [..]]. */
export function axisAngle(a, angle) {
  const n = Math.hypot(a[0], a[1], a[2]);
  const x = a[0] / n, y = a[1] / n, z = a[2] / n;
  const c = Math.cos(angle), s = Math.sin(angle), t = 1 - c;
  return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
          [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
          [t * x * z - s * y, t * y * z + s * x, t * z * z + c]];
}

export function mul3(a, b) {
  const r = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (let i = 0; i < 3; ++i)
    for (let j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  return r;
}

export function transpose3(a) {
  return [[a[0][0], a[1][0], a[2][0]], [a[0][1], a[1][1], a[2][1]], [a[0][2], a[1][2], a[2][2]]];
}

/**
 * The band matrices M_l(R), l = 0..bands−1, in our (Condon–Shortley) basis: an array of
 * Float64Array, band l row-major (2l+1)×(2l+1), element (m, n) at (m+l)(2l+1) + (n+l).
 */
export function rotationBlocks(bands, r) {
  const blocks = [Float64Array.of(1)];
  if (bands < 2) return blocks;
  // Band 1 in the basis (y, z, x) (m = −1, 0, 1): M¹_ij = R[t(i)][t(j)], t = (1, 2, 0).
  const t = [1, 2, 0];
  const m1 = new Float64Array(9);
  for (let i = 0; i < 3; ++i)
    for (let j = 0; j < 3; ++j) m1[i * 3 + j] = r[t[i]][t[j]];
  blocks.push(m1);
  const R = (i, j) => m1[(i + 1) * 3 + (j + 1)];
  for (let l = 2; l < bands; ++l) {
    const prev = blocks[l - 1], w = 2 * l + 1, wp = 2 * l - 1;
    const M = (a, b) => prev[(a + l - 1) * wp + (b + l - 1)];
    // P(i, a, b): the recurrence's building block (Ivanic & Ruedenberg, Table 2).
    const P = (i, a, b) => {
      if (b === l) return R(i, 1) * M(a, l - 1) - R(i, -1) * M(a, -l + 1);
      if (b === -l) return R(i, 1) * M(a, -l + 1) + R(i, -1) * M(a, l - 1);
      return R(i, 0) * M(a, b);
    };
    const cur = new Float64Array(w * w);
    for (let m = -l; m <= l; ++m) {
      for (let n = -l; n <= l; ++n) {
        const d = Math.abs(n) === l ? 2 * l * (2 * l - 1) : (l + n) * (l - n);
        const am = Math.abs(m), m0 = m === 0 ? 1 : 0;
        const u = Math.sqrt(((l + m) * (l - m)) / d);
        const v = 0.5 * Math.sqrt(((1 + m0) * (l + am - 1) * (l + am)) / d) * (1 - 2 * m0);
        const wv = -0.5 * Math.sqrt(((l - am - 1) * (l - am)) / d) * (1 - m0);
        let val = 0;
        if (u !== 0) val += u * P(0, m, n);
        if (v !== 0) {
          let V;
          if (m === 0) V = P(1, 1, n) + P(-1, -1, n);
          else if (m > 0) V = P(1, m - 1, n) * Math.sqrt(1 + (m === 1 ? 1 : 0)) -
                              P(-1, -m + 1, n) * (m === 1 ? 0 : 1);
          else V = P(1, m + 1, n) * (m === -1 ? 0 : 1) +
                   P(-1, -m - 1, n) * Math.sqrt(1 + (m === -1 ? 1 : 0));
          val += v * V;
        }
        if (wv !== 0) {
          const W = m > 0 ? P(1, m + 1, n) + P(-1, -m - 1, n) : P(1, m - 1, n) - P(-1, -m + 1, n);
          val += wv * W;
        }
        cur[(m + l) * w + (n + l)] = val;
      }
    }
    blocks.push(cur);
  }
  // To the Condon–Shortley basis: negate where m + n is odd.
  for (let l = 1; l < bands; ++l) {
    const b = blocks[l], w = 2 * l + 1;
    for (let i = 0; i < w; ++i)
      for (let j = 0; j < w; ++j)
        if ((i + j) & 1) b[i * w + j] = -b[i * w + j];
  }
  return blocks;
}

/**
 * Rotates an RGB light: `light` holds B² × 3 floats (coefficient-major: i·3 + c), the result
 * likewise; `bands` ≤ the light's bands (rotation is block-diagonal over bands, so rotating the
 * first b bands equals cutting the rotated light).
 */
export function rotateLight(bands, r, light, out = new Float32Array(bands * bands * 3)) {
  const blocks = rotationBlocks(bands, r);
  for (let l = 0; l < bands; ++l) {
    const b = blocks[l], w = 2 * l + 1, o = l * l;
    for (let m = 0; m < w; ++m)
      for (let c = 0; c < 3; ++c) {
        let s = 0;
        for (let n = 0; n < w; ++n) s += b[m * w + n] * light[(o + n) * 3 + c];
        out[(o + m) * 3 + c] = s;
      }
  }
  return out;
}

/** N_lm, the factor of Y_lm beyond the Legendre and azimuthal parts (sh::normalization):
 *  K_l|m| = √((2l+1)/4π · (l−|m|)!/(l+|m|)!), times √2 for m ≠ 0. */
export function shNormalization(l, m) {
  const am = Math.abs(m);
  let k = (2 * l + 1) / (4 * Math.PI);
  for (let f = l - am + 1; f <= l + am; ++f) k /= f;
  k = Math.sqrt(k);
  return m === 0 ? k : Math.SQRT2 * k;
}

/**
 * Y_i(d) for i < B² at a unit direction (x, y, z) into `out` (Float64Array(B²)): the associated
 * Legendre recurrence in z with the Condon–Shortley phase, and the azimuthal factors
 * Re/Im (x + i y)^m built by recurrence. Y_l0 = K_l0 P_l0, Y_lm = √2 K_lm P_lm cos mφ (m > 0),
 * Y_l−m = √2 K_lm P_lm sin mφ, K_lm = √((2l+1)/4π · (l−m)!/(l+m)!).
 */
export function evalSh(bands, x, y, z, out = new Float64Array(bands * bands)) {
  // P_m^m(z) with the (−1)^m phase, times sin^m θ absorbed into (x + iy)^m below; we recur the
  // "reduced" P̃_lm = P_lm / sin^m θ, a polynomial in z.
  let cm = 1, sm = 0;  // Re, Im of (x + i y)^m
  let pmm = 1;          // P̃_mm = (−1)^m (2m−1)!!
  for (let m = 0; m < bands; ++m) {
    if (m > 0) {
      pmm *= -(2 * m - 1);
      const c = cm * x - sm * y, s = cm * y + sm * x;
      cm = c, sm = s;
    }
    let prev2 = 0, prev1 = 0;  // P̃_{l−2,m}, P̃_{l−1,m}
    for (let l = m; l < bands; ++l) {
      const p = l === m ? pmm
              : l === m + 1 ? z * (2 * m + 1) * pmm
              : ((2 * l - 1) * z * prev1 - (l + m - 1) * prev2) / (l - m);
      prev2 = prev1, prev1 = p;
      const k = shNormalization(l, m);  // √2 K_lm for m > 0
      if (m === 0) out[l * (l + 1)] = k * p;
      else {
        out[l * (l + 1) + m] = k * p * cm;
        out[l * (l + 1) - m] = k * p * sm;
      }
    }
  }
  return out;
}
