// The shading of a glossy (matrix) transfer as the shaders take it (shaders/prt_glossy.glsl):
// the material's kernels per coefficient times the SH normalisation N_lm that the shaders'
// basis leaves out (relight::shaderKernel), kd (else the vertex albedo) and ks. prt web writes
// them into prt-data.js for its own bake (with --material's override); any other reader — a
// bake dropped on the page, the three.js module — takes them from the file: the kernels per
// band in the transfer's `response` (written since format 5's three.js module,
// docs/formats-bake.md) and kd, ks from its `settings.material`.
import { bands as kBands } from 'prt:constants';
import { shNormalization } from './sh.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/** A short description of a material of the file ({ type, exponent | roughness, ks, kd }). */
function describeMaterial(m) {
  const p = m.type === 'phong' ? `exponent=${m.exponent}` : m.type === 'ggx' ? `roughness=${m.roughness}` : '';
  const ks = m.type === 'lambert' ? '' : `ks=${m.ks.join(',')}`;
  const kd = m.kd ? `kd=${m.kd.join(',')}` : '';
  const q = [p, ks, kd].filter((x) => x).join('&');
  return q ? `${m.type}?${q}` : m.type;
}

const isColour = (c) => Array.isArray(c) && c.length === 3 && c.every((x) => Number.isFinite(x) && x >= 0 && x <= 1);

/**
 * The shading of matrix transfer t from the file: { material, diffuse, lobe (Float32Array of
 * bands.maxShaderGlossy² kernels × N_lm), kd (array or null), ks }. Throws one line naming the
 * file when the transfer carries no response (a file written before it) or a malformed one.
 */
export function glossyFromFile(t, name) {
  const what = `the ${t.mode} glossy transfer`;
  const r = t.response, m = t.recipeMaterial;
  if (!r || !Array.isArray(r.diffuse) || !Array.isArray(r.lobe))
    fail(name, `${what} carries no material kernels ("response", written by prtkit since its three.js module): write the file again with this prtkit (prt compress)`);
  const shown = Math.min(t.bands, kBands.maxShaderGlossy);
  for (const [key, arr] of [['diffuse', r.diffuse], ['lobe', r.lobe]])
    if (arr.length < shown || !arr.every(Number.isFinite))
      fail(name, `${what}'s response.${key} holds ${arr.length} numbers, ${shown} finite ones expected`);
  if (!m || typeof m !== 'object' || !['lambert', 'phong', 'ggx'].includes(m.type))
    fail(name, `${what} has no material (settings.material.type lambert, phong or ggx)`);
  if (m.type !== 'lambert' && !isColour(m.ks)) fail(name, `${what}'s settings.material.ks is not three numbers in 0..1`);
  if (m.kd !== undefined && !isColour(m.kd)) fail(name, `${what}'s settings.material.kd is not three numbers in 0..1`);
  const n = kBands.maxShaderGlossy * kBands.maxShaderGlossy;
  const diffuse = new Float32Array(n), lobe = new Float32Array(n);
  for (let l = 0; l < shown; ++l)
    for (let mm = -l; mm <= l; ++mm) {
      const i = l * (l + 1) + mm, k = shNormalization(l, mm);
      diffuse[i] = r.diffuse[l] * k;
      lobe[i] = r.lobe[l] * k;
    }
  return { material: describeMaterial(m), diffuse, lobe, kd: m.kd || null,
           ks: m.type === 'lambert' ? [0, 0, 0] : m.ks };
}
