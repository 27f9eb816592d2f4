// Time of the page's per-frame SH rotation (src/sh.js rotateLight: band matrices by the
// Ivanic–Ruedenberg recurrence, then the matrix-vector products), at 5 and 9 bands.
// Usage: node web/bench-rotation.mjs   (figures in docs/web.md)
import { rotateLight, rotationEulerXYZ } from './src/sh.js';

for (const B of [5, 9]) {
  const L = Float32Array.from({ length: B * B * 3 }, (_, i) => Math.sin(i));
  const out = new Float32Array(B * B * 3);
  for (let i = 0; i < 200; ++i) rotateLight(B, rotationEulerXYZ(i, 2 * i, 3 * i), L, out);
  const n = 2000, t0 = performance.now();
  for (let i = 0; i < n; ++i) rotateLight(B, rotationEulerXYZ(i, 2 * i, 3 * i), L, out);
  console.log(`${B} bands: ${((performance.now() - t0) / n * 1000).toFixed(1)} µs per rotation`);
}
