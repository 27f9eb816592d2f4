// node verdicts.mjs PRT GENDIR WORKDIR FILE...: one corpus of bakes through the library's reader
// and the browser's. Each file is answered by `prt web` (io::decodeBake and the page's GPU
// paths: what the page must also accept) and, under node, by the page's reader (web/src/bake.js
// parseBake) and by prtkit-three's GLTFLoader plugin (web/three/src/plugin.js), from their
// sources. Required: the three verdicts agree for every file; a file named accept_* / reject_*
// gets that verdict from prt (so a mutation that no longer breaks its file fails here); every
// JS refusal is an Error of one line starting with the file's name. Prints one line per
// disagreement and a summary; exits 1 on any failure.
import fs from 'node:fs';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { register } from 'node:module';

const [prtCli, gen, work, ...files] = process.argv.slice(2);
if (!files.length) {
  console.error('usage: node verdicts.mjs PRT GENDIR WORKDIR FILE...');
  process.exit(2);
}
register('./hooks.mjs', import.meta.url, { data: { gen: path.resolve(gen) } });
const web = new URL('../../../web/', import.meta.url);
const { GLTFLoader } = await import(new URL('node_modules/three/examples/jsm/loaders/GLTFLoader.js', web));
const { parseBake } = await import(new URL('src/bake.js', web));
const { PRTKitRadianceTransfer } = await import(new URL('three/src/plugin.js', web));
const { bands } = await import(new URL('constants.js', `file://${path.resolve(gen)}/`));

// The library's own limits stand in for a GPU's (prt web holds a bake to them: relight::shaderPath).
const limits = { maxTextureSize: 16384, maxBands: bands.maxPackedLight, maxFragmentBands: bands.maxPackedLight };

/** Per-texel glossy matrices are shaded at points prt web computes and hands the page: zeros of
 *  the lightmap's size stand in for them (their values are not what is checked here). */
function texelPoints(bytes) {
  try {
    const b = Buffer.from(bytes), n = b.readUInt32LE(12);
    const j = JSON.parse(b.subarray(20, 20 + n).toString('utf8'));
    const lm = ((j.extensions || {}).PRTKIT_radiance_transfer || {}).lightmap;
    if (lm && Number.isInteger(lm.width * lm.height) && lm.width * lm.height <= 1 << 20)
      return new Float32Array(lm.width * lm.height * 12);
  } catch { /* not a bake the points matter for */ }
  return undefined;
}

/** prt's answer: `prt web` (the page's counterpart: decodeBake, then the page's paths) and
 *  `prt info` (decodeBake alone, what the accept_/reject_ names speak of). */
function prtVerdict(file) {
  const run = (args) => {
    const r = spawnSync(prtCli, ['-q', ...args], { encoding: 'utf8' });
    return { ok: r.status === 0, message: (r.stderr || '').trim().split('\n').pop() };
  };
  return { web: run(['web', file, '-o', path.join(work, 'page'), '--background-width', '8', '--exposure', '0']),
           info: run(['info', file]) };
}

/** Accepted, or refused with the error; a read that never settles (within 20 s) is a refusal
 *  whose "error" is not an Error, which the message check then reports. */
async function jsVerdict(read) {
  let timer;
  const never = new Promise((resolve) => { timer = setTimeout(() => resolve('never settled'), 20000); });
  try {
    const r = await Promise.race([read().then(() => 'ok'), never]);
    return r === 'ok' ? { ok: true } : { ok: false, error: 'the read never settled' };
  } catch (e) {
    return { ok: false, error: e };
  } finally {
    clearTimeout(timer);
  }
}

/** Whether a transfer of the file is a glossy matrix without the material kernels ("response")
 *  prtkit-three shades it with: files from before the module (accept_v3-cpca-matrix) — prt web
 *  writes the kernels into the page's data, the plugin refuses them (naming the file). */
function glossyWithoutKernels(bytes) {
  try {
    const b = Buffer.from(bytes), n = b.readUInt32LE(12);
    const j = JSON.parse(b.subarray(20, 20 + n).toString('utf8'));
    const o = (j.extensions || {}).PRTKIT_radiance_transfer || (j.extras || {}).prtkit || {};
    // (A probe grid's matrices are relit, not shaded with a material: they need no kernels.)
    return (o.transfers || []).some((t) => t.settings && t.settings.layout === 'matrix' && t.settings.domain !== 'probes' && !t.response);
  } catch {
    return false;
  }
}

// three.js's own console chatter on broken geometry (NaN bounds) is not what is checked here.
console.warn = console.error = () => {};

// prtkit-three answers for GLTFLoader's scene errors once it checks the document before them.
const strictPlugin = typeof PRTKitRadianceTransfer.prototype.beforeRoot === 'function';
const leftToLoader = [];
let failures = 0, disagreedPage = 0, disagreedPlugin = 0, unnamed = 0;
const fail = (line) => { console.log(`FAIL ${line}`); ++failures; };
for (const file of files) {
  const name = path.basename(file);
  const bytes = (() => { const b = fs.readFileSync(file); return b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength); })();
  const points = texelPoints(bytes);
  const { web: cpp, info } = prtVerdict(file);
  const meant = name.startsWith('accept') ? true : name.startsWith('reject') ? false : null;
  if (meant !== null && meant !== info.ok)
    fail(`${name}: prt info ${info.ok ? 'accepts' : 'refuses'} it, the corpus means it to be ${meant ? 'accepted' : 'refused'} (${info.message})`);
  if (!info.ok && cpp.ok) fail(`${name}: prt web accepts what prt info refuses (${info.message})`);
  const page = await jsVerdict(() => parseBake(bytes.slice(0), name, limits, { texelPoints: points }));
  // Where the plugin stood when a load failed: GLTFLoader parses the container and the JSON
  // before it makes the plugin, and builds the scene (every mesh accessor) before the plugin's
  // afterRoot; a probe registered first records the latter.
  const stage = { made: false, afterRoot: false };
  const plugin = await jsVerdict(() => new GLTFLoader()
    .register(() => ({ name: 'probe', afterRoot: () => { stage.afterRoot = true; } }))
    .register((parser) => { stage.made = true; return new PRTKitRadianceTransfer(parser, { name, texelPoints: points, required: true }); })
    .parseAsync(bytes.slice(0), ''));
  // The plugin's expected answer: prt web's, except that it refuses glossy matrices without
  // their kernels (glossyWithoutKernels).
  const pluginShould = cpp.ok && !glossyWithoutKernels(bytes);
  // GLTFLoader's part, which the plugin cannot answer for: the container (prt refuses its GLB
  // chunks: GLTFLoader reads a BIN chunk that runs past the file's end as the bytes present), and
  // errors thrown before the plugin's afterRoot (the container, the JSON, the scene's accessors)
  // unless the plugin checks the document in a beforeRoot of its own — then they are its own.
  const container = /: (truncated|not a glTF binary|glTF binary container|first chunk|second chunk)/.test(cpp.message) && !cpp.ok;
  const beforePlugin = !plugin.ok && (!stage.made || (!stage.afterRoot && !strictPlugin));
  if (container || beforePlugin) {
    leftToLoader.push(name);
    plugin.ok = pluginShould;
    plugin.error = undefined;
  }
  for (const [who, v, should] of [['the page (bake.js)', page, cpp.ok], ['prtkit-three (plugin.js)', plugin, pluginShould]]) {
    if (v.ok === should && v.error === undefined && !v.ok) continue;  // GLTFLoader's (above)
    const said = v.ok ? 'accepts it' : `refuses it: ${String(v.error && v.error.message || v.error).split('\n')[0].slice(0, 200)}`;
    if (v.ok !== should) {
      fail(`${name}: prt ${cpp.ok ? 'accepts it' : `refuses it (${cpp.message})`}; ${who} ${said}`);
      if (who.startsWith('the page')) ++disagreedPage; else ++disagreedPlugin;
    }
    if (!v.ok) {
      const m = v.error instanceof Error ? v.error.message : null;
      if (m === null || m.includes('\n') || !m.startsWith(`${name}: `)) {
        fail(`${name}: ${who} refuses it with ${m === null ? `no Error (${String(v.error)})` : 'a message'} not one line starting with the file's name: ${JSON.stringify(String(m).slice(0, 200))}`);
        ++unnamed;
      }
    }
  }
}
if (leftToLoader.length)
  console.log(`prtkit-three: ${leftToLoader.length} files answered by GLTFLoader before the plugin's afterRoot (not checked for the file's name${strictPlugin ? '' : '; plugin.js has no beforeRoot'}): ${leftToLoader.join(' ')}`);
console.log(`${files.length} files: the page disagrees with prt on ${disagreedPage}, prtkit-three on ${disagreedPlugin}; ${unnamed} JS refusals do not name the file`);
process.exit(failures ? 1 : 0);
