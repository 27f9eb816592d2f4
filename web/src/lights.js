// SH lights in the page (docs/formats-light.md): the two light files a user can drop, and the
// library's rule for a light with another band count than the transfer (io::loadLighting): more
// bands are cut (exactly: bands are orthogonal), fewer are used as they are — padded with zeros
// for the shaders, which always read the transfer's bands — with a warning that the transfer's
// upper bands see no light.
import { bands as kBands } from 'prt:constants';
import { lightBandsWarning } from './messages.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/**
 * Parses an SH light JSON: { bands, coefficients: [[r, g, b], ...] }.
 * Returns { bands, coeffs: Float32Array(B² × 3) }.
 */
export function parseLightJson(text, name) {
  let j;
  try {
    j = JSON.parse(text);
  } catch (e) {
    fail(name, `is not JSON (${e.message})`);
  }
  if (!j || typeof j !== 'object' || !('coefficients' in j))
    fail(name, 'is not an SH light (no "coefficients"; write one with prt light)');
  const B = j.bands, c = j.coefficients;
  if (!Number.isInteger(B) || B < 1 || B > kBands.maxLibrary)
    fail(name, `"bands" is ${JSON.stringify(B)}, not 1..${kBands.maxLibrary}`);
  if (!Array.isArray(c) || c.length !== B * B)
    fail(name, `has ${Array.isArray(c) ? c.length : 0} coefficients but ${B} bands need ${B * B}`);
  const coeffs = new Float32Array(B * B * 3);
  c.forEach((row, i) => {
    if (!Array.isArray(row) || row.length !== 3 || !row.every((v) => typeof v === 'number' && Number.isFinite(v)))
      fail(name, `coefficient ${i} is not three finite numbers`);
    coeffs.set(row, 3 * i);
  });
  return { bands: B, coeffs };
}

/** Parses the GAMES202 course's light.txt: B² lines "r g b", nothing else. */
export function parseLightTxt(text, name) {
  const lines = text.split(/\r?\n/).map((l) => l.trim()).filter((l) => l.length > 0);
  const B = Math.round(Math.sqrt(lines.length));
  if (lines.length === 0 || B * B !== lines.length)
    fail(name, `has ${lines.length} lines; a light.txt has B² lines of "r g b"`);
  if (B > kBands.maxLibrary) fail(name, `has ${B} bands, not 1..${kBands.maxLibrary}`);
  const coeffs = new Float32Array(lines.length * 3);
  lines.forEach((l, i) => {
    const v = l.split(/\s+/).map(Number);
    if (v.length !== 3 || !v.every(Number.isFinite)) fail(name, `line ${i + 1} is not three numbers`);
    coeffs.set(v, 3 * i);
  });
  return { bands: B, coeffs };
}

/**
 * A light for a transfer of `bands` bands, as io::loadLighting and io::padded make it: the
 * coefficients at exactly `bands` (cut, or padded with zeros) and the warnings (one line each).
 */
export function lightForTransfer(name, light, bands) {
  const n = bands * bands, coeffs = new Float32Array(n * 3);
  coeffs.set(light.coeffs.subarray(0, Math.min(light.coeffs.length, n * 3)));
  const warnings = light.bands < bands ? [lightBandsWarning(name, light.bands, bands)] : [];
  return { coeffs, warnings };
}
