// prtkit's browser viewer (docs/web.md): relights a bake under SH environments with WebGL2.
// Data come from prt-data.js (window.PRT_DATA, written by `prt web`); the page is one classic
// script so that it runs from file://. The parts, by concept:
//   bake.js, transfer.js, compressed.js   reading a bake: one reader, one dispatch by path
//   parts.js, probe_bake.js               a bake's mesh parts; a probe grid's bake (format 7)
//   probe_lighting.js, probe_relighter.js a probe grid relit on the CPU, as the library does
//   probe_scene.js, probe_ui.js,          a probe bake on screen: its scene and a ball lit
//   radiance_mesh.js                      through the grid, the ball's controls
//   lights.js, environment.js, sh.js      lights, their band rule, backgrounds, SH rotation
//   irradiance_encoding.js,               engines' irradiance encodings, and a matrix transfer
//   encoded_diffuse.js                    drawn through one (the encoding option)
//   draw.js, frame.js, camera.js          the GPU side of a transfer, one frame, the camera
//   ui.js, hooks.js                       the interactive page, the test hooks (tests/web)
//   'prt:constants', 'prt:shaders/…'      generated from the C++ and shaders/ (web/build.mjs)
// This file starts the page and owns what is on screen: the bake, its GPU objects, the
// environments and the view state.
import * as THREE from 'three';

import { bands as kBands, defaultToneMap, haar as kHaar, image as kImage } from 'prt:constants';
import { parseBake } from './bake.js';
import { rotationEulerXYZ } from './sh.js';
import { base64Bytes, environment, fitEnvironment } from './environment.js';
import { pickTransfer } from './transfer.js';
import { encodingRefusal } from './encoded_diffuse.js';
import { disposeTransfers, uploadTransfers } from './draw.js';
import { ballDefaults, disposeProbeScene, uploadProbeScene } from './probe_scene.js';
import { disposeHaarScene, haarCubeOf, uploadHaarScene } from './haar_scene.js';
import { pageHost } from './page_host.js';
import { glossyFromFile } from './glossy.js';
import { applyView, frameView } from './camera.js';
import { createFrame } from './frame.js';
import { startInteractive } from './ui.js';
import { benchHook, dropTest, report, screenshotHook } from './hooks.js';

const query = new URLSearchParams(location.search);
const messageBox = document.getElementById('prt-message');

/** Shows a line on the page: an error (red), a warning (amber) or a fatal one in the middle. */
function showMessage(text, kind = 'error') {
  messageBox.textContent = text;
  messageBox.className = kind === 'error' ? '' : kind;
  if (text) console.warn('prt web: ' + text);
}

function fatal(text) {
  showMessage(text, 'fatal');
  if (query.has('screenshot') || query.has('bench') || query.has('test')) report({ ok: false, error: text });
}

/** The GPU side of a parsed bake (draw.js, the page's host) and per part a mesh wearing the
 *  first transfer's material. Touches no scene. */
function uploadBake(b, limits) {
  if (b.probes) return uploadProbeScene(b);
  if (b.haar) return uploadHaarScene(b, limits);
  const gpu = uploadTransfers(b, limits, pageHost);
  gpu.meshes = b.parts.map((p, i) => {
    const mesh = new THREE.Mesh(p.geometry, gpu.parts[i].materials[b.transfers[0].key]);
    mesh.frustumCulled = false;
    return mesh;
  });
  return gpu;
}

function disposeBake(gpu, scene) {
  if (!gpu) return;
  for (const m of gpu.meshes) {
    scene.remove(m);
    m.geometry.dispose();
  }
  if (gpu.probes) disposeProbeScene(gpu);
  else if (gpu.haar) disposeHaarScene(gpu);
  else disposeTransfers(gpu);
}

/**
 * A file beside the page (data.bake.file and its texel points' file, written there by prt web
 * for bakes too large to carry inside prt-data.js). Browsers fetch files only over http(s):
 * opened from disk, the page says how to serve it.
 */
async function fetchBeside(bake, entry) {
  const megabytes = (bake.bytes / 1e6).toFixed(0);
  let response;
  try {
    response = await fetch(entry.file);
  } catch (e) {
    throw new Error(`${bake.name}: this bake (${megabytes} MB) is beside the page as ${entry.file}, ` +
                    'which a browser loads only when the folder is served over http: run ' +
                    '`python3 -m http.server -d FOLDER` and open http://localhost:8000/ ' +
                    '(or write the page with prt web --embed always to open it from disk)');
  }
  if (!response.ok) throw new Error(`${bake.name}: ${entry.file} could not be loaded (HTTP ${response.status})`);
  const buffer = await response.arrayBuffer();
  if (buffer.byteLength !== entry.bytes)
    throw new Error(`${bake.name}: ${entry.file} has ${buffer.byteLength} bytes, prt-data.js says ${entry.bytes}`);
  return buffer;
}

/** What prt web writes beside its bake for the page (bake.js, readBake's extras): per-texel
 *  glossy matrices' points (data.bake.texelPoints), inside prt-data.js or beside it. */
async function bakeExtras(bake) {
  const p = bake.texelPoints;
  if (!p) return {};
  const bytes = p.base64 ? base64Bytes(p.base64).buffer : await fetchBeside(bake, p);
  if (bytes.byteLength % 4) throw new Error(`${bake.name}: its texel points are ${bytes.byteLength} bytes, not whole floats`);
  return { texelPoints: new Float32Array(bytes) };
}

async function main() {
  const data = window.PRT_DATA;
  if (!data || !data.bake || !Array.isArray(data.environments))
    return fatal('prt-data.js is missing or incomplete: write this folder with `prt web BAKE -o DIR`.');
  const probe = document.createElement('canvas');
  if (!probe.getContext('webgl2'))
    return fatal('This page needs WebGL2, which this browser does not provide (or has disabled). ' +
                 'Try a current Firefox, Chrome, Edge or Safari, with hardware acceleration on.');

  const fixedSize = query.has('screenshot') || query.has('bench') || query.has('test');
  const [fixedW, fixedH] = (query.get('size') || '640x480').split('x').map(Number);
  const renderer = new THREE.WebGLRenderer({ antialias: false, alpha: false, powerPreference: 'high-performance' });
  renderer.setPixelRatio(fixedSize ? 1 : window.devicePixelRatio);
  renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.setClearColor(0x000000, 1);
  document.body.appendChild(renderer.domElement);
  const gl = renderer.getContext();
  // The frame is drawn in linear HDR into a half-float target, then tone mapped.
  if (!gl.getExtension('EXT_color_buffer_float') && !gl.getExtension('EXT_color_buffer_half_float'))
    return fatal('This page needs to render into floating-point images (WebGL2 extension ' +
                 'EXT_color_buffer_float), which this browser or GPU does not offer.');
  const limits = {
    maxTextureSize: gl.getParameter(gl.MAX_TEXTURE_SIZE),
    // uL[pad4(B²)] plus a few other uniforms must fit the vertex shader's uniform vectors.
    maxBands: Math.min(kBands.maxPackedLight, Math.floor(Math.sqrt(gl.getParameter(gl.MAX_VERTEX_UNIFORM_VECTORS) - 16))),
    // Per-texel transfer is relit per pixel: uL[] in the fragment shader's uniform vectors.
    maxFragmentBands: Math.min(kBands.maxPackedLight, Math.floor(Math.sqrt(gl.getParameter(gl.MAX_FRAGMENT_UNIFORM_VECTORS) - 16))),
  };
  const debugInfo = gl.getExtension('WEBGL_debug_renderer_info');
  const rendererName = debugInfo ? gl.getParameter(debugInfo.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);

  // ---- state ------------------------------------------------------------------------------
  const view = data.view || {};
  // The library's exposure limit (image::kMaxExposureStops, from the generated constants): a
  // ?exposure= beyond it is clamped to it, one that is not a number is 0.
  const exposureWithin = (stops) =>
    Number.isFinite(stops)
      ? Math.min(Math.max(stops, -kImage.maxExposureStops), kImage.maxExposureStops)
      : 0;
  const num = (key, fallback) => (query.has(key) ? Number(query.get(key)) : fallback);
  const state = {
    env: num('env', 0),
    mode: query.get('mode') || view.mode || '',  // the mode asked for (pickTransfer's)
    transfer: '',                                 // the key of the transfer shown
    bands: num('bands', view.bands || 0),
    exposure: exposureWithin(num('exposure', view.exposure || 0)),
    tonemap: query.get('tonemap') || view.tonemap || defaultToneMap,
    background: query.get('background') || 'env',
    spin: 0,
    // The irradiance encoding a matrix transfer is drawn through ('none': PRT's own radiance;
    // encoded_diffuse.js), as prt render --encoding.
    encoding: query.get('encoding') || view.encoding || 'none',
    // A probe bake (probe_scene.js): the ball's centre (?at=x,y,z, else the grid's centre) and
    // whether the probes show as points (?probes).
    at: query.has('at') ? query.get('at').split(',').map(Number) : null,
    probes: query.has('probes'),
    // A Haar bake (haar_scene.js): the light's wavelet terms (?terms=, prt web --terms).
    terms: num('terms', view.terms || kHaar.defaultLightTerms),
  };
  const euler = (query.get('rotate') || (view.rotate || [0, 0, 0]).join(',')).split(',').map(Number);
  const page = {
    data, query, renderer, gl, limits, rendererName, state, fixedSize, fixedW, fixedH,
    initialRotation: rotationEulerXYZ(euler[0] || 0, euler[1] || 0, euler[2] || 0),
    envs: data.environments.map((e) => environment(e.name, { bands: e.bands, coeffs: Float32Array.from(e.coefficients.flat()) }, e.background, e.haar || null)),
    frame: createFrame(renderer),
    gpu: null,       // uploadBake's result for the bake on screen
    controls: null,  // OrbitControls once interactive
    showMessage,
  };
  page.lightRotation = page.initialRotation;
  if (!(state.env >= 0 && state.env < page.envs.length)) state.env = 0;

  page.bake = () => page.gpu.bake;
  page.transfer = () => page.gpu.bake.transfers.find((t) => t.key === state.transfer);
  page.frameView = () => ({ gpu: page.gpu, transfer: page.transfer(), env: page.envs[state.env], state,
                            lightRotation: page.lightRotation });
  page.draw = (w, h, target) => page.frame.draw(page.frameView(), w, h, target);
  page.read = (w, h) => page.frame.read(page.frameView(), w, h);

  /** The camera prt web was given (--camera), else the library's framing (render::meshFraming,
   *  written by prt web; a dropped bake with its own sphere, bake.js) fitted to w × h. */
  page.frameCamera = (w, h) => {
    const b = page.bake(), written = data.bake.name === b.name;
    const given = view.camera;
    if (given && written) return applyView(page.frame.camera, page.controls, given);
    const f = view.framing;
    const sphere = written ? { centre: f.centre, radius: f.radius } : { centre: b.centre.toArray(), radius: b.radius };
    applyView(page.frame.camera, page.controls, frameView({ ...f, ...sphere }, w, h));
  };

  /** Adds an environment fitted to the bake; returns its warnings. */
  page.addEnvironment = (e) => {
    if (page.bake().haar) haarCubeOf(e, page.bake().transfers[0].haar.resolution);  // refused: SH only
    const warnings = fitEnvironment(e, Math.max(page.bake().maxBands, 1));
    page.envs.push(e);
    return warnings;
  };

  /** Puts a parsed bake on screen; throws (leaving the old one) if it cannot be shown. Returns
   *  the warnings (lights with fewer bands than the bake: the library's rule, lights.js). */
  page.setBake = (b) => {
    // Compressed glossy matrices shade with the bake's material: as prt web prepared it (with
    // --material's override) for the page's own bake, else from the file (glossy.js).
    for (const t of b.transfers)
      if (t.matrix) t.material = (b.name === data.bake.name && data.glossy && data.glossy[t.mode]) || glossyFromFile(t, b.name);
    // An encoding asked for (?encoding=, prt web --encoding, the panel) refuses a bake whose
    // transfer cannot take it, in one line naming the file, as prt render --encoding does.
    const refusal = b.haar ? null : encodingRefusal(b, pickTransfer(b.transfers, state.mode), state.encoding);
    if (refusal) throw new Error(refusal);
    // A Haar bake is relit from the environments' cubes, at its own resolution.
    if (b.haar) for (const e of page.envs) haarCubeOf(e, b.transfers[0].haar.resolution);
    const gpu = uploadBake(b, limits);
    disposeBake(page.gpu, page.frame.scene);
    page.gpu = gpu;
    for (const m of gpu.meshes) page.frame.scene.add(m);
    const warnings = [];
    for (const e of page.envs) warnings.push(...fitEnvironment(e, Math.max(b.maxBands, 1)));
    if (b.probes && !(state.at && state.at.length === 3 && state.at.every(Number.isFinite) && b.name === data.bake.name))
      state.at = ballDefaults(b.grid).centre;
    state.transfer = pickTransfer(b.transfers, state.mode).key;
    const maxB = Math.max(page.transfer().bands, 1);  // (a Haar transfer has none: its background's SH has 1)
    if (!(state.bands >= 1 && state.bands <= maxB)) state.bands = maxB;
    if (!(Number.isInteger(state.terms) && state.terms >= 1)) state.terms = kHaar.defaultLightTerms;
    return warnings;
  };

  // ---- the bake: inside prt-data.js (small bakes), or beside it (prt web --embed) -----------
  let warnings;
  try {
    const bytes = data.bake.glb ? base64Bytes(data.bake.glb).buffer : await fetchBeside(data.bake, data.bake);
    warnings = page.setBake(await parseBake(bytes, data.bake.name, limits, await bakeExtras(data.bake)));
  } catch (e) {
    return fatal(e.message);
  }
  if (warnings.length) showMessage(warnings.join('\n'), 'warning');

  if (query.has('screenshot')) return screenshotHook(page);
  if (query.has('bench')) return benchHook(page);
  const ui = startInteractive(page);
  if (query.get('test') === 'drop') await dropTest(page, ui.onDrop, messageBox);
}

main().catch((e) => fatal(`prt web: ${e && e.message ? e.message : e}`));
