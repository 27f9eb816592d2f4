// prt export --format probe-grid --engine threejs drawn by three.js's own LightProbeGridWebGL
// (r187; tests/web/test_probes_web.cpp, ThreeLightProbeGridDrawsTheExport). Each grid of
// window.PRT_PROBE_GRID — the JSON's `lightProbeGrid` as written, or the .glb read by three's
// GLTFLoader (the extension's members, the atlas an accessor) — becomes the grid an app makes:
// a LightProbeGridWebGL(width, height, depth, nx, ny, nz) at `position`, its texture the atlas
// as an RGBA float Data3DTexture, linearly filtered. White MeshLambertMaterial spheres lit by
// the grid alone are rendered, one grid at a time, into a float target (linear, no tone
// mapping), then the same spheres' world positions and normals; every float comes back as
// base64 in <pre id="prt-test">, for the test to shade each pixel with the library.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { LightProbeGridWebGL } from 'three/addons/lighting/LightProbeGridWebGL.js';

function report(result) {
  const pre = document.createElement('pre');
  pre.id = 'prt-test';
  pre.textContent = JSON.stringify(result);
  document.body.appendChild(pre);
}

function base64(floats) {
  const bytes = new Uint8Array(floats.buffer, floats.byteOffset, floats.byteLength);
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000)
    s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

function floatsFromBase64(text) {
  const s = atob(text);
  const bytes = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) bytes[i] = s.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}

/// { lightProbeGrid, atlas: Float32Array } of one entry of `grids`.
async function readGrid(entry) {
  if (entry.json) {
    const g = entry.json.lightProbeGrid;
    return { lightProbeGrid: g, atlas: floatsFromBase64(g.atlas.data) };
  }
  const s = atob(entry.glb);
  const bytes = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) bytes[i] = s.charCodeAt(i);
  const gltf = await new GLTFLoader().parseAsync(bytes.buffer, '');
  const ext = gltf.userData.gltfExtensions.PRTKIT_probe_grid;
  const g = ext.lightProbeGrid;
  const accessor = await gltf.parser.getDependency('accessor', g.atlas.accessor);
  return { lightProbeGrid: g, atlas: accessor.array };
}

/// The grid as an app builds it from the export.
function makeGrid({ lightProbeGrid: g, atlas }) {
  const [nx, ny, nz] = g.resolution;
  const grid = new LightProbeGridWebGL(g.width, g.height, g.depth, nx, ny, nz);
  grid.position.fromArray(g.position);
  const [w, h, d] = g.atlas.size;
  if (atlas.length !== w * h * d * 4) throw new Error(`atlas: ${atlas.length} floats for ${w}x${h}x${d} RGBA`);
  const texture = new THREE.Data3DTexture(atlas, w, h, d);
  texture.format = THREE.RGBAFormat;
  texture.type = THREE.FloatType;
  texture.minFilter = texture.magFilter = THREE.LinearFilter;
  texture.unpackAlignment = 1;
  texture.needsUpdate = true;
  grid.texture = texture;
  grid.updateBoundingBox();
  return grid;
}

/// World position or normal per pixel (alpha 1 where a sphere is), as three's shading of the
/// grid takes them (its probeWorldPos and probeWorldNormal).
function geometryMaterial(what) {
  return new THREE.ShaderMaterial({
    vertexShader: `
      varying vec3 vWorld;
      void main() {
        vWorld = ${what === 'position' ? '(modelMatrix * vec4(position, 1.0)).xyz' : 'mat3(modelMatrix) * normal'};
        gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
      }`,
    fragmentShader: `
      varying vec3 vWorld;
      void main() { gl_FragColor = vec4(${what === 'position' ? 'vWorld' : 'normalize(vWorld)'}, 1.0); }`,
  });
}

async function main() {
  const input = window.PRT_PROBE_GRID;
  if (!input) throw new Error('grid-data.js is missing (window.PRT_PROBE_GRID)');
  const { width, height } = input;
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  document.body.appendChild(canvas);
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false });
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
  renderer.setClearColor(0x000000, 0);
  const target = new THREE.WebGLRenderTarget(width, height, { type: THREE.FloatType });

  const c = input.camera;
  const camera = new THREE.PerspectiveCamera(c.fov, width / height, 0.05, 50);
  camera.position.fromArray(c.eye);
  camera.up.fromArray(c.up);
  camera.lookAt(new THREE.Vector3().fromArray(c.target));
  const scene = new THREE.Scene();
  const ball = new THREE.SphereGeometry(input.radius, 96, 48);
  const white = new THREE.MeshLambertMaterial({ color: 0xffffff });
  for (const at of input.spheres) {
    const mesh = new THREE.Mesh(ball, white);
    mesh.position.fromArray(at);
    scene.add(mesh);
  }
  const read = () => {
    renderer.setRenderTarget(target);
    renderer.clear();
    renderer.render(scene, camera);
    const pixels = new Float32Array(width * height * 4);
    renderer.readRenderTargetPixels(target, 0, 0, width, height, pixels);
    renderer.setRenderTarget(null);
    return pixels;
  };

  const frames = {};
  for (const entry of input.grids) {
    const grid = makeGrid(await readGrid(entry));
    scene.add(grid);
    frames[entry.name] = base64(read());
    scene.remove(grid);
    grid.texture.dispose();
  }
  scene.overrideMaterial = geometryMaterial('position');
  const position = base64(read());
  scene.overrideMaterial = geometryMaterial('normal');
  const normal = base64(read());
  const gl = renderer.getContext();
  report({ ok: true, three: THREE.REVISION, width, height, frames, position, normal,
           floatLinear: gl.getExtension('OES_texture_float_linear') !== null });
}

main().catch((e) => report({ ok: false, error: String(e && e.stack || e) }));
