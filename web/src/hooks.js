// The page's test hooks (tests/web, docs/web.md): ?screenshot renders one frame at a fixed size
// and writes its pixels into <pre id="prt-test">; ?bench=N times N frames; ?test=drop drops
// files through the real drop handler.
import * as THREE from 'three';

import { base64Bytes, bytesBase64 } from './environment.js';
import { shownEncoding } from './encoded_diffuse.js';

/** Writes a test hook's result where `chromium --dump-dom` reads it. */
export function report(result) {
  const pre = document.createElement('pre');
  pre.id = 'prt-test';
  pre.textContent = JSON.stringify(result);
  document.body.appendChild(pre);
}

/** ?screenshot&size=WxH: one frame of the default view, its displayed RGB bytes. */
export function screenshotHook(page) {
  const { fixedW: w, fixedH: h } = page;
  page.renderer.setSize(w, h);
  page.frameCamera(w, h);
  const rgb = page.read(w, h);
  const t = page.transfer(), c = t.compressed;
  if (page.bake().probes) return report({ ok: true, width: w, height: h, renderer: page.rendererName, mode: t.mode,
                                          layout: t.layout, probes: probeReport(page, w, h), rgb: bytesBase64(rgb) });
  if (page.bake().haar) {
    // The light the page made (its terms, as haar::turnedLight makes them) and the frame.
    const l = page.gpu.haar.light;
    return report({ ok: true, width: w, height: h, renderer: page.rendererName, mode: t.mode, layout: t.layout,
                    haar: { resolution: t.haar.resolution, terms: t.haar.terms, lightTerms: l.index.length,
                            energyKept: l.energyKept, index: Array.from(l.index), value: Array.from(l.value),
                            unshadowed: Array.from(l.unshadowed), bright: l.bright },
                    rgb: bytesBase64(rgb) });
  }
  report({ ok: true, width: w, height: h, renderer: page.rendererName, mode: t.mode, layout: t.layout,
           path: t.path, compressed: c ? `${c.clusters}x${c.basisCount}, ${16 * c.texelsPerVertex} bytes per ${t.perPixel ? 'texel' : 'vertex'}` : 'no',
           perPixel: !!t.perPixel, encoding: shownEncoding(t, page.state.encoding) || 'none', rgb: bytesBase64(rgb) });
}

/** A probe bake's frame: the grid, the ball (centre, radius, and where it lies in the frame,
 *  pixels from the top left) and the relit incident SH at its centre (our basis, b² RGB), which
 *  tests/web/test_probes_web.cpp holds to the library's. */
function probeReport(page, w, h) {
  const g = page.gpu.probes, at = page.state.at, camera = page.frame.camera;
  const centre = new THREE.Vector3().fromArray(at), ndc = centre.clone().project(camera);
  const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
  const rim = centre.clone().addScaledVector(right, g.ball.radius).project(camera);
  const incident = g.relighter.incidentAt(at[0], at[1], at[2]);
  return { grid: page.bake().grid, at, radius: g.ball.radius, bands: g.relighter.lighting.bands,
           pixel: [(ndc.x + 1) / 2 * w, (1 - ndc.y) / 2 * h], pixelRadius: Math.abs(rim.x - ndc.x) / 2 * w,
           incident: Array.from(incident) };
}

/** ?bench=N: N frames drawn back to back into the canvas, each waited for with a 1-pixel
 *  readPixels; the median. &nomesh: the same frame without the mesh (the baseline). */
export function benchHook(page) {
  const { fixedW: w, fixedH: h, gl, state } = page;
  const n = Math.max(1, Number(page.query.get('bench')) || 20);
  if (page.query.has('nomesh')) for (const m of page.gpu.meshes) m.visible = false;
  page.renderer.setSize(w, h);
  page.frameCamera(w, h);
  const one = new Uint8Array(4), times = [];
  const canvasFrame = () => {
    page.draw(w, h, null);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, one);  // waits for the GPU
  };
  canvasFrame();  // compiles shaders, uploads textures
  for (let i = 0; i < n; ++i) {
    const t0 = performance.now();
    canvasFrame();
    times.push(performance.now() - t0);
  }
  times.sort((a, b) => a - b);
  const b = page.bake();
  report({ ok: true, frames: n, medianMs: times[n >> 1], minMs: times[0], bands: state.bands,
           mode: page.transfer().mode, compressed: !!page.transfer().compressed, vertices: b.vertices,
           triangles: b.triangles, width: w, height: h, renderer: page.rendererName });
}

/**
 * ?test=drop: drops bad files through the real drop handler and checks that the scene (the bake,
 * the environments, the frame's pixels) is unchanged and that the page says why; then a light
 * with fewer bands than the bake (added, padded, with the library's warning) and good light
 * files and a good bake as controls.
 *
 * The files are handed to the handler in memory, with the two methods of a File it uses
 * (arrayBuffer, text) already resolved: real File objects are read as Blobs, which Chromium's
 * virtual time (--virtual-time-budget, the tests' clock) does not wait for, so on a busy machine
 * the page could be dumped before a drop finished (the test then saw no report at all).
 */
export async function dropTest(page, handleDrop, messageBox) {
  const snapshot = () => ({ bake: page.bake(), envCount: page.envs.length });
  const drop = async (name, bytes) => {
    const file = {
      name,
      arrayBuffer: async () => bytes.slice().buffer,
      text: async () => new TextDecoder().decode(bytes),
    };
    await handleDrop({ preventDefault() {}, dataTransfer: { files: [file] } });
    return { message: messageBox.textContent, kind: messageBox.className };
  };
  const w = 64, h = 48;
  const frame0 = bytesBase64(page.read(w, h)), s0 = snapshot();
  const enc = new TextEncoder();
  // A GLB holding only the JSON chunk `doc`.
  const glbWith = (doc) => {
    const j = enc.encode(JSON.stringify(doc)), p = (4 - (j.length % 4)) % 4;
    const b = new Uint8Array(20 + j.length + p), v = new DataView(b.buffer);
    v.setUint32(0, 0x46546c67, true), v.setUint32(4, 2, true), v.setUint32(8, b.length, true);
    v.setUint32(12, j.length + p, true), v.setUint32(16, 0x4e4f534a, true);
    b.set(j, 20);
    b.fill(0x20, 20 + j.length);
    return b;
  };
  const plain = glbWith({ asset: { version: '2.0' } });  // valid glTF, no prtkit bake
  const cases = [
    ['garbage.glb', enc.encode('this is not a glb file at all, just text')],
    ['truncated.glb', plain.slice(0, plain.length - 4)],
    ['plain.glb', plain],
    ['newer.glb', glbWith({ asset: { version: '2.0' }, extensionsUsed: ['PRTKIT_radiance_transfer'], extensions: { PRTKIT_radiance_transfer: { formatVersion: 99 } } })],
    ['broken.json', enc.encode('{"bands": 3, "coefficients": [')],
    ['rows.json', enc.encode(JSON.stringify({ bands: 2, coefficients: [[1, 1, 1], [0, 0, 0], [0, 0, 0]] }))],
    ['picture.png', enc.encode('PNG')],
    ['odd.txt', enc.encode('1 1 1\n0 0 0\n')],
  ];
  const results = [];
  for (const [name, bytes] of cases) {
    const { message, kind } = await drop(name, bytes);
    const s = snapshot();
    results.push({ name, message, kind, sameBake: s.bake === s0.bake, sameEnvs: s.envCount === s0.envCount,
                   sameFrame: bytesBase64(page.read(w, h)) === frame0 });
  }
  // A light with fewer bands than the bake: added and shown, padded with zeros, with the
  // library's warning (io::loadLighting); its frame is the 1-band light's (only L_00 is lit).
  const B = s0.bake.maxBands;
  const constant = (bands, v) => ({ bands, coefficients: Array.from({ length: bands * bands }, (_, i) => (i ? [0, 0, 0] : [v, v, v])) });
  const shortDrop = await drop('short.json', enc.encode(JSON.stringify(constant(2, 1))));
  const shortFrame = bytesBase64(page.read(w, h));
  const short = { ...shortDrop, added: snapshot().envCount === s0.envCount + 1, changed: shortFrame !== frame0 };
  // Control: a good light with the bake's bands is added (so the handler does run) and draws
  // the same frame as the short one (the same light, padded).
  const good = await drop('good.json', enc.encode(JSON.stringify(constant(B, 1))));
  short.sameAsPadded = bytesBase64(page.read(w, h)) === shortFrame;
  // ... and so is the course's light.txt.
  const txt = Array.from({ length: B * B }, (_, i) => (i ? '0 0 0' : '0.5 0.5 0.5')).join('\n');
  const txtDrop = await drop('light.txt', enc.encode(txt));
  const added = snapshot().envCount === s0.envCount + 3 && txtDrop.message === '';
  // Control: a good bake (the page's own, again) replaces the scene.
  const glbDrop = await drop('again.glb', base64Bytes(window.PRT_DATA.bake.glb));
  const replaced = snapshot().bake !== s0.bake && snapshot().bake.vertices === s0.bake.vertices;
  report({ ok: true, cases: results, short, control: { message: good.message, added },
           controlBake: { message: glbDrop.message, replaced } });
}
