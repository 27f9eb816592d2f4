// The three.js example (docs/three.md): a prtkit bake loaded with three.js's own GLTFLoader and
// the prtkit-three plugin, in an ordinary scene — a ground plane, a torus knot and a sphere in
// MeshStandardMaterial lit by a LightProbe holding the same SH light (its first three bands,
// turned by the same rotation), orbit controls, tone mapping by the renderer. A probe bake
// (prt probes) shows its scene lit through the grid and a ball moving through it, lit by a
// LightProbe the grid sets at the ball every frame.
//
// ?bake=URL&light=URL (default bake.glb, light.json beside the page, served over http), or
// example-data.js beside the page. Test hook (tests/web/test_three_web.cpp):
// ?screenshot&size=WxH&camera=eye;target;up;fov&rotate=X,Y,Z&exposure=S&mode=M&bands=B&encoding=E[&only]
// draws one frame with no tone mapping (prt render --tonemap clamp) and writes its RGB bytes
// into <pre id="prt-test">; &only hides everything but the bake (on black).
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import GUI from 'lil-gui';
import { PRTKitRadianceTransfer, PRTBake, haarEnvironment, lightToSphericalHarmonics3, parseLight, rotateLight } from 'prtkit-three';

const encodingNames = PRTBake.encodings;

const query = new URLSearchParams(location.search);
const page = window.PRT_DATA;  // a prt web folder's, when this is its three/ folder
const test = query.has('screenshot');

function report(result) {
  const pre = document.createElement('pre');
  pre.id = 'prt-test';
  pre.textContent = JSON.stringify(result);
  document.body.appendChild(pre);
}
function fail(text) {
  document.getElementById('message').textContent = text;
  if (test) report({ ok: false, error: text });
}

function base64Bytes(s) {
  const bin = atob(s), out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; ++i) out[i] = bin.charCodeAt(i);
  return out;
}

async function fetchOr(url, what) {
  const r = await fetch(url).catch(() => {
    throw new Error(`${url}: the ${what} could not be fetched (serve this folder over http: python3 -m http.server)`);
  });
  if (!r.ok) throw new Error(`${url}: the ${what} could not be fetched (HTTP ${r.status})`);
  return r;
}

/** The bake's bytes and name and the lights [{ name, light }]: example-data.js, else a prt web
 *  folder's ../prt-data.js, else ?bake= and ?light= fetched. */
async function inputs() {
  const ex = window.PRT_EXAMPLE, page = window.PRT_DATA;
  if (ex) return { name: ex.name || 'bake.glb', bytes: base64Bytes(ex.glb).buffer, lights: [{ name: 'light', light: parseLight(ex.light, 'light') }] };
  if (page && page.bake && Array.isArray(page.environments)) {
    const b = page.bake;
    const bytes = b.glb ? base64Bytes(b.glb).buffer : await (await fetchOr(`../${b.file}`, 'bake')).arrayBuffer();
    // Per-texel glossy matrices' points, which prt web writes beside its bake (the plugin's option).
    const p = b.texelPoints;
    const texelPoints = !p ? undefined : new Float32Array(p.base64 ? base64Bytes(p.base64).buffer
                                                                   : await (await fetchOr(`../${p.file}`, 'texel points')).arrayBuffer());
    // A Haar bake's page carries each environment's cube too (its HaarLighting turns the light).
    return { name: b.name, bytes, texelPoints, lights: page.environments.map((e) => ({ name: e.name, light: parseLight({ bands: e.bands, coefficients: e.coefficients }, e.name),
                                                                                    haar: e.haar ? haarEnvironment(e.haar, e.name) : null })) };
  }
  const bake = query.get('bake') || 'bake.glb', lightName = query.get('light') || 'light.json';
  const bytes = await (await fetchOr(bake, 'bake')).arrayBuffer();
  return { name: bake, bytes, lights: [{ name: lightName, light: parseLight(await (await fetchOr(lightName, 'light')).text(), lightName) }] };
}

async function main() {
  const [w, h] = test ? (query.get('size') || '320x240').split('x').map(Number) : [innerWidth, innerHeight];
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(test ? 1 : devicePixelRatio);
  renderer.setSize(w, h);
  renderer.toneMapping = test ? THREE.NoToneMapping : THREE.ACESFilmicToneMapping;
  document.body.appendChild(renderer.domElement);

  // The bake, through three.js's own loader, and the lights.
  const { name: bakeName, bytes, texelPoints, lights } = await inputs();
  const loader = new GLTFLoader().register((parser) => new PRTKitRadianceTransfer(parser, { renderer, name: bakeName, required: true, texelPoints }));
  const gltf = await loader.parseAsync(bytes, '');
  const prt = gltf.userData.prtkit;
  let light = lights[0].light;

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(test ? 0x000000 : 0x30343a);
  scene.add(gltf.scene);

  // The standard side: lit by the same light (three bands) through a LightProbe.
  const box = new THREE.Box3().setFromObject(gltf.scene);
  const size = box.getSize(new THREE.Vector3()), centre = box.getCenter(new THREE.Vector3());
  const r = Math.max(size.x, size.y, size.z) / 2;
  const probe = new THREE.LightProbe();
  scene.add(probe);
  const standard = new THREE.Group();
  const knot = new THREE.Mesh(new THREE.TorusKnotGeometry(0.2 * r, 0.07 * r, 160, 20),
                              new THREE.MeshStandardMaterial({ color: 0xc08040, roughness: 0.6 }));
  knot.position.set(box.max.x + 0.45 * r, box.min.y + 0.32 * r, centre.z);
  const ball = new THREE.Mesh(new THREE.SphereGeometry(0.25 * r, 48, 24),
                              new THREE.MeshStandardMaterial({ color: 0x9aa6b2, roughness: 1 }));
  ball.position.set(box.min.x - 0.4 * r, box.min.y + 0.25 * r, centre.z);
  const floor = new THREE.Mesh(new THREE.CircleGeometry(4 * r, 64), new THREE.MeshStandardMaterial({ color: 0x808080, roughness: 1 }));
  floor.rotation.x = -Math.PI / 2;
  floor.position.set(centre.x, box.min.y - 0.02 * r, centre.z);
  standard.add(knot, ball, floor);
  scene.add(standard);
  standard.visible = !(test && query.has('only'));

  const camera = new THREE.PerspectiveCamera(40, w / h, 0.01 * r, 100 * r);
  const controls = test ? null : new OrbitControls(camera, renderer.domElement);
  if (query.has('camera')) {
    // 'eye=x,y,z;target=x,y,z;up=x,y,z;fov=deg', as prt render --camera.
    const v = Object.fromEntries(query.get('camera').split(';').map((kv) => kv.split('=')));
    const vec = (s, d) => (s ? s.split(',').map(Number) : d);
    camera.fov = Number(v.fov || 40);
    camera.up.fromArray(vec(v.up, [0, 1, 0]));
    camera.position.fromArray(vec(v.eye, [0, 0, 3]));
    camera.lookAt(...vec(v.target, [0, 0, 0]));
    if (controls) controls.target.fromArray(vec(v.target, [0, 0, 0]));
  } else {
    camera.position.set(centre.x + 0.3 * r, centre.y + 1.4 * r, centre.z + 3.4 * r);
    camera.lookAt(centre);
    if (controls) controls.target.copy(centre);
  }
  camera.updateProjectionMatrix();

  // Light rotation: prt render --rotate X,Y,Z is Euler(X, Y, Z, 'ZYX').
  const deg = (query.get('rotate') || '0,0,0').split(',').map((x) => (Number(x) || 0) * Math.PI / 180);
  const settings = { light: lights[0].name, exposure: Number(query.get('exposure') || (page && page.view && page.view.exposure) || 0), turnX: deg[0], turnY: deg[1], turnZ: deg[2],
                     mode: query.get('mode') || prt.mode, bands: Number(query.get('bands') || 0) || prt.bands, spin: false,
                     // A matrix transfer drawn through an irradiance encoding ('none': PRT's own).
                     encoding: query.get('encoding') || (page && page.view && page.view.encoding) || 'none' };
  // A probe bake (prt probes; prt.isProbeGridLighting): the ball moves through its grid, lit by
  // the LightProbe the grid sets at it each frame (updateLightProbe), matte (MeshLambertMaterial:
  // ρ E(n)/π, as the grid shades a normal); the knot and the floor step aside.
  const grid = prt.isProbeGridLighting ? prt.grid : null;
  if (grid) {
    knot.visible = floor.visible = false;
    // prt render's --object: a fifth of the grid's largest side (its cells') across.
    ball.geometry = new THREE.SphereGeometry(0.1 * Math.max(...grid.count.map((n, a) => n * grid.spacing[a])), 48, 24);
    ball.material = new THREE.MeshLambertMaterial({ color: new THREE.Color().setRGB(0.8, 0.8, 0.8, THREE.LinearSRGBColorSpace) });
  }
  const placeBall = (t) => {
    // A slow Lissajous path about the grid's centre, within its probes.
    ball.position.fromArray(grid.origin.map((o, a) => {
      const half = 0.5 * (grid.count[a] - 1) * grid.spacing[a];
      return o + half + 0.8 * half * Math.sin(0.3 * (a + 1) * t + a);
    }));
    prt.updateLightProbe(probe, ball.position);
  };
  // A Haar bake (prt.isHaarLighting): its light is the environment's cube, with no bands and no
  // encoding; the light's wavelet terms instead (?terms=).
  const haar = !!prt.isHaarLighting;
  if (haar) settings.terms = Number(query.get('terms') || (page && page.view && page.view.terms) || prt.terms);
  const apply = () => {
    const chosen = lights.find((l) => l.name === settings.light);
    light = chosen.light;
    if (haar && !chosen.haar) throw new Error(`${chosen.name}: a Haar bake is relit from an environment's cube (prt web writes one beside each environment of a Haar bake's page)`);
    const warnings = prt.setLight(haar ? chosen.haar : light);
    document.getElementById('message').textContent = warnings.join('\n');
    prt.exposure = settings.exposure;
    prt.mode = settings.mode;
    if (haar) prt.terms = settings.terms;
    else {
      prt.encoding = 'none';  // (the new transfer may not take the last one)
      prt.bands = settings.bands;
      prt.encoding = settings.encoding;
    }
    prt.lightRotation.setFromEuler(new THREE.Euler(settings.turnX, settings.turnY, settings.turnZ, 'ZYX'));
    if (grid) placeBall(0);
    else lightToSphericalHarmonics3(rotateLight(light, prt.lightRotation), probe.sh);
    probe.intensity = Math.pow(2, settings.exposure);
  };
  apply();

  if (test) {
    prt.update();  // (an encoded transfer's radiance, a vertex attribute, in this very frame)
    renderer.render(scene, camera);
    const gl = renderer.getContext(), rgba = new Uint8Array(w * h * 4), rgb = new Uint8Array(w * h * 3);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
    for (let y = 0; y < h; ++y)
      for (let x = 0; x < w; ++x)
        for (let c = 0; c < 3; ++c) rgb[(y * w + x) * 3 + c] = rgba[((h - 1 - y) * w + x) * 4 + c];
    let s = '';
    for (let i = 0; i < rgb.length; i += 0x8000) s += String.fromCharCode(...rgb.subarray(i, i + 0x8000));
    report({ ok: true, width: w, height: h, mode: prt.mode, bands: haar ? 0 : prt.bands, terms: haar ? prt.terms : 0,
             encoding: haar ? 'none' : prt.shownEncoding || prt.encoding, transfers: prt.transfers,
             meshes: prt.meshes.length, rgb: btoa(s) });
    return;
  }

  const gui = new GUI({ title: 'prtkit' });
  if (query.has('nogui')) gui.hide();  // (for pictures)
  if (lights.length > 1) gui.add(settings, 'light', lights.map((l) => l.name)).onChange(apply);
  gui.add(settings, 'exposure', -8, 8, 0.1).onChange(apply);
  gui.add(settings, 'turnY', -Math.PI, Math.PI, 0.01).name('light turn').onChange(apply);
  gui.add(settings, 'mode', prt.transfers.map((t) => t.mode)).onChange(apply);
  if (haar) gui.add(settings, 'terms', 1, 2000, 1).name('light terms').onChange(apply);
  else gui.add(settings, 'bands', 1, prt.bands, 1).onChange(apply);
  if (prt.transfers.some((t) => t.layout === 'matrix') && !grid)
    gui.add(settings, 'encoding', ['none', ...encodingNames]).onChange(apply);
  gui.add(settings, 'spin');
  addEventListener('resize', () => {
    renderer.setSize(innerWidth, innerHeight);
    camera.aspect = innerWidth / innerHeight;
    camera.updateProjectionMatrix();
  });
  const clock = new THREE.Clock(), start = performance.now();
  renderer.setAnimationLoop(() => {
    if (grid) placeBall((performance.now() - start) / 1000);
    if (settings.spin) {
      settings.turnY = ((settings.turnY + clock.getDelta() * 0.5 + Math.PI) % (2 * Math.PI)) - Math.PI;
      apply();
      gui.controllersRecursive().forEach((c) => c.updateDisplay());
    } else clock.getDelta();
    controls.update();
    renderer.render(scene, camera);
  });
}

main().catch((e) => fail(String(e && e.message ? e.message : e)));
