// prtkit's browser viewer (docs/web.md): relights a bake under SH environments with WebGL2.
// Data come from prt-data.js (window.PRT_DATA, written by `prt web`); the page is one classic
// script so that it runs from file://. Per frame, as the desktop viewer (docs/viewer.md):
// the light's first b bands are rotated on the CPU (sh.js), packed as vec4 uL[i] = (r, g, b, 0),
// and the mesh's vertex shader sums T_i L'_i from a data texture (shaders/prt_relight.glsl);
// the background, the relit mesh, then exposure + tone map + sRGB (shaders/prt_display.glsl).
// CPCA-compressed transfer (bake version 3) is relit in the compressed space: per frame the
// rotated light is projected onto the K(N+1) cluster vectors here (compressed.js) and the vertex
// shader sums N weighted cluster values (shaders/prt_compressed.glsl).
//
// Test hooks (tests/web, docs/web.md): ?screenshot renders one frame at a fixed size and writes
// its pixels into <pre id="prt-test">; ?bench=N times N frames; ?test=drop drops bad files.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import GUI from 'lil-gui';

import { kMaxGlossyBands, parseBake, parseLightJson, parseLightTxt } from './bake.js';
import { axisAngle, evalSh, mul3, rotateLight, rotationEulerXYZ } from './sh.js';
import { clusterTableImage, projectClusters } from './compressed.js';
import meshVert from 'prt:shaders/mesh.vert';
import compressedVert from 'prt:shaders/compressed.vert';
import compressedGlossyVert from 'prt:shaders/compressedGlossy.vert';
import meshFrag from 'prt:shaders/mesh.frag';
import fullscreenVert from 'prt:shaders/fullscreen.vert';
import backgroundFrag from 'prt:shaders/background.frag';
import toneFrag from 'prt:shaders/tone.frag';

const kToneMaps = { clamp: 0, reinhard: 1, aces: 2 };
const query = new URLSearchParams(location.search);
const hud = document.getElementById('prt-hud');
const messageBox = document.getElementById('prt-message');

/** Shows an error line on the page (red), or a fatal one in the middle. */
function showMessage(text, fatal = false) {
  messageBox.textContent = text;
  messageBox.className = fatal ? 'fatal' : '';
  if (text) console.warn('prt web: ' + text);
}

/** Writes a test hook's result where `chromium --dump-dom` reads it. */
function report(result) {
  const pre = document.createElement('pre');
  pre.id = 'prt-test';
  pre.textContent = JSON.stringify(result);
  document.body.appendChild(pre);
}

function base64Bytes(b64) {
  const s = atob(b64);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
  return out;
}

function bytesBase64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

/** Radiance RGBE bytes (prt web's backgrounds) to float RGB: (m + 0.5) · 2^(e − 136). */
function decodeRgbe(bytes) {
  const n = bytes.length / 4, rgb = new Float32Array(n * 3);
  for (let p = 0; p < n; ++p) {
    const e = bytes[4 * p + 3];
    if (e === 0) continue;
    const f = Math.pow(2, e - 136);
    rgb[3 * p] = (bytes[4 * p] + 0.5) * f;
    rgb[3 * p + 1] = (bytes[4 * p + 1] + 0.5) * f;
    rgb[3 * p + 2] = (bytes[4 * p + 2] + 0.5) * f;
  }
  return rgb;
}

/** A float RGB lat-long image as a filterable half-float RGBA texture (wraps in u). */
function latLongTexture(width, height, rgb) {
  // Half floats end at 65504: a sun's radiance is clamped there (invisible after any tone map
  // unless the exposure is below about −12 stops).
  const half = new Uint16Array(width * height * 4);
  const h = (v) => THREE.DataUtils.toHalfFloat(Math.min(Math.max(v, 0), 65504));
  for (let p = 0, n = width * height; p < n; ++p) {
    half[4 * p] = h(rgb[3 * p]);
    half[4 * p + 1] = h(rgb[3 * p + 1]);
    half[4 * p + 2] = h(rgb[3 * p + 2]);
    half[4 * p + 3] = 0x3c00;
  }
  const t = new THREE.DataTexture(half, width, height, THREE.RGBAFormat, THREE.HalfFloatType);
  t.wrapS = THREE.RepeatWrapping;
  t.wrapT = THREE.ClampToEdgeWrapping;
  t.minFilter = t.magFilter = THREE.LinearFilter;
  t.generateMipmaps = false;
  t.colorSpace = THREE.NoColorSpace;
  t.needsUpdate = true;
  return t;
}

/** Σ_i L_i Y_i(d) over a width × width/2 lat-long (envmap::renderSh), clamped at zero. */
function shImage(bands, coeffs, width = 128) {
  const h = width / 2, rgb = new Float32Array(width * h * 3), y = new Float64Array(bands * bands);
  for (let j = 0; j < h; ++j)
    for (let i = 0; i < width; ++i) {
      const theta = ((j + 0.5) / h) * Math.PI, phi = ((i + 0.5) / width - 0.5) * 2 * Math.PI;
      evalSh(bands, Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi), y);
      for (let c = 0; c < 3; ++c) {
        let s = 0;
        for (let k = 0; k < bands * bands; ++k) s += y[k] * coeffs[3 * k + c];
        rgb[(j * width + i) * 3 + c] = s;
      }
    }
  return latLongTexture(width, h, rgb);
}

function fatal(text) {
  showMessage(text, true);
  if (query.has('screenshot') || query.has('bench') || query.has('test')) report({ ok: false, error: text });
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
    maxBands: Math.min(32, Math.floor(Math.sqrt(gl.getParameter(gl.MAX_VERTEX_UNIFORM_VECTORS) - 16))),
  };
  const debugInfo = gl.getExtension('WEBGL_debug_renderer_info');
  const rendererName = debugInfo ? gl.getParameter(debugInfo.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);

  // ---- state ------------------------------------------------------------------------------
  const view = data.view || {};
  const num = (key, fallback) => (query.has(key) ? Number(query.get(key)) : fallback);
  const state = {
    env: num('env', 0),
    mode: query.get('mode') || view.mode || '',
    bands: num('bands', view.bands || 0),
    exposure: num('exposure', view.exposure || 0),
    tonemap: query.get('tonemap') || view.tonemap || 'aces',
    background: query.get('background') || 'env',
    spin: 0,
  };
  const euler = (query.get('rotate') || (view.rotate || [0, 0, 0]).join(',')).split(',').map(Number);
  const initialRotation = rotationEulerXYZ(euler[0] || 0, euler[1] || 0, euler[2] || 0);
  let lightRotation = initialRotation;

  const envs = data.environments.map((e) => ({
    name: e.name, bands: e.bands, coeffs: Float32Array.from(e.coefficients.flat()),
    background: e.background, texture: null, shCache: null,
  }));
  if (!(state.env >= 0 && state.env < envs.length)) state.env = 0;

  // ---- scene: background triangle + relit parts ---------------------------------------------
  // (three vertices: the stage makes the triangle from gl_VertexID; three.js counts these)
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 100);
  const fullscreen = new THREE.BufferGeometry();
  fullscreen.setAttribute('position', new THREE.Float32BufferAttribute([-1, -1, 0, 3, -1, 0, -1, 3, 0], 3));
  const bgUniforms = {
    uViewport: { value: new THREE.Vector2() }, uForward: { value: new THREE.Vector3() },
    uRightTan: { value: new THREE.Vector3() }, uUpTan: { value: new THREE.Vector3() },
    uRotationT: { value: new THREE.Matrix3() }, uLatLong: { value: null },
  };
  const background = new THREE.Mesh(fullscreen, new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3, vertexShader: fullscreenVert, fragmentShader: backgroundFrag,
    uniforms: bgUniforms, depthTest: false, depthWrite: false,
  }));
  background.frustumCulled = false;
  background.renderOrder = -1;
  scene.add(background);

  const toneUniforms = { uHdr: { value: null }, uScale: { value: 1 }, uToneMap: { value: 2 } };
  const toneScene = new THREE.Scene();
  const toneQuad = new THREE.Mesh(fullscreen, new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3, vertexShader: fullscreenVert, fragmentShader: toneFrag,
    uniforms: toneUniforms, depthTest: false, depthWrite: false,
  }));
  toneQuad.frustumCulled = false;
  toneScene.add(toneQuad);

  let bake = null;        // the parsed bake on screen
  let parts = [];         // THREE.Mesh per part
  let lightUniform = null;
  let clusterTables = {};  // mode → { image, texture, width }: compressed transfers' per-frame tables

  /** Builds the GPU side of a parsed bake; returns { meshes, light } without touching the scene. */
  function buildBake(b) {
    const vec4s = Math.ceil((b.maxBands * b.maxBands) / 4) * 4;
    const light = { value: new Float32Array(vec4s * 4) };
    const dataTexture = (x) => {
      const tex = new THREE.DataTexture(x.data, x.width, x.height, THREE.RGBAFormat, THREE.FloatType);
      tex.minFilter = tex.magFilter = THREE.NearestFilter;
      tex.generateMipmaps = false;
      tex.needsUpdate = true;
      return tex;
    };
    // Compressed transfers: one cluster table per transfer, shared by the parts, refilled per frame.
    const tables = {};
    for (const t of b.transfers)
      if (t.compressed) {
        const img = clusterTableImage(t.compressed, limits, b.name, t.mode);
        tables[t.mode] = { image: img, texture: dataTexture(img), width: img.width };
      }
    const meshes = b.parts.map((p) => {
      const textures = {};
      for (const t of b.transfers) textures[t.mode] = { texture: dataTexture(p.texels[t.mode]), width: p.texels[t.mode].width };
      // The arrays' sizes (shaders/hosts/webgl2.glsl): the light's vec4s, the glossy kernels'.
      const defines = { PRT_LIGHT_VEC4S: vec4s, PRT_GLOSSY_COEFFS: kMaxGlossyBands * kMaxGlossyBands };
      if (p.hasAlbedo) defines.PRT_HAS_ALBEDO = 1;
      const material = new THREE.RawShaderMaterial({
        glslVersion: THREE.GLSL3, vertexShader: meshVert, fragmentShader: meshFrag,
        defines,
        uniforms: {
          uTransfer: { value: null }, uTexelsPerVertex: { value: 1 },
          uCount: { value: 0 }, uRgb: { value: false }, uL: light,
        },
        side: THREE.DoubleSide,
      });
      const compressedMaterial = !b.transfers.some((t) => t.compressed) ? null : new THREE.RawShaderMaterial({
        glslVersion: THREE.GLSL3, vertexShader: compressedVert, fragmentShader: meshFrag, defines,
        uniforms: {
          uWeights: { value: null }, uClusters: { value: null },
          uTexelsPerVertex: { value: 1 }, uBasisCount: { value: 0 },
        },
        side: THREE.DoubleSide,
      });
      const glossyMaterial = !b.transfers.some((t) => t.matrix) ? null : new THREE.RawShaderMaterial({
        glslVersion: THREE.GLSL3, vertexShader: compressedGlossyVert, fragmentShader: meshFrag, defines,
        uniforms: {
          uWeights: { value: null }, uClusters: { value: null },
          uTexelsPerVertex: { value: 1 }, uBasisCount: { value: 0 },
          uBands: { value: 1 }, uCoeffs: { value: 1 }, uDiffuse: { value: new Float32Array(kMaxGlossyBands * kMaxGlossyBands) },
          uGlossy: { value: new Float32Array(kMaxGlossyBands * kMaxGlossyBands) }, uKd: { value: new THREE.Vector3() },
          uKs: { value: new THREE.Vector3() }, uEye: { value: new THREE.Vector3() }, uHasKd: { value: false },
        },
        side: THREE.DoubleSide,
      });
      const mesh = new THREE.Mesh(p.geometry, material);
      mesh.frustumCulled = false;
      mesh.userData = { textures, dense: material, compressed: compressedMaterial, glossy: glossyMaterial };
      return mesh;
    });
    return { meshes, light, tables };
  }

  function disposeBake() {
    for (const m of parts) {
      scene.remove(m);
      m.geometry.dispose();
      m.userData.dense.dispose();
      if (m.userData.compressed) m.userData.compressed.dispose();
      if (m.userData.glossy) m.userData.glossy.dispose();
      for (const t of Object.values(m.userData.textures)) t.texture.dispose();
    }
    for (const t of Object.values(clusterTables)) t.texture.dispose();
  }

  /** The camera prt web was given (--camera), else the library's framing (render::meshFraming,
   *  written by prt web) for a width × height canvas, as render::frameCamera: the bounding
   *  sphere grown by `margin` fits the narrower field of view (docs/conventions.md, "Camera").
   *  A dropped bake is framed with its own sphere (bake.js, as meshFraming computes it). */
  function frameCamera(w, h) {
    const given = data.view && data.view.camera;
    const written = data.bake.name === bake.name;
    if (given && written) {
      camera.fov = given.fov;
      camera.up.fromArray(given.up);
      camera.position.fromArray(given.eye);
      camera.lookAt(new THREE.Vector3().fromArray(given.target));
      if (controls) controls.target.fromArray(given.target), controls.update();
      return;
    }
    const f = data.view.framing;
    const centre = written ? new THREE.Vector3().fromArray(f.centre) : bake.centre;
    const radius = Math.max(written ? f.radius : bake.radius, 1e-6);
    const halfY = (f.fov / 2) * Math.PI / 180, halfX = Math.atan(Math.tan(halfY) * w / h);
    const d = (f.margin * radius) / Math.sin(Math.min(halfX, halfY));
    camera.fov = f.fov;
    camera.up.fromArray(f.up);
    camera.position.copy(centre).addScaledVector(new THREE.Vector3().fromArray(f.direction).normalize(), d);
    camera.lookAt(centre);
    if (controls) controls.target.copy(centre), controls.update();
  }

  /** Puts a parsed bake on screen; throws (leaving the old one) if the lights cannot serve it. */
  function setBake(b) {
    const short = envs.filter((e) => e.bands < b.maxBands);
    if (short.length)
      throw new Error(`${b.name}: the bake has ${b.maxBands} bands but the light ${short[0].name} only ${short[0].bands}; the transfer's upper bands would see no light (write the page for this bake with prt web)`);
    // Compressed glossy matrices shade with the bake's material, which prt web prepared (its
    // kernels) into prt-data.js: only for the page's own bake.
    for (const t of b.transfers)
      if (t.matrix) {
        const g = b.name === data.bake.name && data.glossy && data.glossy[t.mode];
        if (!g) throw new Error(`${b.name}: the ${t.mode} transfer is compressed glossy, whose material comes with the page (write the page for this bake with prt web)`);
        t.material = g;
      }
    const built = buildBake(b);
    disposeBake();
    bake = b;
    parts = built.meshes;
    lightUniform = built.light;
    clusterTables = built.tables;
    for (const m of parts) scene.add(m);
    if (!bake.transfers.some((t) => t.mode === state.mode)) state.mode = bake.transfers[0].mode;
    const maxB = transfer().bands;
    if (!(state.bands >= 1 && state.bands <= maxB)) state.bands = maxB;
  }

  const transfer = () => bake.transfers.find((t) => t.mode === state.mode);

  // ---- frame ------------------------------------------------------------------------------
  let hdrTarget = null, ldrTarget = null;
  function targets(w, h) {
    if (!hdrTarget || hdrTarget.width !== w || hdrTarget.height !== h) {
      if (hdrTarget) hdrTarget.dispose();
      // 4× multisampled float colour, resolved before the tone pass (prt render's 4 spp box).
      hdrTarget = new THREE.WebGLRenderTarget(w, h, { type: THREE.HalfFloatType, samples: 4,
        depthBuffer: true, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter });
    }
    return hdrTarget;
  }

  function envTexture(e) {
    if (state.background === 'sh') {
      const key = `${state.bands}`;
      if (!e.shCache || e.shCache.key !== key) {
        if (e.shCache) e.shCache.texture.dispose();
        e.shCache = { key, texture: shImage(state.bands, e.coeffs) };
      }
      return e.shCache.texture;
    }
    if (!e.texture) {
      if (e.background && e.background.rgbe) {
        e.texture = latLongTexture(e.background.width, e.background.height, decodeRgbe(base64Bytes(e.background.rgbe)));
      } else {
        e.texture = shImage(e.bands, e.coeffs);  // a dropped SH light: its reconstruction
      }
    }
    return e.texture;
  }

  /** Draws one frame into `target` (null: the canvas) at w × h pixels. */
  function drawFrame(w, h, target) {
    const t = transfer(), b = Math.min(state.bands, t.bands);
    const env = envs[state.env];
    // Light: L' = D(R) L for the first b bands, packed (r, g, b, 0), zero past b².
    const R = state.spin ? mul3(axisAngle([0, 1, 0], state.spin), lightRotation) : lightRotation;
    const rotated = rotateLight(b, R, env.coeffs);
    const L = lightUniform.value;
    L.fill(0);
    for (let i = 0; i < b * b; ++i) L[4 * i] = rotated[3 * i], L[4 * i + 1] = rotated[3 * i + 1], L[4 * i + 2] = rotated[3 * i + 2];
    if (t.compressed) {
      // The once-per-frame step: K(N+1) projections of L' (b bands), then N sums per vertex.
      const table = clusterTables[t.mode];
      projectClusters(t.compressed, b, t.channels, rotated, table.image.data);
      table.texture.needsUpdate = true;
    }
    for (const m of parts) {
      m.material = t.matrix ? m.userData.glossy : t.compressed ? m.userData.compressed : m.userData.dense;
      const tex = m.userData.textures[t.mode], u = m.material.uniforms;
      if (t.matrix) {
        // The shaded bands (≤ 8), the material's kernels, kd (else the albedo), ks, the eye.
        u.uBands.value = Math.min(b, 8);
        u.uCoeffs.value = t.compressed.coeffs;
        u.uDiffuse.value.set(t.material.diffuse);
        u.uGlossy.value.set(t.material.lobe);
        u.uHasKd.value = !!t.material.kd;
        if (t.material.kd) u.uKd.value.fromArray(t.material.kd);
        u.uKs.value.fromArray(t.material.ks);
      }
      if (t.compressed) {
        const table = clusterTables[t.mode];
        u.uWeights.value = tex.texture;
        u.uClusters.value = table.texture;
        u.uTexelsPerVertex.value = t.compressed.texelsPerVertex;
        u.uBasisCount.value = t.compressed.basisCount;
        continue;
      }
      u.uTransfer.value = tex.texture;
      u.uTexelsPerVertex.value = t.texelsPerVertex;
      u.uRgb.value = t.channels === 3;
      u.uCount.value = t.channels === 3 ? b * b : Math.ceil((b * b) / 4);
    }
    // Camera: the projection as RayGenerator, near/far around the bounding sphere.
    camera.aspect = w / h;
    camera.updateMatrixWorld();
    const forward = camera.getWorldDirection(new THREE.Vector3());
    const d = new THREE.Vector3().subVectors(bake.centre, camera.position).dot(forward);
    camera.far = Math.max(d + 1.01 * bake.radius, 1e-3 * bake.radius);
    camera.near = Math.max(d - 1.01 * bake.radius, 1e-4 * camera.far);
    camera.updateProjectionMatrix();
    camera.updateMatrixWorld();
    // Glossy: each vertex seen from the camera's eye (the parts are in world space).
    for (const m of parts) if (m.userData.glossy) m.userData.glossy.uniforms.uEye.value.copy(camera.position);
    const right = new THREE.Vector3().crossVectors(forward, camera.up).normalize();
    const up = new THREE.Vector3().crossVectors(right, forward);
    const tanY = Math.tan((camera.fov / 2) * Math.PI / 180), tanX = tanY * w / h;
    bgUniforms.uViewport.value.set(w, h);
    bgUniforms.uForward.value.copy(forward);
    bgUniforms.uRightTan.value.copy(right).multiplyScalar(tanX);
    bgUniforms.uUpTan.value.copy(up).multiplyScalar(tanY);
    // Matrix3.set takes rows; the rows of Rᵀ are R's columns.
    bgUniforms.uRotationT.value.set(R[0][0], R[1][0], R[2][0], R[0][1], R[1][1], R[2][1], R[0][2], R[1][2], R[2][2]);
    background.visible = state.background !== 'none';
    if (background.visible) bgUniforms.uLatLong.value = envTexture(env);

    const hdr = targets(w, h);
    renderer.setRenderTarget(hdr);
    renderer.clear();
    renderer.render(scene, camera);
    toneUniforms.uHdr.value = hdr.texture;
    toneUniforms.uScale.value = Math.pow(2, state.exposure);
    toneUniforms.uToneMap.value = kToneMaps[state.tonemap] ?? 2;
    renderer.setRenderTarget(target);
    renderer.render(toneScene, camera);
    renderer.setRenderTarget(null);
  }

  /** The frame as displayed, top row first, RGB bytes. */
  function readFrame(w, h) {
    if (!ldrTarget || ldrTarget.width !== w || ldrTarget.height !== h) {
      if (ldrTarget) ldrTarget.dispose();
      ldrTarget = new THREE.WebGLRenderTarget(w, h, { type: THREE.UnsignedByteType, depthBuffer: false });
    }
    drawFrame(w, h, ldrTarget);
    const rgba = new Uint8Array(w * h * 4);
    renderer.readRenderTargetPixels(ldrTarget, 0, 0, w, h, rgba);
    const rgb = new Uint8Array(w * h * 3);
    for (let y = 0; y < h; ++y)
      for (let x = 0; x < w; ++x)
        for (let c = 0; c < 3; ++c) rgb[(y * w + x) * 3 + c] = rgba[((h - 1 - y) * w + x) * 4 + c];
    return rgb;
  }

  // ---- the bake from prt-data.js ----------------------------------------------------------
  let controls = null;
  try {
    const glb = base64Bytes(data.bake.glb);
    setBake(await parseBake(glb.buffer, data.bake.name, limits));
  } catch (e) {
    return fatal(e.message);
  }
  if (!bake.transfers.some((t) => t.mode === state.mode)) state.mode = bake.transfers[0].mode;

  // ---- test hooks -------------------------------------------------------------------------
  if (query.has('screenshot')) {
    renderer.setSize(fixedW, fixedH);
    frameCamera(fixedW, fixedH);
    const rgb = readFrame(fixedW, fixedH);
    const c = transfer().compressed;
    return report({ ok: true, width: fixedW, height: fixedH, renderer: rendererName, mode: state.mode,
                    compressed: c ? `${c.clusters}x${c.basisCount}, ${16 * c.texelsPerVertex} bytes per vertex` : 'no',
                    rgb: bytesBase64(rgb) });
  }
  if (query.has('bench')) {
    const n = Math.max(1, Number(query.get('bench')) || 20);
    // &nomesh: the same frame without the mesh (background, resolve, tone map), the baseline.
    if (query.has('nomesh')) for (const m of parts) m.visible = false;
    renderer.setSize(fixedW, fixedH);
    frameCamera(fixedW, fixedH);
    const one = new Uint8Array(4), times = [];
    const canvasFrame = () => {
      drawFrame(fixedW, fixedH, null);
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, one);  // waits for the GPU
    };
    canvasFrame();  // compiles shaders, uploads textures
    for (let i = 0; i < n; ++i) {
      const t0 = performance.now();
      canvasFrame();
      times.push(performance.now() - t0);
    }
    times.sort((a, b) => a - b);
    return report({ ok: true, frames: n, medianMs: times[n >> 1], minMs: times[0], bands: state.bands,
                    mode: state.mode, compressed: !!transfer().compressed, vertices: bake.vertices, triangles: bake.triangles,
                    width: fixedW, height: fixedH, renderer: rendererName });
  }

  // ---- interactive page -------------------------------------------------------------------
  controls = new OrbitControls(camera, renderer.domElement);
  controls.mouseButtons = { LEFT: THREE.MOUSE.ROTATE, MIDDLE: THREE.MOUSE.DOLLY, RIGHT: null };
  controls.enableDamping = false;
  const resize = () => {
    const w = fixedSize ? fixedW : window.innerWidth, h = fixedSize ? fixedH : window.innerHeight;
    renderer.setSize(w, h);
  };
  resize();
  window.addEventListener('resize', resize);
  frameCamera(renderer.domElement.width, renderer.domElement.height);

  // Light drag: right button, or shift + left; horizontal about world +Y, vertical about the
  // camera's right axis, 0.25° per pixel (as prt view).
  let drag = null;
  renderer.domElement.addEventListener('pointerdown', (e) => {
    if (e.button === 2 || (e.button === 0 && e.shiftKey)) {
      drag = { x: e.clientX, y: e.clientY, id: e.pointerId };
      renderer.domElement.setPointerCapture(e.pointerId);
      e.stopImmediatePropagation();
      e.preventDefault();
    }
  }, { capture: true });
  renderer.domElement.addEventListener('pointermove', (e) => {
    if (!drag || e.pointerId !== drag.id) return;
    const k = 0.25 * Math.PI / 180;
    const forward = new THREE.Vector3().subVectors(controls.target, camera.position).normalize();
    const right = new THREE.Vector3().crossVectors(forward, camera.up).normalize();
    const turn = mul3(axisAngle([0, 1, 0], (e.clientX - drag.x) * k), axisAngle(right.toArray(), (e.clientY - drag.y) * k));
    lightRotation = mul3(turn, lightRotation);
    drag.x = e.clientX, drag.y = e.clientY;
    e.stopImmediatePropagation();
  }, { capture: true });
  const endDrag = (e) => { if (drag && e.pointerId === drag.id) drag = null; };
  renderer.domElement.addEventListener('pointerup', endDrag, { capture: true });
  renderer.domElement.addEventListener('pointercancel', endDrag, { capture: true });
  renderer.domElement.addEventListener('contextmenu', (e) => e.preventDefault());

  // Panel.
  const gui = new GUI({ title: 'prtkit', container: document.getElementById('prt-panel') });
  const envNames = () => Object.fromEntries(envs.map((e, i) => [e.name, i]));
  const envCtl = gui.add(state, 'env', envNames()).name('environment');
  let modeCtl = null, bandsCtl = null;
  function rebuildBakeControls() {
    if (modeCtl) modeCtl.destroy();
    if (bandsCtl) bandsCtl.destroy();
    modeCtl = gui.add(state, 'mode', bake.transfers.map((t) => t.mode)).name('transfer').onChange(() => {
      state.bands = Math.min(state.bands, transfer().bands);
      bandsCtl.max(transfer().bands).updateDisplay();
    });
    bandsCtl = gui.add(state, 'bands', 1, transfer().bands, 1).name('bands');
  }
  rebuildBakeControls();
  gui.add(state, 'background', ['env', 'sh', 'none']).name('background');
  gui.add(state, 'exposure', -8, 8, 0.1).name('exposure (stops)');
  gui.add(state, 'tonemap', Object.keys(kToneMaps)).name('tone map');
  const actions = {
    'auto-rotate': false, 'speed (°/s)': 30,
    'reset light': () => { lightRotation = initialRotation; state.spin = 0; },
    'reset camera': () => frameCamera(renderer.domElement.width, renderer.domElement.height),
  };
  gui.add(actions, 'auto-rotate');
  gui.add(actions, 'speed (°/s)', 0, 180, 1);
  gui.add(actions, 'reset light');
  gui.add(actions, 'reset camera');

  // Keys, as prt view: [ ] one band fewer / more, B background, Tab next environment, space
  // auto-rotate.
  const backgrounds = ['env', 'sh', 'none'];
  window.addEventListener('keydown', (e) => {
    if (e.target && /INPUT|SELECT|TEXTAREA/.test(e.target.tagName)) return;
    if (e.key === '[') state.bands = Math.max(1, state.bands - 1);
    else if (e.key === ']') state.bands = Math.min(transfer().bands, state.bands + 1);
    else if (e.key === 'b' || e.key === 'B') state.background = backgrounds[(backgrounds.indexOf(state.background) + 1) % 3];
    else if (e.key === 'Tab') state.env = (state.env + 1) % envs.length;
    else if (e.key === ' ') actions['auto-rotate'] = !actions['auto-rotate'];
    else return;
    e.preventDefault();
    gui.controllersRecursive().forEach((c) => c.updateDisplay());
  });

  // Drag and drop: a .glb replaces the bake, an SH light .json is added and shown. A bad file
  // leaves everything as it was and says why.
  async function loadFile(file) {
    const name = file.name, ext = name.toLowerCase().split('.').pop();
    if (ext === 'glb') {
      const b = await parseBake(await file.arrayBuffer(), name, limits);
      setBake(b);
      rebuildBakeControls();
      frameCamera(renderer.domElement.width, renderer.domElement.height);
    } else if (ext === 'json' || ext === 'txt') {
      const text = await file.text();
      const l = ext === 'json' ? parseLightJson(text, name) : parseLightTxt(text, name);
      if (l.bands < bake.maxBands)
        throw new Error(`${name}: the light has ${l.bands} bands but the bake ${bake.maxBands}; the transfer's upper bands would see no light (write it with prt light --bands ${bake.maxBands})`);
      envs.push({ name, bands: l.bands, coeffs: l.coeffs, background: null, texture: null, shCache: null });
      state.env = envs.length - 1;
      envCtl.options(envNames()).setValue(state.env);
    } else {
      throw new Error(`${name}: not a bake (.glb) or an SH light (.json, or the course's light.txt)`);
    }
  }
  async function onDrop(e) {
    e.preventDefault();
    document.getElementById('prt-drop').style.display = 'none';
    const files = e.dataTransfer ? [...e.dataTransfer.files] : [];
    for (const f of files) {
      try {
        await loadFile(f);
        showMessage('');
      } catch (err) {
        showMessage(err.message);
      }
    }
  }
  window.addEventListener('dragover', (e) => { e.preventDefault(); document.getElementById('prt-drop').style.display = 'block'; });
  window.addEventListener('dragleave', () => { document.getElementById('prt-drop').style.display = 'none'; });
  window.addEventListener('drop', (e) => { onDrop(e); });

  // Loop, with the frame time on screen (interval between frames, smoothed).
  let last = performance.now(), smooth = 0;
  function loop(now) {
    const dt = now - last;
    last = now;
    smooth = smooth ? 0.9 * smooth + 0.1 * dt : dt;
    if (actions['auto-rotate']) state.spin += (actions['speed (°/s)'] * Math.PI / 180) * (dt / 1000);
    controls.update();
    drawFrame(renderer.domElement.width, renderer.domElement.height, null);
    const t = transfer();
    hud.textContent = `${bake.name}  ${bake.triangles} triangles, ${bake.vertices} vertices\n` +
      `${t.mode}, ${Math.min(state.bands, t.bands)} of ${t.bands} bands, ${t.channels === 3 ? 'RGB' : 'scalar'}\n` +
      (t.matrix ? `glossy ${t.material.material}, toward the eye\n` : '') +
      (t.compressed ? `relit compressed: CPCA ${t.compressed.clusters} x ${t.compressed.basisCount}, ` +
        `${16 * t.compressed.texelsPerVertex} bytes/vertex (dense ${t.matrix ? 16 * t.bands * t.bands * Math.ceil(t.bands * t.bands / 4) : 16 * t.texelsPerVertex}), ` +
        `${16 * t.compressed.clusters * (t.compressed.basisCount + 1) * t.compressed.coeffs} bytes of cluster table per frame\n` : '') +
      `frame ${smooth.toFixed(1)} ms (${(1000 / smooth).toFixed(0)} fps)\n${rendererName}`;
    if (!query.has('test')) requestAnimationFrame(loop);
  }
  requestAnimationFrame(loop);

  if (query.get('test') === 'drop')
    await dropTest(readFrame, () => ({ bake, envCount: envs.length }), onDrop);
}

/**
 * ?test=drop: drops bad files through the real drop handler and checks that the scene (the bake,
 * the environments, the frame's pixels) is unchanged and that the page says why; then a good
 * light file as a control (it must be added).
 *
 * The files are handed to the handler in memory, with the two methods of a File it uses
 * (arrayBuffer, text) already resolved: real File objects are read as Blobs, which Chromium's
 * virtual time (--virtual-time-budget, the tests' clock) does not wait for, so on a busy machine
 * the page could be dumped before a drop finished (the test then saw no report at all).
 */
async function dropTest(readFrame, snapshot, handleDrop) {
  const drop = async (name, bytes) => {
    const file = {
      name,
      arrayBuffer: async () => bytes.slice().buffer,
      text: async () => new TextDecoder().decode(bytes),
    };
    await handleDrop({ preventDefault() {}, dataTransfer: { files: [file] } });
    return messageBox.textContent;
  };
  const w = 64, h = 48;
  const frame0 = bytesBase64(readFrame(w, h)), s0 = snapshot();
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
    ['newer.glb', glbWith({ asset: { version: '2.0' }, extras: { prtkit: { formatVersion: 99 } } })],
    ['broken.json', enc.encode('{"bands": 3, "coefficients": [')],
    ['rows.json', enc.encode(JSON.stringify({ bands: 2, coefficients: [[1, 1, 1], [0, 0, 0], [0, 0, 0]] }))],
    ['short.json', enc.encode(JSON.stringify({ bands: 2, coefficients: [[1, 1, 1], [0, 0, 0], [0, 0, 0], [0, 0, 0]] }))],
    ['picture.png', enc.encode('PNG')],
    ['odd.txt', enc.encode('1 1 1\n0 0 0\n')],
  ];
  const results = [];
  for (const [name, bytes] of cases) {
    const message = await drop(name, bytes);
    const s = snapshot();
    results.push({ name, message, sameBake: s.bake === s0.bake, sameEnvs: s.envCount === s0.envCount,
                   sameFrame: bytesBase64(readFrame(w, h)) === frame0 });
  }
  // Control: a good light with the bake's bands is added (so the handler does run).
  const B = s0.bake.maxBands, good = { bands: B, coefficients: Array.from({ length: B * B }, (_, i) => (i ? [0, 0, 0] : [1, 1, 1])) };
  const message = await drop('good.json', enc.encode(JSON.stringify(good)));
  // ... and so is the course's light.txt.
  const txt = Array.from({ length: B * B }, (_, i) => (i ? '0 0 0' : '0.5 0.5 0.5')).join('\n');
  const txtMessage = await drop('light.txt', enc.encode(txt));
  const added = snapshot().envCount === s0.envCount + 2 && txtMessage === '';
  // Control: a good bake (the page's own, again) replaces the scene.
  const glbMessage = await drop('again.glb', base64Bytes(window.PRT_DATA.bake.glb));
  const replaced = snapshot().bake !== s0.bake && snapshot().bake.vertices === s0.bake.vertices;
  report({ ok: true, cases: results, control: { message, added }, controlBake: { message: glbMessage, replaced } });
}

main().catch((e) => fatal(`prt web: ${e && e.message ? e.message : e}`));
