// The interactive page (docs/web.md, "Controls"): orbit controls, the light drag, the panel,
// the keys and dropped files, as prt view has them; and the loop with the status line.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import GUI from 'lil-gui';

import { toneMaps } from 'prt:constants';
import { parseBake } from './bake.js';
import { environment } from './environment.js';
import { parseLightJson, parseLightTxt } from './lights.js';
import { axisAngle, mul3 } from './sh.js';
import { describeTransfer } from './draw.js';
import { encodingNames } from './irradiance_encoding.js';
import { ballDrag, describeProbes, probeControls } from './probe_ui.js';
import { describeHaar } from './haar_scene.js';
import { pointerDrag } from './pointer_drag.js';

const kBackgrounds = ['env', 'sh', 'none'];
// The light drag, as prt view's (apps/viewer/scene.hpp, kDragDegreesPerPixel).
const kDragRadiansPerPixel = 0.25 * Math.PI / 180;

/** Starts the interactive page on `page` (main.js); returns { onDrop } for the drop test. */
export function startInteractive(page) {
  const { renderer, state, envs, query } = page;
  const camera = page.frame.camera;
  const hud = document.getElementById('prt-hud');
  const controls = new OrbitControls(camera, renderer.domElement);
  page.controls = controls;
  controls.mouseButtons = { LEFT: THREE.MOUSE.ROTATE, MIDDLE: THREE.MOUSE.DOLLY, RIGHT: null };
  controls.enableDamping = false;
  const resize = () => {
    const w = page.fixedSize ? page.fixedW : window.innerWidth, h = page.fixedSize ? page.fixedH : window.innerHeight;
    renderer.setSize(w, h);
  };
  resize();
  window.addEventListener('resize', resize);
  const reframe = () => page.frameCamera(renderer.domElement.width, renderer.domElement.height);
  reframe();

  // Light drag: right button, or shift + left; horizontal about world +Y, vertical about the
  // camera's right axis.
  const canvas = renderer.domElement;
  pointerDrag(canvas, (e) => e.button === 2 || (e.button === 0 && e.shiftKey), (dx, dy) => {
    const k = kDragRadiansPerPixel;
    const forward = new THREE.Vector3().subVectors(controls.target, camera.position).normalize();
    const right = new THREE.Vector3().crossVectors(forward, camera.up).normalize();
    const turn = mul3(axisAngle([0, 1, 0], dx * k), axisAngle(right.toArray(), dy * k));
    page.lightRotation = mul3(turn, page.lightRotation);
  });
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  // A probe bake's ball: Alt + left drag (probe_ui.js).
  ballDrag(page, canvas, camera, () => ballFolder && ballFolder.sync());

  // Panel.
  const gui = new GUI({ title: 'prtkit', container: document.getElementById('prt-panel') });
  const envNames = () => Object.fromEntries(envs.map((e, i) => [e.name, i]));
  const envCtl = gui.add(state, 'env', envNames()).name('environment');
  let transferCtl = null, bandsCtl = null, encodingCtl = null, ballFolder = null;
  function rebuildBakeControls() {
    if (transferCtl) transferCtl.destroy();
    if (bandsCtl) bandsCtl.destroy();
    if (encodingCtl) encodingCtl.destroy();
    if (ballFolder) ballFolder.destroy();
    ballFolder = page.bake().probes ? probeControls(gui, page) : null;
    if (page.bake().haar) {
      // A Haar bake: the transfer shown and the light's wavelet terms (no bands, no encoding).
      const t = page.bake().transfers[0], most = Math.min(6 * t.haar.resolution ** 2, 5000);
      transferCtl = gui.add(state, 'transfer', page.bake().transfers.map((x) => x.key)).name('transfer')
        .onChange(() => { state.mode = page.transfer().mode; });
      state.terms = Math.min(state.terms, most);
      bandsCtl = gui.add(state, 'terms', 1, most, 1).name('light terms');
      encodingCtl = null;
      return;
    }
    // The transfers in the library's preference order, each named with its layout.
    transferCtl = gui.add(state, 'transfer', page.bake().transfers.map((t) => t.key)).name('transfer').onChange(() => {
      state.mode = page.transfer().mode;
      state.bands = Math.min(state.bands, page.transfer().bands);
      bandsCtl.max(page.transfer().bands).updateDisplay();
    });
    bandsCtl = gui.add(state, 'bands', 1, page.transfer().bands, 1).name('bands');
    // Per-vertex matrices: the irradiance encoding they are drawn through (encoded_diffuse.js),
    // as prt render --encoding; 'none' is PRT's own radiance.
    encodingCtl = page.bake().transfers.some((t) => t.matrix && !t.perPixel)
      ? gui.add(state, 'encoding', ['none', ...encodingNames]).name('encoding') : null;
  }
  rebuildBakeControls();
  gui.add(state, 'background', kBackgrounds).name('background');
  gui.add(state, 'exposure', -8, 8, 0.1).name('exposure (stops)');
  gui.add(state, 'tonemap', Object.keys(toneMaps)).name('tone map');
  const actions = {
    'auto-rotate': false, 'speed (°/s)': 30,
    'reset light': () => { page.lightRotation = page.initialRotation; state.spin = 0; },
    'reset camera': reframe,
  };
  gui.add(actions, 'auto-rotate');
  gui.add(actions, 'speed (°/s)', 0, 180, 1);
  gui.add(actions, 'reset light');
  gui.add(actions, 'reset camera');

  // Keys, as prt view: [ ] one band fewer / more, B background, Tab next environment, space
  // auto-rotate.
  window.addEventListener('keydown', (e) => {
    if (e.target && /INPUT|SELECT|TEXTAREA/.test(e.target.tagName)) return;
    if (e.key === '[') state.bands = Math.max(1, state.bands - 1);
    else if (e.key === ']') state.bands = Math.min(Math.max(page.transfer().bands, 1), state.bands + 1);
    else if (e.key === 'b' || e.key === 'B') state.background = kBackgrounds[(kBackgrounds.indexOf(state.background) + 1) % kBackgrounds.length];
    else if (e.key === 'Tab') state.env = (state.env + 1) % envs.length;
    else if (e.key === ' ') actions['auto-rotate'] = !actions['auto-rotate'];
    else return;
    e.preventDefault();
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
  });

  // Drag and drop: a .glb replaces the bake, an SH light (.json, light.txt) is added and shown
  // (with fewer bands than the bake: padded, with the library's warning). A bad file leaves
  // everything as it was and says why. Returns the warnings.
  async function loadFile(file) {
    const name = file.name, ext = name.toLowerCase().split('.').pop();
    if (ext === 'glb') {
      const warnings = page.setBake(await parseBake(await file.arrayBuffer(), name, page.limits));
      rebuildBakeControls();
      reframe();
      return warnings;
    }
    if (ext === 'json' || ext === 'txt') {
      const text = await file.text();
      const l = ext === 'json' ? parseLightJson(text, name) : parseLightTxt(text, name);
      const warnings = page.addEnvironment(environment(name, l, null));
      state.env = envs.length - 1;
      envCtl.options(envNames()).setValue(state.env);
      return warnings;
    }
    throw new Error(`${name}: not a bake (.glb) or an SH light (.json, or the course's light.txt)`);
    // (An SH light dropped on a Haar bake's page is refused by page.addEnvironment: its light
    // is turned from an environment's cube, which only prt web writes.)
  }
  async function onDrop(e) {
    e.preventDefault();
    document.getElementById('prt-drop').style.display = 'none';
    const files = e.dataTransfer ? [...e.dataTransfer.files] : [];
    for (const f of files) {
      try {
        const warnings = await loadFile(f);
        page.showMessage(warnings.join('\n'), 'warning');
      } catch (err) {
        page.showMessage(err.message);
      }
    }
  }
  window.addEventListener('dragover', (e) => { e.preventDefault(); document.getElementById('prt-drop').style.display = 'block'; });
  window.addEventListener('dragleave', () => { document.getElementById('prt-drop').style.display = 'none'; });
  window.addEventListener('drop', (e) => { onDrop(e); });

  // Loop, with the frame time on screen: the interval between two frames' timestamps, smoothed.
  // The first frame has no interval (a rAF timestamp may even precede the setup's clock), so
  // nothing is shown until the second.
  let last = null, smooth = 0;
  function loop(now) {
    const dt = last === null ? 0 : Math.max(0, now - last);
    if (last !== null) smooth = smooth ? 0.9 * smooth + 0.1 * dt : dt;
    last = now;
    if (actions['auto-rotate']) state.spin += (actions['speed (°/s)'] * Math.PI / 180) * (dt / 1000);
    controls.update();
    page.draw(canvas.width, canvas.height, null);
    const b = page.bake(), t = page.transfer();
    hud.textContent = `${b.name}  ${b.triangles} triangles, ${b.vertices} vertices\n` +
      (b.haar ? `${t.mode} ${t.layout}, ${t.channels === 3 ? 'RGB' : 'scalar'}\n`
              : `${t.mode} ${t.layout}, ${Math.min(state.bands, t.bands)} of ${t.bands} bands, ${t.channels === 3 ? 'RGB' : 'scalar'}\n`) +
      (b.probes ? describeProbes(b, t, state) : b.haar ? describeHaar(t, page.gpu.haar)
                : describeTransfer(t, state.encoding)).map((l) => l + '\n').join('') +
      (smooth > 0 ? `frame ${smooth.toFixed(1)} ms (${(1000 / smooth).toFixed(0)} fps)` : 'frame time: measuring') +
      `\n${page.rendererName}`;
    if (!query.has('test')) requestAnimationFrame(loop);
  }
  requestAnimationFrame(loop);
  return { onDrop };
}
