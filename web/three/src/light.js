// SH lights for the three.js module (docs/formats-light.md, docs/three.md): prtkit's light
// files, and three.js's own SphericalHarmonics3 (a LightProbe's) both ways. three.js's basis is
// ours without the Condon–Shortley phase: coefficients 1, 3, 5, 7 (odd m) change sign
// (io::engine_light, `prt light --format threejs`, checked against three.js's
// LightProbeGenerator in tests/web).
import * as THREE from 'three';
import { parseLightJson, parseLightTxt } from '../../src/lights.js';

const kCondonShortley = [1, -1, 1, -1, 1, -1, 1, -1, 1];

/**
 * A light { bands, coeffs: Float32Array(B² × 3) } from prt light's JSON (text or the parsed
 * object) or the GAMES202 course's light.txt (text). Throws one line naming `name`.
 */
export function parseLight(input, name = 'light') {
  if (typeof input === 'object' && input !== null) return parseLightJson(JSON.stringify(input), name);
  const text = String(input);
  return text.trimStart().startsWith('{') ? parseLightJson(text, name) : parseLightTxt(text, name);
}

/** Our 3-band light from three.js's SphericalHarmonics3 (e.g. LightProbeGenerator's). */
export function lightFromSphericalHarmonics3(sh) {
  const coeffs = new Float32Array(27);
  sh.coefficients.forEach((c, i) => coeffs.set([c.x * kCondonShortley[i], c.y * kCondonShortley[i], c.z * kCondonShortley[i]], 3 * i));
  return { bands: 3, coeffs };
}

/** The first three bands of our light as three.js's SphericalHarmonics3 (for a LightProbe that
 *  lights standard materials beside the bake with the same environment), zero-padded. */
export function lightToSphericalHarmonics3(light, target = new THREE.SphericalHarmonics3()) {
  for (let i = 0; i < 9; ++i) {
    const s = kCondonShortley[i], o = 3 * i;
    target.coefficients[i].set(...(i < light.bands * light.bands
      ? [light.coeffs[o] * s, light.coeffs[o + 1] * s, light.coeffs[o + 2] * s] : [0, 0, 0]));
  }
  return target;
}
