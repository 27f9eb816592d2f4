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
 * object), the three.js LightProbe that `prt light --format threejs` writes (three.js object
 * JSON, ObjectLoader's: 3 bands, signs turned back to our basis, times its intensity) or the
 * GAMES202 course's light.txt (text). Throws one line naming `name`.
 */
export function parseLight(input, name = 'light') {
  let j = typeof input === 'object' && input !== null ? input : null;
  const text = j ? '' : String(input);
  if (!j && text.trimStart().startsWith('{')) {
    try {
      j = JSON.parse(text);
    } catch (e) {
      throw new Error(`${name}: is not JSON (${e.message})`);
    }
  }
  if (!j) return parseLightTxt(text, name);
  if (!('coefficients' in j) && j.object && typeof j.object === 'object') return fromLightProbeJson(j.object, name);
  return parseLightJson(JSON.stringify(j), name);
}

/** Our light from a three.js LightProbe's object JSON (ObjectLoader's `object`). */
function fromLightProbeJson(o, name) {
  if (o.type !== 'LightProbe')
    throw new Error(`${name}: is a three.js ${JSON.stringify(o.type)}, not a LightProbe (write one with prt light --format threejs)`);
  const sh = o.sh, k = o.intensity === undefined ? 1 : o.intensity;
  if (!Array.isArray(sh) || sh.length !== 27 || !sh.every((v) => typeof v === 'number' && Number.isFinite(v)))
    throw new Error(`${name}: the LightProbe's "sh" is not 27 finite numbers (9 × r, g, b)`);
  if (typeof k !== 'number' || !Number.isFinite(k))
    throw new Error(`${name}: the LightProbe's "intensity" is ${JSON.stringify(k)}, not a finite number`);
  const coeffs = new Float32Array(27);
  for (let i = 0; i < 27; ++i) coeffs[i] = sh[i] * kCondonShortley[Math.floor(i / 3)] * k;
  return { bands: 3, coeffs };
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
