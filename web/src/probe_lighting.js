// Relighting a probe grid in JavaScript (issue 32), step for step the library's
// relight/relight_probes.cpp (Sloan, Kautz & Snyder 2002, §7; Ramamoorthi & Hanrahan 2001):
//
//   relightProbes   L'_p = M_p L per probe and colour channel, at b = min(light, transfer) bands
//                   (the light already rotated: sh.js rotateLight, as the library rotates it
//                   with sh::Rotation before relighting), b²·b² multiply-adds per probe and channel;
//   sampleProbes    the trilinear blend of the eight probes around a point, clamped to the grid
//                   (outside it, the nearest face's probes);
//   shadeDiffuse    ρ E(n)/π with E(n) = Σ_l A_l Σ_m L'_lm Y_lm(n), A_l the clamped cosine's
//                   kernel (sh::clampedCosineKernel, from 'prt:constants': A_0 = π, A_1 = 2π/3,
//                   A_2 = π/4, 0 for odd l > 1), Y our basis (sh.js evalSh);
//   shadeVertices   render::shadeThroughProbes: every vertex of a mesh lit so.
//
// Coefficients are RGB, coefficient-major (i·3 + c), in prtkit's SH convention (sh.js). The grid
// and the matrices are probe_bake.js's. tests/web/test_probes_web.cpp holds these to the C++.
import { clampedCosine } from 'prt:constants';
import { evalSh } from './sh.js';

const f = Math.fround;  // the library's float arithmetic, where an index or a weight depends on it

/**
 * The light arriving at every probe: { grid, bands b, coeffs: Float32Array(P·b²·3) } (probe p's
 * coefficient i, channel c at (p·b² + i)·3 + c). `transfer` a probe transfer (probe_bake.js),
 * `light` the rotated light's first `bands` bands (b²·3 values, or more: only b² are read).
 */
export function relightProbes(transfer, grid, light, bands, out = null) {
  const B = transfer.bands, n = B * B, C = transfer.channels, M = transfer.matrices;
  const b = Math.min(bands, B), b2 = b * b;
  const P = grid.count[0] * grid.count[1] * grid.count[2];
  const coeffs = out && out.length === P * b2 * 3 ? out : new Float32Array(P * b2 * 3);
  for (let p = 0; p < P; ++p) {
    // M row-major (row i arriving, column j source), channels innermost.
    const base = p * n * n * C, o = p * b2 * 3;
    for (let i = 0; i < b2; ++i) {
      const row = base + i * n * C;
      let r = 0, g = 0, bl = 0;
      for (let j = 0; j < b2; ++j) {
        const e = row + j * C, lr = light[3 * j], lg = light[3 * j + 1], lb = light[3 * j + 2];
        if (C === 1) {
          const t = M[e];
          r += t * lr, g += t * lg, bl += t * lb;
        } else {
          r += M[e] * lr, g += M[e + 1] * lg, bl += M[e + 2] * lb;
        }
      }
      coeffs[o + 3 * i] = r, coeffs[o + 3 * i + 1] = g, coeffs[o + 3 * i + 2] = bl;
    }
  }
  return { grid, bands: b, coeffs };
}

/** The position of probe row r: origin + (x·sx, y·sy, z·sz), r = x + nx·(y + ny·z). */
export function probePosition(grid, r, out = [0, 0, 0]) {
  const nx = grid.count[0], ny = grid.count[1];
  const cell = [r % nx, Math.floor(r / nx) % ny, Math.floor(r / (nx * ny))];
  for (let a = 0; a < 3; ++a) out[a] = f(grid.origin[a] + f(grid.spacing[a] * cell[a]));
  return out;
}

/**
 * The trilinear blend of the eight probes around the point (x, y, z) into `out` (b²·3 values):
 * u = clamp((p − origin)/spacing, 0, n − 1) per axis, the cell's low corner
 * min(⌊u⌋, max(n − 2, 0)), weights (1 − t, t) with t = u − corner (0 along a single probe).
 */
export function sampleProbes(lighting, x, y, z, out = new Float64Array(lighting.bands ** 2 * 3)) {
  const g = lighting.grid, k = lighting.bands * lighting.bands * 3, c = lighting.coeffs;
  const point = [x, y, z], lo = [0, 0, 0], t = [0, 0, 0];
  for (let a = 0; a < 3; ++a) {
    const n = g.count[a];
    const u = Math.min(Math.max(f(f(f(point[a]) - g.origin[a]) / g.spacing[a]), 0), n - 1);
    lo[a] = Math.min(Math.floor(u), Math.max(n - 2, 0));
    t[a] = n > 1 ? f(u - lo[a]) : 0;
  }
  out.fill(0, 0, k);
  const nx = g.count[0], ny = g.count[1];
  for (let corner = 0; corner < 8; ++corner) {
    let w = 1;
    const cell = [0, 0, 0];
    for (let a = 0; a < 3; ++a) {
      const up = (corner >> a) & 1;
      w = f(w * (up ? t[a] : f(1 - t[a])));
      cell[a] = Math.min(lo[a] + up, g.count[a] - 1);
    }
    if (w === 0) continue;
    const o = (cell[0] + nx * (cell[1] + ny * cell[2])) * k;
    for (let i = 0; i < k; ++i) out[i] += c[o + i] * w;
  }
  return out;
}

/**
 * Diffuse exit radiance ρ E(n)/π of a surface with unit normal (nx, ny, nz) and albedo
 * (ρr, ρg, ρb) lit by the SH `incident` (b² RGB coefficients): E(n) = Σ_l A_l Σ_m L'_lm Y_lm(n).
 * `y` is scratch for the basis (Float64Array(b²)). Returns out = [r, g, b].
 */
export function shadeDiffuse(incident, bands, nx, ny, nz, albedo, out = [0, 0, 0], y = new Float64Array(bands * bands)) {
  evalSh(bands, nx, ny, nz, y);
  let r = 0, g = 0, b = 0;
  for (let l = 0; l < bands; ++l) {
    const a = clampedCosine[l];
    for (let i = l * l; i < (l + 1) * (l + 1); ++i) {
      const w = a * y[i];
      r += incident[3 * i] * w, g += incident[3 * i + 1] * w, b += incident[3 * i + 2] * w;
    }
  }
  out[0] = (albedo[0] * r) / Math.PI, out[1] = (albedo[1] * g) / Math.PI, out[2] = (albedo[2] * b) / Math.PI;
  return out;
}

/**
 * render::shadeThroughProbes: per vertex, ρ E(n)/π through the probes at the vertex, into `out`
 * (3 floats a vertex). positions, normals (unit): 3 floats a vertex, in the grid's frame;
 * albedo: 3 floats a vertex, or null for white. Returns out.
 */
export function shadeVertices(lighting, positions, normals, albedo, out = new Float32Array(positions.length)) {
  const sh = new Float64Array(lighting.bands ** 2 * 3), y = new Float64Array(lighting.bands ** 2);
  const white = [1, 1, 1], rho = [0, 0, 0], rgb = [0, 0, 0];
  for (let v = 0, V = positions.length / 3; v < V; ++v) {
    const o = 3 * v;
    sampleProbes(lighting, positions[o], positions[o + 1], positions[o + 2], sh);
    if (albedo) rho[0] = albedo[o], rho[1] = albedo[o + 1], rho[2] = albedo[o + 2];
    shadeDiffuse(sh, lighting.bands, normals[o], normals[o + 1], normals[o + 2], albedo ? rho : white, rgb, y);
    out[o] = rgb[0], out[o + 1] = rgb[1], out[o + 2] = rgb[2];
  }
  return out;
}
