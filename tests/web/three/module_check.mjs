// The built prtkit-three package as an app uses it, under node (no browser, no GL): imported by
// name ('prtkit-three', resolved through its package.json) beside the app's own three.js and
// GLTFLoader, against files prt wrote (run.sh). Checks what can be checked without drawing:
// the plugin dresses every part, the light conversions agree with `prt light --format threejs`
// and `--rotate` (the library), the environment stays in the world as the bake's scene turns,
// and bad values are refused. Exits non-zero on the first failure.
import fs from 'node:fs';
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { HaarLighting, PRTKitRadianceTransfer, ProbeGridLighting, lightFromSphericalHarmonics3, lightProbeGridAtlas,
         lightToSphericalHarmonics3, parseHaarLight, parseLight, rotateLight } from 'prtkit-three';

let failures = 0;
function check(ok, what) {
  if (!ok) {
    console.error(`FAIL: ${what}`);
    ++failures;
  }
}
const maxDiff = (a, b) => a.reduce((m, x, i) => Math.max(m, Math.abs(x - b[i])), 0);
const bytes = (f) => { const b = fs.readFileSync(f); return b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength); };

const loader = () => new GLTFLoader().register((parser) => new PRTKitRadianceTransfer(parser, { name: 'cornell.glb' }));
const gltf = await loader().parseAsync(bytes('cornell.glb'), '');
const prt = gltf.userData.prtkit;
check(prt !== undefined, 'the plugin leaves a PRTBake in gltf.userData.prtkit');
const parts = [];
gltf.scene.traverse((o) => { if (o.isMesh) parts.push(o); });
check(prt.meshes.length === parts.length && parts.length > 1, `every part is dressed (${prt.meshes.length} of ${parts.length})`);
check(parts.every((m) => m.material.isShaderMaterial && m.material.name === 'PRTKIT_radiance_transfer'),
      'the parts wear prtkit ShaderMaterials');
check(prt.mode === 'interreflected' && prt.bands === 3, `the richest transfer is shown first (${prt.mode}, ${prt.bands})`);
check(JSON.stringify(prt.transfers.map((t) => t.mode)) === '["interreflected","shadowed"]', 'transfers in the library\'s order');
prt.mode = 'shadowed';
check(prt.mode === 'shadowed' && parts.every((m) => m.material === prt.meshes[parts.indexOf(m)].material), 'mode switches materials');
check(parts[0].geometry.getAttribute('_prt_shadowed_t0') === undefined, 'transfer attributes moved into textures');

// Lights: prt's file, three.js's SphericalHarmonics3 both ways, against prt light --format threejs.
const sky = parseLight(fs.readFileSync('sky.json', 'utf8'), 'sky.json');
check(sky.bands === 3 && sky.coeffs.length === 27, 'parseLight reads prt light\'s JSON');
const three = JSON.parse(fs.readFileSync('sky-three.json', 'utf8')).object.sh;
const sh3 = lightToSphericalHarmonics3(sky);
check(maxDiff(sh3.toArray(), three) < 1e-5 * Math.max(...three.map(Math.abs)),
      `lightToSphericalHarmonics3 is prt light --format threejs (max diff ${maxDiff(sh3.toArray(), three)})`);
check(maxDiff(lightFromSphericalHarmonics3(sh3).coeffs, sky.coeffs) < 1e-6, 'lightFromSphericalHarmonics3 inverts it');
// parseLight takes the file prt light --format threejs writes (text and parsed), as our light.
const fromThree = parseLight(fs.readFileSync('sky-three.json', 'utf8'), 'sky-three.json');
check(fromThree.bands === 3 && maxDiff(fromThree.coeffs, sky.coeffs) < 1e-6 * Math.max(...sky.coeffs.map(Math.abs)),
      `parseLight reads prt light --format threejs as the same light (max diff ${maxDiff(fromThree.coeffs, sky.coeffs)})`);
const probeJson = JSON.parse(fs.readFileSync('sky-three.json', 'utf8'));
probeJson.object.intensity = 2;
check(maxDiff(parseLight(probeJson, 'p').coeffs, sky.coeffs.map((v) => 2 * v)) < 2e-6 * Math.max(...sky.coeffs.map(Math.abs)),
      'parseLight applies the LightProbe\'s intensity');
// Euler(X, Y, Z, 'ZYX') in radians is prt's --rotate X,Y,Z.
const d = Math.PI / 180;
const turned = rotateLight(sky, new THREE.Euler(30 * d, -50 * d, 20 * d, 'ZYX'));
const prtTurned = parseLight(fs.readFileSync('sky-turned.json', 'utf8'));
check(maxDiff(turned.coeffs, prtTurned.coeffs) < 1e-4 * Math.max(...sky.coeffs.map(Math.abs)),
      `rotateLight(Euler 'ZYX') is prt light --rotate (max diff ${maxDiff(turned.coeffs, prtTurned.coeffs)})`);

// The frame's light, as the materials read it (uL: (r, g, b, 0) per coefficient).
const camera = new THREE.PerspectiveCamera();
camera.position.set(0, 1, 4);
camera.updateMatrixWorld();
const frameLight = () => {
  parts[0].updateMatrixWorld(true);
  parts[0].onBeforeRender(null, null, camera);
  const L = parts[0].material.uniforms.uL.value, out = [];
  for (let i = 0; i < 9; ++i) out.push(L[4 * i], L[4 * i + 1], L[4 * i + 2]);
  return out;
};
check(prt.setLight(sky).length === 0, 'a light with the bake\'s bands: no warning');
check(maxDiff(frameLight(), Array.from(sky.coeffs)) < 1e-6, 'unturned, the frame\'s light is the light');
prt.lightRotation.setFromEuler(new THREE.Euler(30 * d, -50 * d, 20 * d, 'ZYX'));
check(maxDiff(frameLight(), Array.from(prtTurned.coeffs)) < 1e-4 * 8, 'lightRotation turns the frame\'s light as prt --rotate');
// Turning the bake's scene by the same rotation leaves the light unturned in its frame.
gltf.scene.quaternion.copy(prt.lightRotation);
gltf.scene.updateMatrixWorld(true);
check(maxDiff(frameLight(), Array.from(sky.coeffs)) < 1e-4 * 8, 'the environment stays in the world as the scene turns');
prt.lightRotation.identity();
gltf.scene.quaternion.identity();
// The library's band rule: fewer bands are used as they are, with a warning; more are cut.
const w = prt.setLight(parseLight(fs.readFileSync('sky2.json', 'utf8'), 'sky2.json'));
check(w.length === 1 && /2 bands but the transfer 3/.test(w[0]), `a 2-band light warns: ${w}`);
const f2 = frameLight();
check(f2.slice(12).every((x) => x === 0) && maxDiff(f2.slice(0, 12), Array.from(sky.coeffs.slice(0, 12))) < 1e-6,
      'a 2-band light is zero past 4 coefficients');
prt.exposure = -2;
check(parts.every((m) => Math.abs(m.material.uniforms.uExposureScale.value - 0.25) < 1e-12) && prt.exposure === -2,
      'exposure is one uniform shared by the materials');

// Refusals: one line naming the file, or the value.
const throws = (f, re, what) => {
  try {
    f();
  } catch (e) {
    check(re.test(e.message), `${what}: "${e.message}"`);
    return;
  }
  check(false, `${what}: did not throw`);
};
throws(() => { prt.bands = 0; }, /bands must be a positive integer/, 'bands 0');
throws(() => { prt.exposure = NaN; }, /exposure must be a finite number/, 'exposure NaN');
throws(() => prt.setLight({ bands: 2, coeffs: new Float32Array(3) }), /a light is/, 'a short light');
throws(() => parseLight('{"bands": 2, "coefficients": [[1,1,1]]}', 'bad.json'), /^bad\.json: has 1 coefficients/, 'a bad light file');
throws(() => parseLight('{"metadata": {}, "object": {"type": "Mesh"}}', 'mesh.json'), /^mesh\.json: is a three\.js "Mesh", not a LightProbe/, 'a three.js object that is no LightProbe');
throws(() => parseLight('{"object": {"type": "LightProbe", "sh": [1, 2]}}', 'short.json'), /^short\.json: the LightProbe's "sh" is not 27/, 'a short LightProbe');
// The extension's object renamed (a byte in the JSON chunk): a glTF that only says it uses it.
const foreign = new Uint8Array(bytes('cornell.glb'));
const at = Buffer.from(foreign).indexOf('"PRTKIT_radiance_transfer":{');
check(at > 0, 'the bake holds the extension\'s object');
foreign[at + 1] = 'X'.charCodeAt(0);
const plain = await loader().parseAsync(foreign.buffer, '');
check(plain.userData.prtkit === undefined, 'a glTF that is not a bake loads untouched');
let rejected = '';
await new GLTFLoader().register((parser) => new PRTKitRadianceTransfer(parser, { name: 'plain.glb', required: true }))
  .parseAsync(foreign.buffer, '').catch((e) => { rejected = e.message; });
check(/^plain\.glb: is a glTF file but not a prtkit bake/.test(rejected), `required: refused by name ("${rejected}")`);
// A Haar bake (prt bake --basis haar) gives a HaarLighting, relit on the CPU under a Haar light
// file (parseHaarLight; prt light --basis haar). Its numbers against prt render:
// tests/web/test_haar_web.cpp; here the package's surface.
const haarGltf = await new GLTFLoader().register((parser) => new PRTKitRadianceTransfer(parser, { name: 'haar.glb', required: true }))
  .parseAsync(bytes('haar.glb'), '');
const hl = haarGltf.userData.prtkit;
check(hl instanceof HaarLighting && hl.isHaarLighting, 'a Haar bake gives a HaarLighting');
check(hl.transfers.length === 1 && hl.transfers[0].basis === 'haar' && hl.transfers[0].resolution === 4 && hl.mode === 'shadowed' &&
      hl.transfers[0].bounceBands === 0 && hl.transfers[0].channels === 1,
      `its transfer (${JSON.stringify(hl.transfers)})`);
throws(() => hl.update(), /^haar\.glb: no light yet/, 'a Haar relight before setLight');
const haarSky = parseHaarLight(fs.readFileSync('haar-sky.json', 'utf8'), 'haar-sky.json');
check(haarSky.fullSh.length === 75 && haarSky.fullSh.every(Number.isFinite), 'a Haar light file carries its full SH (for an inter-reflected bounce)');
throws(() => hl.setLight(parseHaarLight(fs.readFileSync('haar-sky8.json', 'utf8'), 'haar-sky8.json')),
       /^haar\.glb: the Haar light is over a 8² cube, the bake's transfer over 4²/, 'a Haar light over another cube');
throws(() => hl.setLight(sky), /^haar\.glb: a Haar bake is relit by haarEnvironment/, 'an SH light for a Haar bake');
throws(() => { hl.terms = 0; }, /terms must be a positive integer/, 'Haar terms 0');
hl.setLight(haarSky);
check(hl.update() === true && hl.update() === false, 'update relights once per change');
const radiance = (g) => { const out = []; g.scene.traverse((o) => { if (o.isMesh) out.push(...o.geometry.getAttribute('radiance').array); }); return out; };
const lit = radiance(haarGltf);
check(lit.every(Number.isFinite) && lit.some((x) => x > 0), 'the Haar bake is lit, finitely');
// Linear in the light: twice the light, twice the radiance.
const doubled = { ...haarSky, value: haarSky.value.map((v) => 2 * v), unshadowed: haarSky.unshadowed.map((v) => 2 * v),
                 bright: haarSky.bright.map((b) => ({ texel: b.texel, radiance: b.radiance.map((v) => 2 * v) })),
                 fullSh: haarSky.fullSh.map((v) => 2 * v) };
hl.setLight(doubled);
hl.update();
check(maxDiff(radiance(haarGltf), lit.map((v) => 2 * v)) < 1e-5 * Math.max(...lit), 'Haar relighting is linear in the light');
hl.lightRotation.setFromEuler(new THREE.Euler(0, 0.5, 0));
throws(() => hl.update(), /cannot be turned/, 'a turned Haar light file');
hl.dispose();

prt.dispose();

// A probe bake (prt probes): a ProbeGridLighting, its LightProbe, its exported grid. (Its numbers
// against the library: tests/web/test_probes_web.cpp.)
const probeGltf = await new GLTFLoader().register((parser) => new PRTKitRadianceTransfer(parser, { name: 'probes.glb' }))
  .parseAsync(bytes('probes.glb'), '');
const grid = probeGltf.userData.prtkit;
check(grid instanceof ProbeGridLighting && grid.isProbeGridLighting, 'a probe bake gives a ProbeGridLighting');
check(JSON.stringify(grid.grid.count) === '[3,2,2]' && grid.bands === 3, `its grid and bands (${JSON.stringify(grid.grid)})`);
throws(() => grid.incidentAt(new THREE.Vector3()), /^probes\.glb: no light yet/, 'a query before setLight');
grid.setLight(sky);
const lp = grid.updateLightProbe(new THREE.LightProbe(), new THREE.Vector3(0.1, 0.9, 0.2));
const here = grid.incidentAt(new THREE.Vector3(0.1, 0.9, 0.2));
check(maxDiff(lp.sh.toArray(), lightToSphericalHarmonics3(here).toArray()) === 0, 'updateLightProbe holds incidentAt in three.js\'s basis');
check(here.coeffs.some((x) => x !== 0), 'the light arrives');
// The light stays in the world: turning the light and the bake's scene alike turns the light
// arriving at a probe by the same rotation.
const probe0 = new THREE.Vector3(...grid.irradianceVolume().positions.slice(0, 3));
const still = grid.incidentAt(probe0);
const turn = new THREE.Quaternion().setFromEuler(new THREE.Euler(0.3, -0.7, 0.4));
grid.lightRotation.copy(turn);
probeGltf.scene.quaternion.copy(turn);
probeGltf.scene.updateMatrixWorld(true);
const turnedAt = grid.incidentAt(probe0.clone().applyQuaternion(turn));
check(maxDiff(turnedAt.coeffs, rotateLight({ bands: 3, coeffs: Float32Array.from(still.coeffs) }, turn).coeffs) < 1e-4,
      'turning the light and the scene together turns the light arriving at a probe with them');
grid.lightRotation.identity();
probeGltf.scene.quaternion.identity();
probeGltf.scene.updateMatrixWorld(true);
const v = grid.irradianceVolume('sky.json');
check(v.asset.format === 'prtkit probe grid' && v.engine === 'threejs' && v.light === 'sky.json' && v.source === 'probes.glb',
      'the exported grid is prt export --format probe-grid\'s (three.js)');
check(v.positions.length === 36 && v.probes.length === 324 && v.coefficients.count === 9, 'the exported grid: 12 positions, 27 floats each');
const sh1 = new THREE.SphericalHarmonics3().fromArray(v.probes, 27);
const p1 = new THREE.Vector3().fromArray(v.positions, 3);
check(maxDiff(sh1.toArray(), lp.sh.toArray()) > 0 && maxDiff(sh1.toArray(), grid.updateLightProbe(new THREE.LightProbe(), p1).sh.toArray()) < 1e-6,
      'probe 1 of the export is the LightProbe at its position');
const g = v.lightProbeGrid, size = [g.width, g.height, g.depth];
// three.js r187's getProbePosition: position − size/2 + (i + ½)·size/resolution (cell centres).
check(maxDiff(g.resolution, [3, 2, 2]) === 0 &&
      maxDiff(g.position.map((c, a) => c - size[a] / 2 + 0.5 * size[a] / g.resolution[a]), v.positions.slice(0, 3)) < 1e-6,
      'LightProbeGrid\'s first cell centre is probe 0');
const atlas = lightProbeGridAtlas(grid.grid, v.probes);
const written = new Float32Array(Uint8Array.from(atlas.length ? Buffer.from(g.atlas.data, 'base64') : []).buffer);
check(atlas.length === 4 * 3 * 2 * 7 * 4 && maxDiff(written, atlas) === 0 && maxDiff(g.atlas.size, [3, 2, 28]) === 0,
      'the atlas: 7 sub-volumes of nz + 2 slices, as written in the export');
check(grid.meshes.length > 1 && grid.meshes.every((m) => m.material.isShaderMaterial && m.geometry.getAttribute('radiance')),
      'the bake\'s meshes are drawn lit through the grid');
grid.meshes[0].onBeforeRender();
check(grid.meshes[0].geometry.getAttribute('radiance').array.some((x) => x > 0), 'their radiance is filled before they draw');
grid.dispose();
if (failures) process.exit(1);
console.log('prtkit-three under node: all checks passed');
