// What PRTBake and ProbeGridLighting take from their users, checked by one set of rules: the
// bands relit, the exposure of the bake's own meshes, the light (the library's band rule:
// lights.js lightForTransfer) and the irradiance encoding a matrix transfer is drawn through
// (encoded_diffuse.js: prt render --encoding's refusals). Each throws one line naming the bake.
import { image as kImage } from 'prt:constants';
import { lightForTransfer } from '../../src/lights.js';
import { encodingRefusal } from '../../src/encoded_diffuse.js';

/** Bands to relight: a positive integer, cut to the transfer's `max`. */
export function checkedBands(name, b, max) {
  if (!(Number.isInteger(b) && b >= 1)) throw new Error(`${name}: bands must be a positive integer, not ${b}`);
  return Math.min(b, max);
}

/** The radiance scale 2^stops, the stops clamped to the library's exposure range. */
export function exposureScale(name, stops) {
  if (!Number.isFinite(stops)) throw new Error(`${name}: exposure must be a finite number of stops, not ${stops}`);
  return Math.pow(2, Math.min(Math.max(stops, -kImage.maxExposureStops), kImage.maxExposureStops));
}

/** `light` ({ bands, coeffs: B² × 3 }, parseLight's) checked, and its coefficients for a
 *  transfer of `bands` bands with the warnings of the library's band rule: { coeffs, warnings }. */
export function transferLight(name, light, bands) {
  if (!light || !Number.isInteger(light.bands) || !(light.coeffs && light.coeffs.length === light.bands * light.bands * 3))
    throw new Error(`${name}: a light is { bands, coeffs: bands² × 3 numbers } (parseLight makes one)`);
  return lightForTransfer('light', light, bands);
}

/** `encoding` ('none' or an encoding's name, irradiance_encoding.js) for transfer t of bake b
 *  (readBake's), checked: a vector, per-texel or probe transfer refuses a name. */
export function checkedEncoding(b, t, encoding) {
  if (typeof encoding !== 'string') throw new Error(`${b.name}: encoding must be 'none' or an encoding's name, not ${encoding}`);
  const refusal = encodingRefusal(b, t, encoding);
  if (refusal) throw new Error(refusal);
  return encoding;
}
