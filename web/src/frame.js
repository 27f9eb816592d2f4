// One frame of the page, as the desktop viewer draws it (docs/viewer.md, "How a frame is
// made"): the light's first b bands rotated on the CPU (sh.js) and packed as vec4 uL[i] =
// (r, g, b, 0), zero past b², and the transfer's per-frame step (draw.js) — or, for a probe
// bake, the grid relit and the meshes shaded through it (probe_scene.js); then, into a 4×
// multisampled half-float target, the background (a full-screen triangle) and the relit parts
// (a matrix transfer drawn through an irradiance encoding, a Haar bake (haar_scene.js): from
// radiance made on the CPU);
// a second full-screen pass applies 2^exposure, the tone map and the sRGB encode.
import * as THREE from 'three';

import { defaultToneMap, toneMaps } from 'prt:constants';
import { axisAngle, mul3 } from './sh.js';
import { fitProjection } from './camera.js';
import { backgroundTexture } from './environment.js';
import { setEncodedRadiance, setFrameLight, setTransferUniforms, transferMaterialOf } from './draw.js';
import fullscreenVert from 'prt:shaders/fullscreen.vert';
import backgroundFrag from 'prt:shaders/background.frag';
import toneFrag from 'prt:shaders/tone.frag';

/** The frame's GL objects on `renderer`; draw(view, w, h, target) and read(view, w, h). */
export function createFrame(renderer) {
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 100);
  // Three vertices (the stage makes the triangle from gl_VertexID; three.js counts these).
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

  const toneUniforms = { uHdr: { value: null }, uScale: { value: 1 }, uToneMap: { value: toneMaps[defaultToneMap] } };
  const toneScene = new THREE.Scene();
  const toneQuad = new THREE.Mesh(fullscreen, new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3, vertexShader: fullscreenVert, fragmentShader: toneFrag,
    uniforms: toneUniforms, depthTest: false, depthWrite: false,
  }));
  toneQuad.frustumCulled = false;
  toneScene.add(toneQuad);

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

  /**
   * Draws one frame into `target` (null: the canvas) at w × h pixels. v = { gpu: the bake on
   * the GPU (main.js), transfer, env, state, lightRotation }.
   */
  function draw(v, w, h, target) {
    const { gpu, transfer: t, env, state } = v;
    const b = Math.min(state.bands, t.bands);
    const R = state.spin ? mul3(axisAngle([0, 1, 0], state.spin), v.lightRotation) : v.lightRotation;
    const forward = fitProjection(camera, w, h, gpu.bake.centre, gpu.bake.radius);
    if (gpu.probes) {
      // A probe bake: the grid relit on the CPU, the scene and the ball shaded through it.
      gpu.probes.frame({ transfer: t, bands: b, rotation: R, light: env.coeffs, at: state.at, showProbes: state.probes });
    } else if (gpu.haar) {
      // A Haar bake: the light turned from the environment's cube, the vertices relit on the CPU.
      gpu.haar.frame({ transfer: t, env, rotation: R, terms: state.terms });
    } else {
      // A matrix transfer drawn through an irradiance encoding: its radiance per vertex, made
      // on the CPU when the light, its rotation, the bands or the encoding changed.
      setFrameLight(gpu, t, b, R, env.coeffs);
      setEncodedRadiance(gpu, t, b, state.encoding);
      gpu.meshes.forEach((m, p) => {
        m.material = transferMaterialOf(gpu, p, t, state.encoding);
        setTransferUniforms(gpu, p, t, { bands: b, eye: camera.position, encoding: state.encoding });
      });
    }
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
    if (background.visible) bgUniforms.uLatLong.value = backgroundTexture(env, state.background, gpu.haar ? 1 : state.bands);

    const hdr = targets(w, h);
    renderer.setRenderTarget(hdr);
    renderer.clear();
    renderer.render(scene, camera);
    toneUniforms.uHdr.value = hdr.texture;
    toneUniforms.uScale.value = Math.pow(2, state.exposure);
    toneUniforms.uToneMap.value = toneMaps[state.tonemap] ?? toneMaps[defaultToneMap];
    renderer.setRenderTarget(target);
    renderer.render(toneScene, camera);
    renderer.setRenderTarget(null);
  }

  /** The frame as displayed, top row first, RGB bytes. */
  function read(v, w, h) {
    if (!ldrTarget || ldrTarget.width !== w || ldrTarget.height !== h) {
      if (ldrTarget) ldrTarget.dispose();
      ldrTarget = new THREE.WebGLRenderTarget(w, h, { type: THREE.UnsignedByteType, depthBuffer: false });
    }
    draw(v, w, h, ldrTarget);
    const rgba = new Uint8Array(w * h * 4);
    renderer.readRenderTargetPixels(ldrTarget, 0, 0, w, h, rgba);
    const rgb = new Uint8Array(w * h * 3);
    for (let y = 0; y < h; ++y)
      for (let x = 0; x < w; ++x)
        for (let c = 0; c < 3; ++c) rgb[(y * w + x) * 3 + c] = rgba[((h - 1 - y) * w + x) * 4 + c];
    return rgb;
  }

  return { scene, camera, draw, read };
}
