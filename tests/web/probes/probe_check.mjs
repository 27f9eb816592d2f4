// node probe_check.mjs GENDIR BAKE.glb LIGHT.json QUERY.json: a probe bake relit in JavaScript,
// through both readers, for tests/web/test_probes_web.cpp to hold to the library
// (relight::relightProbes, sampleProbes, shadeDiffuse). QUERY = { rotate: [X, Y, Z] degrees (prt
// render --rotate's), points: [[x, y, z]...], normals: [[x, y, z]...], albedo: [r, g, b] }.
// Prints one JSON object:
//   page:  the page's reader (web/src/bake.js parseBake) and relighter (probe_relighter.js,
//          the light turned by sh.js's rotationEulerXYZ rows): incident[point] (b² × 3, our
//          basis), shade[point][normal] ([r, g, b])
//   three: prtkit-three's plugin and ProbeGridLighting (the light turned by a THREE.Euler
//          'ZYX'): incident, shade (shadeAt), lightProbe[point] (updateLightProbe: 27 floats,
//          three.js's basis), volume (irradianceVolume(LIGHT's name): prt export --format
//          probe-grid's JSON), atlas (lightProbeGridAtlas of the volume's probes, base64 as the
//          volume writes it)
// The sources run as they are bundled: 'prt:' imports resolve into GENDIR (bake_verdicts/hooks.mjs).
import fs from 'node:fs';
import path from 'node:path';
import { register } from 'node:module';

const [gen, bakeFile, lightFile, queryFile] = process.argv.slice(2);
if (!queryFile) {
  console.error('usage: node probe_check.mjs GENDIR BAKE.glb LIGHT.json QUERY.json');
  process.exit(2);
}
register('../bake_verdicts/hooks.mjs', import.meta.url, { data: { gen: path.resolve(gen) } });
const web = new URL('../../../web/', import.meta.url);
const THREE = await import(new URL('node_modules/three/build/three.module.js', web));
const { GLTFLoader } = await import(new URL('node_modules/three/examples/jsm/loaders/GLTFLoader.js', web));
const { parseBake } = await import(new URL('src/bake.js', web));
const { ProbeRelighter } = await import(new URL('src/probe_relighter.js', web));
const { shadeDiffuse } = await import(new URL('src/probe_lighting.js', web));
const { rotationEulerXYZ } = await import(new URL('src/sh.js', web));
const { lightForTransfer } = await import(new URL('src/lights.js', web));
const three = await import(new URL('three/src/index.js', web));

const bytes = () => { const b = fs.readFileSync(bakeFile); return b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength); };
const name = path.basename(bakeFile);
const lightText = fs.readFileSync(lightFile, 'utf8');
const q = JSON.parse(fs.readFileSync(queryFile, 'utf8'));
const limits = { maxTextureSize: 16384, maxBands: 32, maxFragmentBands: 32 };

// The page: its reader, the relighter the page's probe mode holds, sh.js's rotation.
async function page() {
  const bake = await parseBake(bytes(), name, limits);
  if (!bake.probes) throw new Error(`${name}: the page did not read a probe grid`);
  const t = bake.transfers[0], light = three.parseLight(lightText, lightFile);
  const { coeffs } = lightForTransfer(lightFile, light, t.bands);
  const relighter = new ProbeRelighter(bake.grid);
  relighter.relight(t, t.bands, rotationEulerXYZ(...q.rotate), coeffs);
  const incident = q.points.map((p) => Array.from(relighter.incidentAt(p[0], p[1], p[2])));
  const b = relighter.lighting.bands;
  const shade = incident.map((sh) => q.normals.map((n) => shadeDiffuse(sh, b, n[0], n[1], n[2], q.albedo)));
  return { grid: bake.grid, bands: b, incident, shade };
}

// prtkit-three: the plugin, ProbeGridLighting, a THREE.Euler for prt render --rotate X,Y,Z.
async function module() {
  const gltf = await new GLTFLoader().register((parser) => new three.PRTKitRadianceTransfer(parser, { name, required: true }))
    .parseAsync(bytes(), '');
  const lighting = gltf.userData.prtkit;
  if (!lighting || !lighting.isProbeGridLighting) throw new Error(`${name}: the plugin left no ProbeGridLighting`);
  lighting.setLight(three.parseLight(lightText, lightFile));
  const d = Math.PI / 180;
  lighting.lightRotation.setFromEuler(new THREE.Euler(q.rotate[0] * d, q.rotate[1] * d, q.rotate[2] * d, 'ZYX'));
  const at = q.points.map((p) => new THREE.Vector3(...p));
  const incident = at.map((p) => Array.from(lighting.incidentAt(p).coeffs));
  const albedo = new THREE.Color(...q.albedo);
  const shade = at.map((p) => q.normals.map((n) => lighting.shadeAt(p, new THREE.Vector3(...n), albedo).toArray()));
  const lightProbe = at.map((p) => lighting.updateLightProbe(new THREE.LightProbe(), p).sh.toArray());
  const volume = lighting.irradianceVolume(path.basename(lightFile));
  const atlas = three.lightProbeGridAtlas(lighting.grid, volume.probes);
  return { incident, shade, lightProbe, volume, atlas: Buffer.from(atlas.buffer).toString('base64'),
           meshes: lighting.meshes.length, dressed: lighting.meshes.every((m) => m.material.isShaderMaterial) };
}

console.warn = () => {};
try {
  console.log(JSON.stringify({ page: await page(), three: await module() }));
} catch (e) {
  console.log(JSON.stringify({ error: String(e && e.message ? e.message : e) }));
  process.exit(1);
}
